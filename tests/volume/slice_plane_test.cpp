// VolumeGeometry::patientToIndex, the slice planes (slice_plane.h) and their iso contour
// (slice_contour.h) on synthetic volumes: regular, tilted, unevenly spaced and refined grids.
#include "filled_volume.h"
#include "lw/volume/slice_contour.h"
#include "lw/volume/slice_plane.h"
#include "lw/volume/volume_geometry.h"

#include <cmath>
#include <functional>
#include <gtest/gtest.h>
#include <limits>
#include <map>
#include <random>
#include <string>

namespace lw::volume {
namespace {

constexpr double kPi = 3.14159265358979323846;

void expectNear(glm::dvec3 a, glm::dvec3 b, double tol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// Image rows tilted by 18.5 degrees, slices advancing along the table (z): the GE HiSpeed case;
// `gaps` the distances between consecutive slices (uneven when they differ).
VolumeGeometry tiltedGeometry(const std::vector<double>& gaps) {
    const double t = 18.5 * kPi / 180.0;
    std::vector<glm::dvec3> positions{{-20.0, -15.0, 10.0}};
    for (double gap : gaps)
        positions.push_back(positions.back() + glm::dvec3(0.0, 0.0, gap));
    return VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, std::cos(t), -std::sin(t)}, 0.7, 0.6,
                                              positions);
}

const std::vector<double> kUnevenGaps = {1.08, 3.0, 7.0, 2.0, 5.0, 1.5, 4.0};

struct NamedGeometry {
    const char* name;
    VolumeGeometry geometry;
    glm::ivec3 dims;
};

std::vector<NamedGeometry> testGeometries() {
    const VolumeGeometry uneven = tiltedGeometry(kUnevenGaps);
    const glm::dvec3 obliqueI = glm::normalize(glm::dvec3(1, 0.3, 0.1));
    const glm::dvec3 obliqueJ = glm::normalize(glm::cross(glm::dvec3(0.2, 0, 1), obliqueI));
    return {
        {"regular", VolumeGeometry::regular({-10, 5, 30}, {0.7, 0.8, 2.5}), {20, 30, 10}},
        {"oblique",
         VolumeGeometry::regular({3, -4, 8}, {0.9, 1.1, 1.7}, obliqueI, obliqueJ,
                                 glm::cross(obliqueI, obliqueJ)),
         {12, 14, 9}},
        {"tilted", tiltedGeometry(std::vector<double>(9, 2.5)), {24, 20, 10}},
        {"tilted uneven", uneven, {24, 20, 8}},
        {"refined uneven", uneven.refined({2, 3, 4}, 8), {47, 58, 29}},
    };
}

TEST(PatientToIndex, InvertsIndexToPatientOnEveryGeometry) {
    std::mt19937 random(7);
    for (const NamedGeometry& g : testGeometries()) {
        SCOPED_TRACE(g.name);
        // Within the grid and beyond its ends, where both extrapolate with the end gaps.
        const glm::dvec3 lo(-2.0), hi = glm::dvec3(g.dims) + 1.0;
        for (int n = 0; n < 500; ++n) {
            glm::dvec3 ijk;
            for (int a = 0; a < 3; ++a)
                ijk[a] = std::uniform_real_distribution<double>(lo[a], hi[a])(random);
            expectNear(g.geometry.patientToIndex(g.geometry.indexToPatient(ijk)), ijk, 1e-9);
        }
        for (int k = 0; k < g.dims.z; ++k)
            EXPECT_NEAR(g.geometry.sliceIndexAtOffset(g.geometry.sliceOffset(k)), k, 1e-12);
    }
}

TEST(SliceOrientation, NamesAxesAndLabels) {
    for (SliceOrientation o :
         {SliceOrientation::Axial, SliceOrientation::Coronal, SliceOrientation::Sagittal}) {
        EXPECT_EQ(parseSliceOrientation(sliceOrientationName(o)), o);
        const SliceAxes axes = sliceAxes(o);
        EXPECT_NEAR(std::abs(glm::dot(glm::cross(axes.right, axes.down), axes.normal)), 1.0, 1e-12);
    }
    EXPECT_FALSE(parseSliceOrientation("oblique"));
    // LPS: +x left, +y posterior, +z superior; the radiological views of the diagram.
    const auto letters = [](SliceEdgeLabels l) {
        return std::string{l.left, l.right, l.top, l.bottom};
    };
    EXPECT_EQ(letters(sliceEdgeLabels(SliceOrientation::Axial)), "RLAP");
    EXPECT_EQ(letters(sliceEdgeLabels(SliceOrientation::Coronal)), "RLSI");
    EXPECT_EQ(letters(sliceEdgeLabels(SliceOrientation::Sagittal)), "APSI");
    expectNear(sliceAxes(SliceOrientation::Axial).down, {0, 1, 0}, 0);     // towards P
    expectNear(sliceAxes(SliceOrientation::Coronal).down, {0, 0, -1}, 0);  // towards I
    expectNear(sliceAxes(SliceOrientation::Sagittal).right, {0, 1, 0}, 0); // towards P
    expectNear(sliceAxes(SliceOrientation::Sagittal).normal, {1, 0, 0}, 0);
}

struct ExpectedSlice {
    SliceOrientation orientation;
    glm::dvec2 originMm;
    glm::ivec2 size;
    double first, last, step;
};

TEST(SliceGeometry, ThreeOrientationsOfARegularGrid) {
    // x in [-10, 3.3], y in [5, 28.2], z in [30, 52.5]; the finest spacing 0.7 mm.
    const Volume volume({20, 30, 10}, VoxelType::Int16,
                        VolumeGeometry::regular({-10, 5, 30}, {0.7, 0.8, 2.5}));
    const ExpectedSlice expected[] = {
        {SliceOrientation::Axial, {-10, 5}, {20, 35}, 30, 52.5, 2.5},
        {SliceOrientation::Coronal, {-10, -52.5}, {20, 34}, 5, 28.2, 0.8},
        {SliceOrientation::Sagittal, {5, -52.5}, {35, 34}, -10, 3.3, 0.7},
    };
    for (const ExpectedSlice& e : expected) {
        SCOPED_TRACE(std::string(sliceOrientationName(e.orientation)));
        const SliceGeometry s = sliceGeometry(volume, e.orientation);
        EXPECT_EQ(s.orientation, e.orientation);
        EXPECT_DOUBLE_EQ(s.pixelMm, 0.7);
        EXPECT_NEAR(s.originMm.x, e.originMm.x, 1e-9);
        EXPECT_NEAR(s.originMm.y, e.originMm.y, 1e-9);
        EXPECT_EQ(s.size, e.size);
        EXPECT_NEAR(s.firstPosition, e.first, 1e-9);
        EXPECT_NEAR(s.lastPosition, e.last, 1e-9);
        EXPECT_NEAR(s.step, e.step, 1e-9);
        EXPECT_NEAR(s.middlePosition(), 0.5 * (e.first + e.last), 1e-9);
        const glm::dvec3 p(-3.1, 12.7, 41.9);
        const glm::dvec3 back = s.patientPoint(s.pixelOf(p), s.positionOf(p));
        expectNear(back, p, 1e-9);
    }
}

TEST(SliceGeometry, TiltedGridCoversItsBoxAndStepsAlongTheTable) {
    const VolumeGeometry g = tiltedGeometry(std::vector<double>(9, 2.5));
    const Volume volume({24, 20, 10}, VoxelType::Int16, g);
    const double t = 18.5 * kPi / 180.0;
    const std::map<SliceOrientation, double> steps = {
        {SliceOrientation::Axial, 2.5},                 // the stack advances along z
        {SliceOrientation::Coronal, 0.6 * std::cos(t)}, // columns tilted from y
        {SliceOrientation::Sagittal, 0.7}};             // rows along x
    for (const auto& [orientation, step] : steps) {
        SCOPED_TRACE(std::string(sliceOrientationName(orientation)));
        const SliceGeometry s = sliceGeometry(volume, orientation);
        EXPECT_NEAR(s.step, step, 1e-9);
        EXPECT_NEAR(s.pixelMm, std::min(0.6, 2.5 * std::cos(t)), 1e-9);
        // Every voxel centre's corner lies on the image, and the image is no larger than needed.
        glm::dvec2 lo(1e9), hi(-1e9);
        double first = 1e9, last = -1e9;
        for (int c = 0; c < 8; ++c) {
            const glm::dvec3 p =
                g.indexToPatient({(c & 1) ? 23 : 0, (c & 2) ? 19 : 0, (c & 4) ? 9 : 0});
            lo = glm::min(lo, s.pixelOf(p));
            hi = glm::max(hi, s.pixelOf(p));
            first = std::min(first, s.positionOf(p));
            last = std::max(last, s.positionOf(p));
        }
        EXPECT_NEAR(lo.x, 0.0, 1e-9);
        EXPECT_NEAR(lo.y, 0.0, 1e-9);
        EXPECT_LE(hi.x, s.size.x - 1 + 1e-9);
        EXPECT_LE(hi.y, s.size.y - 1 + 1e-9);
        EXPECT_GT(hi.x, s.size.x - 2);
        EXPECT_GT(hi.y, s.size.y - 2);
        EXPECT_NEAR(s.firstPosition, first, 1e-9);
        EXPECT_NEAR(s.lastPosition, last, 1e-9);
    }
}

TEST(SliceGeometry, ImagesStayAtMost2048PixelsASide) {
    // 0.1 mm pixels over 400 mm would be 4000 pixels.
    const Volume volume({4000, 8, 8}, VoxelType::UInt8,
                        VolumeGeometry::regular({0, 0, 0}, {0.1, 0.1, 0.1}));
    const SliceGeometry s = sliceGeometry(volume, SliceOrientation::Axial);
    EXPECT_LE(s.size.x, 2048);
    EXPECT_GE(s.size.x, 2040);
    EXPECT_GT(s.pixelMm, 0.1);
}

// value(p) = a . p + c: trilinear interpolation in index space reproduces it exactly, also on
// a tilted and uneven grid (p is affine in i and j and linear in k between slices).
constexpr glm::dvec3 kGradient{0.3, -0.2, 0.5};
constexpr double kConstant = 7.0;
double linearField(glm::dvec3 p) {
    return glm::dot(kGradient, p) + kConstant;
}

// A float volume whose real values (slope 2, intercept -100) are linearField at the voxels.
Volume linearVolume(const NamedGeometry& g) {
    Volume v = test::makeFilledVolume<float>(
        g.dims,
        [&](int x, int y, int z) {
            return (linearField(g.geometry.indexToPatient({x, y, z})) + 100.0) / 2.0;
        },
        g.geometry);
    v.setValueMapping({2.0, -100.0});
    return v;
}

bool insideVoxelCentres(glm::dvec3 ijk, glm::ivec3 dims, double margin) {
    for (int a = 0; a < 3; ++a)
        if (ijk[a] < margin || ijk[a] > dims[a] - 1 - margin)
            return false;
    return true;
}

TEST(SampleSlice, ReproducesALinearFieldExactlyAndIsNaNOutside) {
    for (const NamedGeometry& g : testGeometries()) {
        const Volume volume = linearVolume(g);
        for (SliceOrientation o :
             {SliceOrientation::Axial, SliceOrientation::Coronal, SliceOrientation::Sagittal}) {
            SCOPED_TRACE(std::string(g.name) + " " + std::string(sliceOrientationName(o)));
            const SliceGeometry s = sliceGeometry(volume, o);
            for (double t : {0.0, 0.31, 0.5, 0.77, 1.0}) {
                const double position = s.firstPosition + t * (s.lastPosition - s.firstPosition);
                const SliceImage image = sampleSlice(volume, s, position);
                ASSERT_EQ(image.values.size(), std::size_t(s.size.x) * std::size_t(s.size.y));
                int inside = 0;
                for (int y = 0; y < s.size.y; ++y)
                    for (int x = 0; x < s.size.x; ++x) {
                        const glm::dvec3 p = s.patientPoint({x, y}, position);
                        const glm::dvec3 ijk = g.geometry.patientToIndex(p);
                        if (insideVoxelCentres(ijk, g.dims, -1e-9)) {
                            ++inside;
                            ASSERT_NEAR(image.at(x, y), linearField(p), 2e-4) << x << "," << y;
                            ASSERT_NEAR(*sampleAt(volume, p), linearField(p), 2e-4);
                        } else if (!insideVoxelCentres(ijk, g.dims, -1e-3)) {
                            ASSERT_TRUE(std::isnan(image.at(x, y))) << x << "," << y;
                            ASSERT_FALSE(sampleAt(volume, p));
                        }
                    }
                // At the ends, a tilted box may touch the plane at a corner only.
                if (t > 0.0 && t < 1.0) {
                    EXPECT_GT(inside, 0);
                }
            }
            const SliceImage beyond = sampleSlice(volume, s, s.lastPosition + 0.1);
            for (float value : beyond.values)
                ASSERT_TRUE(std::isnan(value));
        }
    }
}

TEST(SampleSlice, SameImageOnOneThreadAndMany) {
    const NamedGeometry g = testGeometries()[3];
    const Volume volume = linearVolume(g);
    const SliceGeometry s = sliceGeometry(volume, SliceOrientation::Coronal);
    const SliceImage one = sampleSlice(volume, s, s.middlePosition(), 1);
    const SliceImage many = sampleSlice(volume, s, s.middlePosition(), 4);
    ASSERT_EQ(one.values.size(), many.values.size());
    for (std::size_t n = 0; n < one.values.size(); ++n) {
        if (!std::isnan(one.values[n])) {
            ASSERT_EQ(one.values[n], many.values[n]);
        }
    }
}

// An image of given size and pixel values, in a plane 1 mm a pixel.
SliceImage syntheticImage(glm::ivec2 size, const std::function<float(int, int)>& value) {
    SliceImage image;
    image.geometry.size = size;
    for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x)
            image.values.push_back(value(x, y));
    return image;
}

