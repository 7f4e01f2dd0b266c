// Shape-based interpolation across thick slices (volume/slice_distance.h): each slice's signed
// in-plane distance to its iso contour, to the sub-pixel contour, in millimetres; interpolated
// between slices it moves a contour straight from one slice's ring to the next one's, where
// grey values leave a flat tread.
#include "filled_volume.h"
#include "lw/core/error.h"
#include "lw/kernels/slice_field_rules.h"
#include "lw/volume/oversampling.h"
#include "lw/volume/slice_distance.h"
#include "lw/volume/volume.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <gtest/gtest.h>
#include <limits>
#include <random>
#include <vector>

namespace lw::volume {
namespace {

constexpr double kIso = 300.0;
constexpr double kLimitMm = 100.0; // beyond every distance in these slices

// A stack of discs of radius radii[k] (mm) about (cx, cy), bone (1000) inside and water (0)
// outside, with a one-pixel partial-volume rim as a scanner gives: the value falls linearly
// from 1000 to 0 across the pixel the edge runs through.
Volume discStack(glm::ivec3 dims, glm::dvec2 spacing, const std::vector<double>& radii) {
    const double cx = 0.5 * (dims.x - 1) * spacing.x;
    const double cy = 0.5 * (dims.y - 1) * spacing.y;
    return lw::test::makeFilledVolume<std::int16_t>(
        dims,
        [&](int i, int j, int k) {
            const double r = std::hypot(i * spacing.x - cx, j * spacing.y - cy);
            const double inside =
                std::clamp(0.5 + (radii[std::size_t(k)] - r) / spacing.x, 0.0, 1.0);
            return std::lround(1000.0 * inside);
        },
        VolumeGeometry::regular({0, 0, 0}, {spacing.x, spacing.y, 5.0}));
}

// Where the real value crosses kIso along row j of slice k, from the centre outward (mm from
// the centre column), by linear interpolation between samples.
double crossingAlongRow(const Volume& v, int j, int k) {
    const int centre = (v.dims().x - 1) / 2;
    const double spacing = v.geometry().spacingI();
    const ValueMapping m = v.valueMapping();
    for (int i = centre; i + 1 < v.dims().x; ++i) {
        const double a = m.toReal(v.storedValue(i, j, k)) - kIso;
        const double b = m.toReal(v.storedValue(i + 1, j, k)) - kIso;
        if (a >= 0.0 && b < 0.0)
            return (double(i - centre) + a / (a - b)) * spacing;
    }
    return -1.0;
}

// Every pixel's distance by brute force: the smallest over all of the slice's crossings, with
// the shared arithmetic (kernels/slice_field_rules.h) -- what the separable minimum must equal
// exactly, since a minimum of the same values does not depend on the order it is taken in.
std::int16_t bruteForceStored(const std::vector<float>& above, int width, int height, int x, int y,
                              float scaleI, float scaleJ, double limitMm) {
    float best = std::numeric_limits<float>::infinity();
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < width; ++c) {
            const float a = above[std::size_t(r * width + c)];
            if (c + 1 < width && kernels::crossesIso(a, above[std::size_t(r * width + c + 1)])) {
                const float at =
                    float(c) + kernels::crossingOffset(a, above[std::size_t(r * width + c + 1)]);
                const float near = at <= float(x) ? float(x) - at : at - float(x);
                best = std::min(best,
                                kernels::nearTerm(scaleI, near) + kernels::stepTerm(scaleJ, r - y));
            }
            if (r + 1 < height && kernels::crossesIso(a, above[std::size_t((r + 1) * width + c)])) {
                const float at =
                    float(r) + kernels::crossingOffset(a, above[std::size_t((r + 1) * width + c)]);
                const float near = at <= float(y) ? float(y) - at : at - float(y);
                best = std::min(best,
                                kernels::nearTerm(scaleJ, near) + kernels::stepTerm(scaleI, c - x));
            }
        }
    return kernels::storedSliceDistance(best, above[std::size_t(y * width + x)] >= 0.0f, limitMm,
                                        kSliceDistanceStepsPerMm);
}

// Smooth blobs with noise on anisotropic pixels, at limits shorter and longer than the slices.
TEST(SliceDistance, EqualsTheBruteForceMinimumOverAllCrossings) {
    std::mt19937 random(7);
    std::normal_distribution<double> noise(0.0, 120.0);
    const glm::ivec3 dims(37, 29, 3);
    const Volume blobs = lw::test::makeFilledVolume<std::int16_t>(
        dims,
        [&](int i, int j, int k) {
            const double wave = std::sin(0.3 * i + k) * std::cos(0.23 * j) * 600.0;
            return std::lround(250.0 + wave + noise(random));
        },
        VolumeGeometry::regular({0, 0, 0}, {0.7, 1.1, 4.0}));
    const float scaleI = float(0.7 * 0.7), scaleJ = float(1.1 * 1.1);
    for (const double limit : {2.5, 4.0, 30.0}) {
        const Volume distance = signedSliceDistance(blobs, kIso, limit, 2);
        std::size_t differing = 0;
        for (int k = 0; k < dims.z; ++k) {
            std::vector<float> above(std::size_t(dims.x) * std::size_t(dims.y));
            for (int j = 0; j < dims.y; ++j)
                for (int i = 0; i < dims.x; ++i)
                    above[std::size_t(j * dims.x + i)] =
                        float(double(blobs.storedValue(i, j, k)) - kIso);
            for (int j = 0; j < dims.y; ++j)
                for (int i = 0; i < dims.x; ++i)
                    differing +=
                        distance.storedValue(i, j, k) !=
                        bruteForceStored(above, dims.x, dims.y, i, j, scaleI, scaleJ, limit);
        }
        EXPECT_EQ(differing, 0u) << "limit " << limit << " mm";
    }
}

TEST(SliceDistance, IsTheSignedDistanceToTheSubPixelContour) {
    const Volume discs = discStack({81, 81, 1}, {0.5, 0.5}, {12.3});
    const Volume distance = signedSliceDistance(discs, kIso, kLimitMm, 2);
    ASSERT_EQ(distance.dims(), discs.dims());
    EXPECT_EQ(distance.voxelType(), VoxelType::Int16);
    EXPECT_EQ(distance.valueMapping().intercept, kIso);
    // The contour is where the grey values put it (drawn at kIso, the same crossing) ...
    EXPECT_NEAR(crossingAlongRow(distance, 40, 0), crossingAlongRow(discs, 40, 0), 0.02);
    // ... and every sample holds its distance to it: the centre about the radius inside, a
    // corner its distance to the circle outside (the grey values' contour is the circle of
    // radius 12.3 mm + 0.2 px, the rim's 30 % level, as a polygon through the crossings).
    const double radius = crossingAlongRow(discs, 40, 0);
    const ValueMapping m = distance.valueMapping();
    EXPECT_NEAR(m.toReal(distance.storedValue(40, 40, 0)) - kIso, radius, 0.05);
    EXPECT_NEAR(m.toReal(distance.storedValue(0, 0, 0)) - kIso, -(std::hypot(20.0, 20.0) - radius),
                0.1);
    EXPECT_NEAR(m.toReal(distance.storedValue(40, 70, 0)) - kIso, -(15.0 - radius), 0.1);
}

// Pixels 0.5 x 1.0 mm: distances count millimetres, not pixels.
TEST(SliceDistance, CountsMillimetresOnAnisotropicPixels) {
    Volume v({41, 21, 1}, VoxelType::Float32, VolumeGeometry::regular({0, 0, 0}, {0.5, 1.0, 5.0}));
    for (int j = 0; j < 21; ++j)
        for (int i = 0; i < 41; ++i)
            v.dataAs<float>()[v.index(i, j, 0)] = i <= 20 && j <= 10 ? 1000.0f : 0.0f;
    const Volume distance = signedSliceDistance(v, 500.0, kLimitMm, 1);
    const ValueMapping m = distance.valueMapping();
    // The contour runs half a pixel beyond the last bone pixel: x = 10.25 mm, y = 10.5 mm.
    EXPECT_NEAR(m.toReal(distance.storedValue(0, 0, 0)) - 500.0, 10.25, 0.02);
    EXPECT_NEAR(m.toReal(distance.storedValue(30, 0, 0)) - 500.0, -(15.0 - 10.25), 0.02);
    EXPECT_NEAR(m.toReal(distance.storedValue(0, 20, 0)) - 500.0, -(20.0 - 10.5), 0.02);
}

// Distances stop at the limit, and a slice with no contour is at it throughout: the disc of
// slice 0 (radius 5 mm) closes 5 / (5 + 4) of the way to slice 1 under a 4 mm limit.
TEST(SliceDistance, ASliceWithoutContourIsAtTheLimit) {
    const Volume discs = discStack({21, 21, 2}, {1.0, 1.0}, {5.0, -10.0});
    const Volume distance = signedSliceDistance(discs, kIso, 4.0, 1);
    const ValueMapping m = distance.valueMapping();
    EXPECT_NEAR(m.toReal(distance.storedValue(10, 10, 1)) - kIso, -4.0, 1e-9);
    EXPECT_NEAR(m.toReal(distance.storedValue(0, 0, 0)) - kIso, -4.0, 1e-9);
    const double centre = m.toReal(distance.storedValue(10, 10, 0)) - kIso;
    EXPECT_NEAR(centre, 4.0, 1e-9); // 5.2 mm from the rim, limited
    EXPECT_THROW(signedSliceDistance(discs, kIso, 0.0, 1), core::Error);
    EXPECT_THROW(signedSliceDistance(discs, kIso, 1000.0, 1), core::Error);
}

// Two slices whose discs differ by 8 mm in radius (a wall at a shallow angle): halfway
// between them the interpolated distance puts the contour halfway between the two rings, and
// a quarter of the way a quarter of the way -- a straight slope. The grey values, linearly
// interpolated, keep the contour of the nearer slice for most of the gap.
TEST(SliceDistance, InterpolatedItMovesTheContourStraightFromRingToRing) {
    const Volume discs = discStack({101, 101, 2}, {0.5, 0.5}, {8.0, 16.0});
    const Volume shapes = oversampled(signedSliceDistance(discs, kIso, kLimitMm, 2), {1, 1, 4}, 2);
    const double first = crossingAlongRow(discs, 50, 0);
    const double last = crossingAlongRow(discs, 50, 1);
    for (int step = 0; step <= 4; ++step)
        EXPECT_NEAR(crossingAlongRow(shapes, 50, step), first + (last - first) * step / 4.0, 0.05)
            << step;
    // Grey values: the band between the rings is 1000 in one slice and 0 in the other, so it
    // crosses 300 at t = 0.3 everywhere at once -- a tread at the first ring, then a riser.
    const Volume greys = oversampled(discs, {1, 1, 4}, 2);
    EXPECT_NEAR(crossingAlongRow(greys, 50, 1), first, 0.3);
    EXPECT_NEAR(crossingAlongRow(greys, 50, 2), last, 0.3);
}

// The slice's values less the iso-value as the field sees them, through the volume's mapping.
std::vector<float> aboveIsoOf(const Volume& v, int k, double iso) {
    std::vector<float> above(std::size_t(v.dims().x) * std::size_t(v.dims().y));
    for (int j = 0; j < v.dims().y; ++j)
        for (int i = 0; i < v.dims().x; ++i)
            above[std::size_t(j * v.dims().x + i)] =
                float(v.valueMapping().toReal(v.storedValue(i, j, k)) - iso);
    return above;
}

// Slices whose contours are few and small -- specks, a small disc, a line -- in a wide field
// below the iso-value: the rows and blocks no crossing reaches are skipped, the rest must still
// be the exact minimum. Every voxel type, mappings that rise and fall, widths that are not a
// multiple of the blocks.
struct SparseCase {
    const char* name;
    VoxelType type;
    ValueMapping mapping;
    double limitMm;
};

class SliceDistanceSparse : public ::testing::TestWithParam<SparseCase> {};

TEST_P(SliceDistanceSparse, EqualsTheBruteForceMinimum) {
    const SparseCase& c = GetParam();
    const glm::ivec3 dims(150, 61, 3);
    Volume v(dims, c.type, VolumeGeometry::regular({0, 0, 0}, {0.6, 0.9, 5.0}));
    v.setValueMapping(c.mapping);
    std::mt19937 random(11);
    std::uniform_real_distribution<double> jitter(-40.0, 40.0);
    std::uniform_int_distribution<int> column(0, dims.x - 1), row(0, dims.y - 1);
    std::vector<std::pair<int, int>> specks;
    for (int n = 0; n < 6; ++n)
        specks.emplace_back(column(random), row(random));
    const double iso = 300.0;
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                double real = 100.0 + jitter(random); // below the iso-value
                if (k == 0 && std::hypot(i - 40.0, j - 30.0) < 4.5 + 0.3 * (i % 3))
                    real = 700.0 + jitter(random); // a small disc
                if (k == 1 && j == 20 && i > 60 && i < 140)
                    real = 600.0; // a line one row thick
                for (const auto& [si, sj] : specks)
                    if (k == 2 && i == si && j == sj)
                        real = 900.0; // single pixels
                const double stored = std::round(c.mapping.toStored(real));
                dispatchVoxelType(c.type, [&](auto tag) {
                    using T = decltype(tag);
                    v.dataAs<T>()[v.index(i, j, k)] = T(stored);
                });
            }
    const Volume distance = signedSliceDistance(v, iso, c.limitMm, 2);
    const float scaleI = float(0.6 * 0.6), scaleJ = float(0.9 * 0.9);
    std::size_t differing = 0, nearer = 0;
    for (int k = 0; k < dims.z; ++k) {
        const std::vector<float> above = aboveIsoOf(v, k, iso);
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) {
                const std::int16_t expected =
                    bruteForceStored(above, dims.x, dims.y, i, j, scaleI, scaleJ, c.limitMm);
                differing += distance.storedValue(i, j, k) != expected;
                nearer +=
                    std::abs(expected) < int(std::lround(c.limitMm * kSliceDistanceStepsPerMm));
            }
    }
    EXPECT_EQ(differing, 0u);
    EXPECT_GT(nearer, 200u); // the contours are there, and the test sees them
}

