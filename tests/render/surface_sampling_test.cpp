// The rule that oversamples coarse volumes for rendering (render/surface_sampling.h) and method
// 2's neighbour reach on an oversampled grid (kernels/cpu/voxel_ray.h).
#include "lw/kernels/cpu/voxel_ray.h"
#include "lw/render/surface_sampling.h"
#include "lw/volume/oversampling.h"
#include "lw/volume/phantom.h"
#include "lw/volume/slice_bridging.h"
#include "lw/volume/slice_distance.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <gtest/gtest.h>
#include <memory>
#include <string>
#include <vector>

namespace lw::render {
namespace {

using volume::VolumeGeometry;

// A parameter's name as a test name: letters and digits, the rest '_'.
std::string testNameOf(std::string name) {
    for (char& ch : name)
        if (!std::isalnum(static_cast<unsigned char>(ch)))
            ch = '_';
    return name;
}

TEST(SurfaceSampling, NamesParse) {
    EXPECT_EQ(parseOversampling("auto"), Oversampling::Auto);
    EXPECT_EQ(parseOversampling("off"), Oversampling::Off);
    EXPECT_FALSE(parseOversampling("2").has_value());
    EXPECT_EQ(oversamplingName(Oversampling::Auto), "auto");
    EXPECT_EQ(oversamplingName(Oversampling::Off), "off");
}

struct SeriesCase {
    const char* name;
    glm::ivec3 dims;
    glm::dvec3 spacing;
    glm::ivec3 factors; // under Auto
};

class SurfaceSamplingAuto : public ::testing::TestWithParam<SeriesCase> {};

TEST_P(SurfaceSamplingAuto, SplitsTheCoarseAxesOnly) {
    const SeriesCase& c = GetParam();
    const VolumeGeometry g = VolumeGeometry::regular({0, 0, 0}, c.spacing);
    EXPECT_EQ(oversamplingFactors(c.dims, g, Oversampling::Auto), c.factors) << c.name;
    EXPECT_EQ(oversamplingFactors(c.dims, g, Oversampling::Off), glm::ivec3(1)) << c.name;
}

// Diagonals: the 5 mm head 353 mm (largest cell 2.76 mm), the 4 mm one 462 mm (3.61 mm), the
// 1 mm one 355 mm (2.77 mm), the quarter-resolution head 317 mm (2.47 mm), the 64^3 grid of
// unit cells 109 (0.85).
INSTANTIATE_TEST_SUITE_P(
    Series, SurfaceSamplingAuto,
    ::testing::Values(
        SeriesCase{"head 5 mm", {512, 512, 28}, {0.4512, 0.4512, 5.0}, {1, 1, 2}},
        SeriesCase{"head 4 mm", {256, 256, 26}, {1.25, 1.25, 4.0}, {1, 1, 2}},
        SeriesCase{"head 1 mm", {512, 512, 140}, {0.4512, 0.4512, 1.0}, {1, 1, 1}},
        SeriesCase{"quarter head", {64, 64, 93}, {3.2, 3.2, 1.5}, {2, 2, 1}},
        SeriesCase{"unit 64^3", {64, 64, 64}, {1.0, 1.0, 1.0}, {2, 2, 2}},
        SeriesCase{"unit 256^3", {256, 256, 256}, {1.0, 1.0, 1.0}, {1, 1, 1}},
        SeriesCase{"one slice", {512, 512, 1}, {0.5, 0.5, 5.0}, {1, 1, 1}},
        SeriesCase{"a needle", {2, 2, 400}, {50.0, 50.0, 1.0}, {8, 8, 1}},
        // Issue 30: no 4 GiB or 16 GiB copy of a volume whose cells are small.
        SeriesCase{"phantom 1024x1024x2048", {1024, 1024, 2048}, {1.0, 1.0, 1.0}, {1, 1, 1}},
        SeriesCase{"photon-counting 0.2 mm", {1024, 1024, 2048}, {0.2, 0.2, 0.2}, {1, 1, 1}},
        SeriesCase{"micro-CT 2048^3", {2048, 2048, 2048}, {0.05, 0.05, 0.05}, {1, 1, 1}}),
    [](const auto& info) { return testNameOf(info.param.name); });

TEST(SurfaceSampling, VolumeToRenderCopiesOnlyWhenItMust) {
    auto fine =
        std::make_shared<const volume::Volume>(glm::ivec3(16, 16, 16), volume::VoxelType::Int16,
                                               VolumeGeometry::regular({0, 0, 0}, {0.1, 0.1, 0.1}));
    // 16 cells on a diagonal: every cell is coarser than 1/128 of it.
    EXPECT_EQ(volumeToRender(fine, {Oversampling::Off, ThickSlices::Smooth}, 0.0), fine);
    const auto finer = volumeToRender(fine, {Oversampling::Auto, ThickSlices::Smooth}, 0.0);
    ASSERT_NE(finer, fine);
    EXPECT_EQ(finer->dims(), volume::oversampledDims({16, 16, 16}, finer->geometry().refinement()));
    EXPECT_EQ(volumeToRender(nullptr, VolumeSampling{}, 0.0), nullptr);
}

TEST(SurfaceSampling, ThickSliceNamesParse) {
    EXPECT_EQ(parseThickSlices("smooth"), ThickSlices::Smooth);
    EXPECT_EQ(parseThickSlices("linear"), ThickSlices::Linear);
    EXPECT_FALSE(parseThickSlices("cubic").has_value());
    EXPECT_EQ(thickSlicesName(ThickSlices::Smooth), "smooth");
    EXPECT_EQ(thickSlicesName(ThickSlices::Linear), "linear");
    EXPECT_EQ(VolumeSampling{}, (VolumeSampling{Oversampling::Auto, ThickSlices::Smooth}));
}

struct ThickCase {
    const char* name;
    glm::ivec3 dims;
    glm::dvec3 spacing;
    double tiltDeg;
    glm::ivec3 smoothFactors; // under Auto + Smooth; all 1 = as loaded
    bool smoothed;
};

class SurfaceSamplingThick : public ::testing::TestWithParam<ThickCase> {};

VolumeGeometry stackOf(const ThickCase& c) {
    const double tilt = c.tiltDeg * 3.14159265358979323846 / 180.0;
    const glm::dvec3 stack(0.0, std::sin(tilt), std::cos(tilt));
    std::vector<glm::dvec3> positions;
    // The slice step along the normal is spacing.z: along the tilted stack it is longer.
    for (int k = 0; k < c.dims.z; ++k)
        positions.push_back(double(k) * c.spacing.z / std::cos(tilt) * stack);
    return VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, c.spacing.x, c.spacing.y,
                                              positions);
}

// Smooth where the slices are at least three (finer) pixels apart along their normal, with the
// slice axis split at least kThickSliceFactor times; everything else exactly as oversampling
// alone has it, and Linear is oversampling alone.
TEST_P(SurfaceSamplingThick, SmoothsThickSlicesOnly) {
    const ThickCase& c = GetParam();
    const VolumeGeometry g = stackOf(c);
    EXPECT_EQ(hasThickSlices(c.dims, g), c.smoothed) << c.name;
    const SamplingPlan smooth = samplingPlan(c.dims, g, {Oversampling::Auto, ThickSlices::Smooth});
    EXPECT_EQ(smooth.factors, c.smoothFactors) << c.name;
    EXPECT_EQ(smooth.shapeBased, c.smoothed) << c.name;
    EXPECT_EQ(smooth.dependsOnIso(), c.smoothed) << c.name;
    EXPECT_EQ(smooth.alongSlices == volume::SliceInterpolation::MonotoneCubic, c.smoothed);
    const SamplingPlan linear = samplingPlan(c.dims, g, {Oversampling::Auto, ThickSlices::Linear});
    EXPECT_EQ(linear.factors, oversamplingFactors(c.dims, g, Oversampling::Auto)) << c.name;
    EXPECT_EQ(linear.alongSlices, volume::SliceInterpolation::Linear);
    EXPECT_FALSE(linear.shapeBased);
    const SamplingPlan smoothOnly =
        samplingPlan(c.dims, g, {Oversampling::Off, ThickSlices::Smooth});
    EXPECT_EQ(smoothOnly.factors.z, c.smoothed ? kThickSliceFactor : 1) << c.name;
    EXPECT_TRUE(samplingPlan(c.dims, g, kSamplingAsLoaded).asLoaded()) << c.name;
}

INSTANTIATE_TEST_SUITE_P(
    Series, SurfaceSamplingThick,
    ::testing::Values(
        ThickCase{"head 5 mm", {512, 512, 28}, {0.4512, 0.4512, 5.0}, 0.0, {1, 1, 3}, true},
        ThickCase{"tilted 2.4 mm", {512, 512, 54}, {0.48, 0.48, 2.4}, 18.5, {1, 1, 3}, true},
        ThickCase{"head 1 mm", {512, 512, 140}, {0.4512, 0.4512, 1.0}, 0.0, {1, 1, 1}, false},
        ThickCase{"CThead 1x1x2", {256, 256, 113}, {1.0, 1.0, 2.0}, 0.0, {1, 1, 1}, false},
        ThickCase{"quarter head", {64, 64, 93}, {3.2, 3.2, 1.5}, 0.0, {2, 2, 1}, false},
        ThickCase{"two thick slices", {512, 512, 2}, {0.5, 0.5, 5.0}, 0.0, {1, 1, 2}, false},
        ThickCase{"unit 256^3", {256, 256, 256}, {1.0, 1.0, 1.0}, 0.0, {1, 1, 1}, false},
        ThickCase{
            "phantom 1024x1024x2048", {1024, 1024, 2048}, {1.0, 1.0, 1.0}, 0.0, {1, 1, 1}, false}),
    [](const auto& info) { return testNameOf(info.param.name); });

// The copy the methods draw on thick slices is the shape-based field at the iso-value: a wall
// whose edge moves one pixel a slice (a staircase of slices, the shallow wall of a skull cap)
// crosses the iso-value between the slices where the contour moves, not at one height across
// the band as the grey values do.
TEST(SurfaceSampling, VolumeToRenderInterpolatesThickSlicesByShape) {
    auto thick =
        std::make_shared<volume::Volume>(glm::ivec3(12, 1, 6), volume::VoxelType::Int16,
                                         VolumeGeometry::regular({0, 0, 0}, {0.5, 0.5, 5.0}));
    for (int k = 0; k < 6; ++k)
        for (int i = 0; i < 12; ++i)
            thick->dataAs<std::int16_t>()[k * 12 + i] = std::int16_t(i < 2 * k + 1 ? 1000 : -1000);
    const std::shared_ptr<const volume::Volume> loaded = thick;
    EXPECT_EQ(volumeToRender(loaded, {Oversampling::Off, ThickSlices::Linear}, 0.0), loaded);
    const auto shaped = volumeToRender(loaded, {Oversampling::Off, ThickSlices::Smooth}, 0.0);
    ASSERT_NE(shaped, loaded);
    EXPECT_EQ(shaped->dims(), glm::ivec3(12, 1, 16));
    EXPECT_EQ(shaped->geometry().refinement(), glm::ivec3(1, 1, kThickSliceFactor));
    // Slice 2's edge lies at column 4.5, slice 3's at 6.5 (refined k = 6 and 9). A third of the
    // way across the shape puts it at 5.17, two thirds at 5.83: column 5 inside at k = 7,
    // column 6 still outside at k = 8. The grey values cross 0 over the whole band at once,
    // halfway: column 5 outside at k = 7 (-333), column 6 inside at k = 8 (+333).
    const auto real = [&](int i, int k) {
        return shaped->valueMapping().toReal(shaped->storedValue(i, 0, k));
    };
    EXPECT_GT(real(5, 7), 0.0);
    EXPECT_LT(real(6, 7), 0.0);
    EXPECT_GT(real(5, 8), 0.0);
    EXPECT_LT(real(6, 8), 0.0);
    // The slices themselves keep their contours.
    EXPECT_GT(real(4, 6), 0.0);
    EXPECT_LT(real(5, 6), 0.0);
    EXPECT_GT(real(6, 9), 0.0);
    EXPECT_LT(real(7, 9), 0.0);
}

// A thin wall (2 mm) slanted across 5 mm slices, 5 mm further each slice: its cuts lie side by
// side, and point by point the shape-based field is outside between them at every depth (the
// wall breaks into one lip per slice). With thin walls slid (the default) it runs straight from
// cut to cut; --thin-walls 0 leaves the pointwise field.
TEST(SurfaceSampling, SlidesThinWallsBetweenThickSlicesByDefault) {
    auto wall =
        std::make_shared<volume::Volume>(glm::ivec3(64, 5, 3), volume::VoxelType::Int16,
                                         VolumeGeometry::regular({0, 0, 0}, {0.5, 0.5, 5.0}));
    for (int k = 0; k < 3; ++k)
        for (int j = 0; j < 5; ++j)
            for (int i = 0; i < 64; ++i)
                wall->dataAs<std::int16_t>()[wall->index(i, j, k)] =
                    std::abs(i * 0.5 - (10.0 + 5.0 * k)) <= 1.0 ? 1000 : -1000;
    const std::shared_ptr<const volume::Volume> loaded = wall;
    VolumeSampling pointwise{Oversampling::Off, ThickSlices::Smooth};
    pointwise.thinWallMm = 0.0;
    const auto slid = volumeToRender(loaded, {Oversampling::Off, ThickSlices::Smooth}, 0.0);
    const auto unslid = volumeToRender(loaded, pointwise, 0.0);
    const auto real = [](const volume::Volume& v, int i, int k) {
        return v.valueMapping().toReal(v.storedValue(i, 2, k));
    };
    // A third of the way from slice 0 to 1 the wall's middle is at 11.67 mm (column 23), two
    // thirds at 13.33 mm (column 27).
    EXPECT_GT(real(*slid, 23, 1), 0.0);
    EXPECT_GT(real(*slid, 27, 2), 0.0);
    EXPECT_LT(real(*unslid, 23, 1), 0.0);
    EXPECT_LT(real(*unslid, 27, 2), 0.0);
    // Away from the wall, and in the slices themselves, the same field.
    EXPECT_EQ(real(*slid, 10, 2), real(*unslid, 10, 2));
    EXPECT_EQ(real(*slid, 20, 3), real(*unslid, 20, 3));
}

// The field of an oversampled volume is its original's, terraces as deep as the original slabs:
// method 2's neighbour ray reaches as far in millimetres as on the original grid.
TEST(SurfaceSampling, NeighbourReachFollowsTheOriginalSlabs) {
    const volume::Volume coarse({6, 6, 6}, volume::VoxelType::Int16,
                                VolumeGeometry::regular({0, 0, 0}, {0.5, 0.5, 2.0}));
    const kernels::cpu::VoxelRayGrid original(coarse);
    ASSERT_NEAR(original.slabOverPixel(), 4.0, 1e-12);
    ASSERT_NEAR(original.neighbourReach(), 4.0, 1e-12); // cells of 0.5 mm: 2 mm
    const kernels::cpu::VoxelRayGrid alongSlices(volume::oversampled(coarse, {1, 1, 2}));
    EXPECT_NEAR(alongSlices.slabOverPixel(), 2.0, 1e-12);
    EXPECT_NEAR(alongSlices.neighbourReach(), 4.0, 1e-12); // still 0.5 mm cells: 2 mm
    const kernels::cpu::VoxelRayGrid inPlane(volume::oversampled(coarse, {2, 2, 1}));
    EXPECT_NEAR(inPlane.neighbourReach(), 8.0, 1e-12); // cells of 0.25 mm: 2 mm
}

// A grid coarse in plane and fine across slices (VTK's quarter head: 3.2 mm pixels, 1.5 mm
// slices) is terraced in plane: the reach spans its pixel in units of its slab, as loaded and
// after the in-plane split, and an isotropic grid keeps one cell.
TEST(SurfaceSampling, NeighbourReachFollowsCoarsePixels) {
    const volume::Volume coarse({6, 6, 6}, volume::VoxelType::Int16,
                                VolumeGeometry::regular({0, 0, 0}, {3.2, 3.2, 1.5}));
    EXPECT_NEAR(kernels::cpu::VoxelRayGrid(coarse).neighbourReach(), 3.2 / 1.5, 1e-12);
    const kernels::cpu::VoxelRayGrid split(volume::oversampled(coarse, {2, 2, 1}));
    EXPECT_NEAR(split.neighbourReach(), 3.2 / 1.5, 1e-12); // 1.6 mm pixels, 1.5 mm slices
    const volume::Volume isotropic({6, 6, 6}, volume::VoxelType::Int16,
                                   VolumeGeometry::regular({0, 0, 0}, {0.7, 0.7, 0.7}));
    EXPECT_NEAR(kernels::cpu::VoxelRayGrid(isotropic).neighbourReach(), 1.0, 1e-12);
}

// On the host the thick-slice field is written in one volume, and the maker keeps its copies:
// each is the distances oversampled as a second volume would give them, bit for bit; a copy
// someone holds keeps its voxels across later iso-values, and a released one is written again
// (fresh pages for each iso-value would cost their page faults).
TEST(DrawnVolumeMakerOnTheHost, KeepsItsCopiesAndWritesOnlyReleasedOnes) {
    const auto source = std::make_shared<const volume::Volume>(
        volume::makePhantom({260, 200, 12}, volume::PhantomKind::Ct));
    auto thick = std::make_shared<volume::Volume>(
        source->dims(), source->voxelType(),
        VolumeGeometry::regular({-20.0, 10.0, 5.0}, {0.5, 0.5, 3.0}));
    std::memcpy(thick->data(), source->data(), source->byteSize());
    thick->setValueMapping(source->valueMapping());
    const VolumeSampling sampling{Oversampling::Auto, ThickSlices::Smooth};
    const SamplingPlan plan = samplingPlan(thick->dims(), thick->geometry(), sampling);
    ASSERT_TRUE(plan.shapeBased);
    ASSERT_EQ(plan.factors.x, 1); // fine pixels: refined along the slices only, in one volume
    ASSERT_EQ(plan.factors.y, 1);
    const double limit = kThickSliceDistanceLimitSteps * 3.0;
    const auto expected = [&](double iso) {
        volume::Volume field = volume::oversampled(
            volume::signedSliceDistance(*thick, iso, limit, 2), plan.factors, 2, plan.alongSlices);
        volume::bridgeThinWalls(field, plan.factors.z, limit, plan.thinWallMm, 2);
        return field;
    };
    const auto sameVoxels = [](const volume::Volume& a, const volume::Volume& b) {
        return a.dims() == b.dims() && a.geometry().refinement() == b.geometry().refinement() &&
               std::memcmp(a.data(), b.data(), a.byteSize()) == 0;
    };
    DrawnVolumeMaker maker(thick, Backend::Cpu);
    const auto held = maker.make(sampling, 300.5, 1);
    EXPECT_FALSE(maker.lastMadeOnDevice());
    const void* heldVoxels = held->data();
    const void* releasedVoxels = nullptr;
    for (const double iso : {-400.0, 700.5, 100.0}) {
        auto next = maker.make(sampling, iso, 2);
        EXPECT_NE(next->data(), heldVoxels) << iso << ": a held copy was written again";
        EXPECT_TRUE(sameVoxels(*next, expected(iso))) << iso;
        EXPECT_EQ(next->valueMapping().intercept, iso);
        EXPECT_EQ(next->description(), thick->description());
        releasedVoxels = next->data();
    }
    EXPECT_TRUE(sameVoxels(*held, expected(300.5)));
    EXPECT_EQ(held->valueMapping().intercept, 300.5);
    const auto reused = maker.make(sampling, 500.5, 1);
    EXPECT_EQ(reused->data(), releasedVoxels) << "a released copy's memory is written again";
    EXPECT_TRUE(sameVoxels(*reused, expected(500.5)));
    EXPECT_TRUE(sameVoxels(*volumeToRender(thick, sampling, 500.5, 2), expected(500.5)));
}

} // namespace
} // namespace lw::render