TEST(IsoContour, ClosedCircleOnAConeField) {
    const glm::dvec2 centre(31.3, 29.6);
    const double radius = 20.0;
    const SliceImage image = syntheticImage({64, 64}, [&](int x, int y) {
        return float(radius - glm::length(glm::dvec2(x, y) - centre));
    });
    const std::vector<ContourSegment> segments = isoContour(image, 0.0);
    ASSERT_FALSE(segments.empty());
    double length = 0.0;
    std::map<std::pair<long, long>, int> endpoints;
    const auto key = [](glm::dvec2 p) {
        return std::pair{std::lround(p.x * 1e6), std::lround(p.y * 1e6)};
    };
    for (const ContourSegment& s : segments) {
        // Linear interpolation along a pixel edge of a cone: within 1/(8 R) of the circle.
        EXPECT_NEAR(glm::length(s.a - centre), radius, 0.01);
        EXPECT_NEAR(glm::length(s.b - centre), radius, 0.01);
        length += glm::length(s.b - s.a);
        ++endpoints[key(s.a)];
        ++endpoints[key(s.b)];
    }
    EXPECT_NEAR(length, 2.0 * kPi * radius, 0.01 * 2.0 * kPi * radius);
    for (const auto& [point, count] : endpoints)
        EXPECT_EQ(count, 2) << "an open end at " << point.first * 1e-6 << ","
                            << point.second * 1e-6;
}