INSTANTIATE_TEST_SUITE_P(
    Types, SliceDistanceSparse,
    ::testing::Values(SparseCase{"Int16", VoxelType::Int16, {1.0, 0.0}, 2.0},
                      SparseCase{"UInt16Ct", VoxelType::UInt16, {0.5, -1024.0}, 3.0},
                      SparseCase{"UInt8Falling", VoxelType::UInt8, {-4.0, 1000.0}, 2.5},
                      SparseCase{"Float32", VoxelType::Float32, {1.0, 0.0}, 1.5}),
    [](const ::testing::TestParamInfo<SparseCase>& info) { return info.param.name; });

// The field written in one volume -- the distances into every factor-th slice, the slices between
// refined in place -- is what the distances oversampled as a second volume give, bit for bit:
// linear and monotone, one gap and several, planes that are not a multiple of the runs.
struct InPlaceCase {
    const char* name;
    glm::ivec3 dims;
    int factor;
    SliceInterpolation interpolation;
};

class ThickSliceFieldInPlace : public ::testing::TestWithParam<InPlaceCase> {};

// Refined slice k of an int16 volume along the slices, voxel by voxel with the shared arithmetic
// (kernels/slice_field_rules.h): the reference that oversampled's runs and copies must equal.
std::int16_t refinedAlongSlices(const Volume& v, int i, int j, int k, int factor, bool monotone) {
    const int lower = k / factor;
    const float t = float(k % factor) / float(factor);
    const auto at = [&](int slice) { return float(v.storedValue(i, j, slice)); };
    if (k % factor == 0)
        return std::int16_t(at(lower));
    const float y1 = at(lower), y2 = at(lower + 1);
    if (!monotone || v.dims().z <= 2)
        return std::int16_t(kernels::roundHalfAway(kernels::linearBlend(y1, t, y2)));
    const float secant = y2 - y1;
    const float m1 = lower == 0 ? secant : kernels::monotoneTangent(y1 - at(lower - 1), secant);
    const float m2 =
        lower + 2 >= v.dims().z ? secant : kernels::monotoneTangent(secant, at(lower + 2) - y2);
    return std::int16_t(
        kernels::roundHalfAway(kernels::hermiteBlend(kernels::HermiteWeights(t), y1, m1, y2, m2)));
}

