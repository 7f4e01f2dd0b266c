// The rule that oversamples coarse volumes for rendering (render/surface_sampling.h) and method
// 2's neighbour reach on an oversampled grid (kernels/cpu/voxel_ray.h).
#include "lw/kernels/cpu/voxel_ray.h"
#include "lw/render/surface_sampling.h"
#include "lw/volume/oversampling.h"

#include <cctype>
#include <gtest/gtest.h>
#include <memory>

namespace lw::render {
namespace {

using volume::VolumeGeometry;

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
    ::testing::Values(SeriesCase{"head 5 mm", {512, 512, 28}, {0.4512, 0.4512, 5.0}, {1, 1, 2}},
                      SeriesCase{"head 4 mm", {256, 256, 26}, {1.25, 1.25, 4.0}, {1, 1, 2}},
                      SeriesCase{"head 1 mm", {512, 512, 140}, {0.4512, 0.4512, 1.0}, {1, 1, 1}},
                      SeriesCase{"quarter head", {64, 64, 93}, {3.2, 3.2, 1.5}, {2, 2, 1}},
                      SeriesCase{"unit 64^3", {64, 64, 64}, {1.0, 1.0, 1.0}, {2, 2, 2}},
                      SeriesCase{"unit 256^3", {256, 256, 256}, {1.0, 1.0, 1.0}, {1, 1, 1}},
                      SeriesCase{"one slice", {512, 512, 1}, {0.5, 0.5, 5.0}, {1, 1, 1}},
                      SeriesCase{"a needle", {2, 2, 400}, {50.0, 50.0, 1.0}, {8, 8, 1}}),
    [](const auto& info) {
        std::string name = info.param.name;
        for (char& ch : name)
            if (!std::isalnum(static_cast<unsigned char>(ch)))
                ch = '_';
        return name;
    });

TEST(SurfaceSampling, VolumeToRenderCopiesOnlyWhenItMust) {
    auto fine =
        std::make_shared<const volume::Volume>(glm::ivec3(16, 16, 16), volume::VoxelType::Int16,
                                               VolumeGeometry::regular({0, 0, 0}, {0.1, 0.1, 0.1}));
    // 16 cells on a diagonal: every cell is coarser than 1/128 of it.
    EXPECT_EQ(volumeToRender(fine, Oversampling::Off), fine);
    const auto finer = volumeToRender(fine, Oversampling::Auto);
    ASSERT_NE(finer, fine);
    EXPECT_EQ(finer->dims(), volume::oversampledDims({16, 16, 16}, finer->geometry().refinement()));
    EXPECT_EQ(volumeToRender(nullptr, Oversampling::Auto), nullptr);
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

} // namespace
} // namespace lw::render