TEST(IsoContour, SaddleFollowsTheMeanOfTheCorners) {
    // Corners 0 (0,0) and 2 (1,1) inside; the centre decides which pair the segments cut off.
    for (float high : {1.0f, 0.8f}) {
        const SliceImage image =
            syntheticImage({2, 2}, [&](int x, int y) { return x == y ? high : 0.0f; });
        const double iso = 0.45; // mean 0.5 (inside) or 0.4 (outside)
        const bool centreInside = 0.5 * high >= iso;
        const std::vector<ContourSegment> segments = isoContour(image, iso);
        ASSERT_EQ(segments.size(), 2u);
        for (const ContourSegment& s : segments) {
            const glm::dvec2 mid = 0.5 * (s.a + s.b);
            // Each segment cuts off the corner on the other side from the centre.
            const bool nearInsideCorner = glm::length(mid - glm::dvec2(0, 0)) < 0.6 ||
                                          glm::length(mid - glm::dvec2(1, 1)) < 0.6;
            EXPECT_EQ(nearInsideCorner, !centreInside) << "high " << high;
        }
    }
}

TEST(IsoContour, CellsWithANaNCornerHaveNoContour) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    // A vertical edge at x = 2.5 crossing every row; column 4 is outside the volume.
    const SliceImage image =
        syntheticImage({5, 6}, [&](int x, int) { return x == 4 ? nan : float(x); });
    const std::vector<ContourSegment> at = isoContour(image, 2.5);
    EXPECT_EQ(at.size(), 5u);
    for (const ContourSegment& s : at) {
        EXPECT_DOUBLE_EQ(s.a.x, 2.5);
        EXPECT_DOUBLE_EQ(s.b.x, 2.5);
    }
    EXPECT_TRUE(isoContour(image, 3.5).empty()); // only in the cells that touch the NaN column
}