std::size_t differingFromReference(const Volume& refined, const Volume& original, int factor,
                                   bool monotone) {
    std::size_t differing = 0;
    for (int k = 0; k < refined.dims().z; ++k)
        for (int j = 0; j < refined.dims().y; ++j)
            for (int i = 0; i < refined.dims().x; ++i)
                differing += refined.storedValue(i, j, k) !=
                             refinedAlongSlices(original, i, j, k, factor, monotone);
    return differing;
}

TEST_P(ThickSliceFieldInPlace, EqualsTheDistancesOversampled) {
    const InPlaceCase& c = GetParam();
    std::mt19937 random(3);
    std::normal_distribution<double> noise(0.0, 80.0);
    const Volume blobs = lw::test::makeFilledVolume<std::int16_t>(
        c.dims,
        [&](int i, int j, int k) {
            const double wave = std::sin(0.35 * i + 0.9 * k) * std::cos(0.2 * j) * 700.0;
            return std::lround(250.0 + wave + noise(random));
        },
        VolumeGeometry::regular({0, 0, 0}, {0.7, 0.8, 4.0}));
    const double limit = 3.0;
    const Volume expected = oversampled(signedSliceDistance(blobs, kIso, limit, 2),
                                        {1, 1, c.factor}, 2, c.interpolation);
    Volume field(expected.dims(), VoxelType::Int16, expected.geometry());
    std::fill_n(field.dataAs<std::int16_t>(), field.voxelCount(), std::int16_t(12345));
    writeSignedSliceDistance(blobs, kIso, limit, c.factor, field, 2);
    refineBetweenSlices(field, c.factor, 2, c.interpolation);
    ASSERT_EQ(field.dims(), expected.dims());
    EXPECT_EQ(std::memcmp(field.data(), expected.data(), field.byteSize()), 0);
    // Both against the voxel-by-voxel reference (they share the runs' code).
    const bool monotone = c.interpolation == SliceInterpolation::MonotoneCubic;
    EXPECT_EQ(differingFromReference(field, signedSliceDistance(blobs, kIso, limit, 1), c.factor,
                                     monotone),
              0u);
    // Written again at another iso-value, the same volume holds that one's field.
    const Volume other = oversampled(signedSliceDistance(blobs, kIso + 150.0, limit, 2),
                                     {1, 1, c.factor}, 2, c.interpolation);
    writeSignedSliceDistance(blobs, kIso + 150.0, limit, c.factor, field, 1);
    refineBetweenSlices(field, c.factor, 1, c.interpolation);
    EXPECT_EQ(std::memcmp(field.data(), other.data(), field.byteSize()), 0);
}