TEST(SliceEdges, OnePixelWideImagesAndASingleSlice) {
    const auto ramp = [](int x, int y, int z) { return x + 2 * y + 3 * z; };
    // One slice: its axial plane is the only position, its other planes are one row high.
    const Volume flat = test::makeFilledVolume<std::int16_t>(
        {6, 5, 1}, ramp, VolumeGeometry::regular({0, 0, 4}, {1, 1, 2}));
    const SliceGeometry axial = sliceGeometry(flat, SliceOrientation::Axial);
    EXPECT_EQ(axial.size, glm::ivec2(6, 5));
    EXPECT_DOUBLE_EQ(axial.firstPosition, 4.0);
    EXPECT_DOUBLE_EQ(axial.lastPosition, 4.0);
    const SliceImage image = sampleSlice(flat, axial, 4.0);
    EXPECT_FLOAT_EQ(image.at(5, 4), 13.0f);
    EXPECT_FALSE(isoContour(image, 6.5).empty());
    for (float v : sampleSlice(flat, axial, 4.01).values)
        EXPECT_TRUE(std::isnan(v));
    const SliceGeometry coronal = sliceGeometry(flat, SliceOrientation::Coronal);
    EXPECT_EQ(coronal.size, glm::ivec2(6, 1));
    const SliceImage row = sampleSlice(flat, coronal, 2.0);
    EXPECT_FLOAT_EQ(row.at(3, 0), 7.0f);
    EXPECT_TRUE(isoContour(row, 5.0).empty());
    // One column: sagittal planes are one pixel wide... and so are coronal ones.
    const Volume column = test::makeFilledVolume<std::uint8_t>({1, 7, 4}, ramp);
    const SliceGeometry coronalColumn = sliceGeometry(column, SliceOrientation::Coronal);
    EXPECT_EQ(coronalColumn.size, glm::ivec2(1, 4));
    const SliceImage one = sampleSlice(column, coronalColumn, 3.0);
    EXPECT_FLOAT_EQ(one.at(0, 0), 6.0f + 9.0f);
    EXPECT_TRUE(isoContour(one, 8.0).empty());
    const Volume voxel =
        test::makeFilledVolume<float>({1, 1, 1}, [](int, int, int) { return 5.0f; });
    EXPECT_EQ(sampleSlice(voxel, sliceGeometry(voxel, SliceOrientation::Sagittal), 0.0).values,
              std::vector<float>{5.0f});
    EXPECT_EQ(sampleAt(voxel, {0, 0, 0}), 5.0);
    EXPECT_FALSE(sampleAt(voxel, {0.1, 0, 0}));
}

} // namespace
} // namespace lw::volume