INSTANTIATE_TEST_SUITE_P(
    Fields, ThickSliceFieldInPlace,
    ::testing::Values(
        InPlaceCase{"MonotoneFactor3", {37, 29, 5}, 3, SliceInterpolation::MonotoneCubic},
        InPlaceCase{"MonotoneOneGap", {40, 16, 2}, 4, SliceInterpolation::MonotoneCubic},
        InPlaceCase{"MonotoneTwoGapsOddPlane", {17, 9, 3}, 2, SliceInterpolation::MonotoneCubic},
        InPlaceCase{"LinearFactor3", {33, 20, 4}, 3, SliceInterpolation::Linear},
        InPlaceCase{"MonotoneWidePlane", {101, 37, 4}, 3, SliceInterpolation::MonotoneCubic}),
    [](const ::testing::TestParamInfo<InPlaceCase>& info) { return info.param.name; });

TEST(ThickSliceFieldInPlace, RefusesAFieldOfAnotherSizeOrType) {
    const Volume discs = discStack({21, 21, 3}, {1.0, 1.0}, {5.0, 6.0, 7.0});
    Volume wrongSize({21, 21, 6}, VoxelType::Int16);
    EXPECT_THROW(writeSignedSliceDistance(discs, kIso, 4.0, 3, wrongSize, 1), core::Error);
    Volume wrongType({21, 21, 7}, VoxelType::Float32);
    EXPECT_THROW(writeSignedSliceDistance(discs, kIso, 4.0, 3, wrongType, 1), core::Error);
    EXPECT_THROW(refineBetweenSlices(wrongType, 3, 1), core::Error);
    EXPECT_THROW(refineBetweenSlices(wrongSize, 2, 1), core::Error); // 6 slices: not 2n + 1
}

} // namespace
} // namespace lw::volume
