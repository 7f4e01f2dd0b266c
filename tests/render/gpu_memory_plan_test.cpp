// The CUDA back-end's memory decisions (gpu_memory_plan.h), on any machine: slab schedules under a
// budget, whole volume or slabs, and the fallbacks after running out of device memory.

#include "lw/render/gpu_memory_plan.h"

#include <gtest/gtest.h>
#include <random>

namespace lw::render {
namespace {

// The slabs cover cell layers 0 .. dims.z - 2 in order, without gaps or overlaps.
void expectCover(const std::vector<glm::ivec2>& slabs, int layers) {
    ASSERT_FALSE(slabs.empty());
    EXPECT_EQ(slabs.front().x, 0);
    EXPECT_EQ(slabs.back().y, layers);
    for (std::size_t i = 0; i < slabs.size(); ++i) {
        EXPECT_LT(slabs[i].x, slabs[i].y) << "slab " << i;
        if (i > 0) {
            EXPECT_EQ(slabs[i].x, slabs[i - 1].y) << "slab " << i;
        }
    }
}

class SlabPlan : public testing::TestWithParam<std::tuple<glm::ivec3, std::size_t, std::size_t>> {};

TEST_P(SlabPlan, CoversTheVolumeWithinTheBudget) {
    const auto [dims, voxelBytes, budget] = GetParam();
    const std::size_t reserved = std::size_t(1) << 20;
    const std::vector<glm::ivec2> slabs = planSlabs(dims, voxelBytes, budget, reserved);
    expectCover(slabs, dims.z - 1);
    const double slice = double(dims.x) * dims.y * double(voxelBytes);
    int thickest = 0;
    for (const glm::ivec2& s : slabs)
        thickest = std::max(thickest, s.y - s.x);
    // Every slab's estimate fits, unless a single layer is already too much (then one layer).
    if (thickest > 1) {
        EXPECT_LE(kSlabOverhead * (thickest + 3) * slice + double(reserved),
                  double(budget) * 1.0001);
    }
    // Even slabs: no sliver at the end.
    for (const glm::ivec2& s : slabs)
        EXPECT_GE(s.y - s.x, thickest - 1);
}

INSTANTIATE_TEST_SUITE_P(
    Budgets, SlabPlan,
    testing::Values(
        // 512 x 512 x 1024 int16 under 256 MiB: the GPU-run goal's case.
        std::make_tuple(glm::ivec3(512, 512, 1024), std::size_t(2), std::size_t(256) << 20),
        std::make_tuple(glm::ivec3(512, 512, 1024), std::size_t(2), std::size_t(64) << 40),
        std::make_tuple(glm::ivec3(100, 67, 45), std::size_t(4), std::size_t(3) << 20),
        // A budget below one layer: one layer per slab, still covered.
        std::make_tuple(glm::ivec3(512, 512, 40), std::size_t(2), std::size_t(1) << 20),
        std::make_tuple(glm::ivec3(17, 16, 2), std::size_t(1), std::size_t(1) << 30)));

TEST(GpuMemoryPlan, ThicknessCanBeCapped) {
    const std::vector<glm::ivec2> slabs = planSlabs({64, 64, 64}, 2, std::size_t(1) << 30, 0, 7);
    expectCover(slabs, 63);
    EXPECT_EQ(slabs.size(), 9u);
    for (const glm::ivec2& s : slabs)
        EXPECT_LE(s.y - s.x, 7);
}

TEST(GpuMemoryPlan, NoSlabsWithoutCells) {
    EXPECT_TRUE(planSlabs({10, 10, 1}, 2, std::size_t(1) << 30, 0).empty());
    EXPECT_TRUE(planSlabs({0, 10, 10}, 2, std::size_t(1) << 30, 0).empty());
}

TEST(GpuMemoryPlan, WholeVolumeOnlyWhenItFitsAndNoChunksWereAsked) {
    const glm::ivec3 dims(512, 512, 512); // 256 MiB of int16
    EXPECT_EQ(chooseResidency(dims, 2, std::size_t(8) << 30, 0, false), GpuResidency::WholeVolume);
    EXPECT_EQ(chooseResidency(dims, 2, std::size_t(8) << 30, 0, true), GpuResidency::Slabs);
    EXPECT_EQ(chooseResidency(dims, 2, std::size_t(512) << 20, 0, false), GpuResidency::Slabs);
    // The image buffers count too.
    const std::size_t justEnough = std::size_t((256.0 * (1.0 + kWholeVolumeOverhead)) * (1 << 20));
    EXPECT_EQ(chooseResidency(dims, 2, justEnough, 0, false), GpuResidency::WholeVolume);
    EXPECT_EQ(chooseResidency(dims, 2, justEnough, 1 << 20, false), GpuResidency::Slabs);
}

// An int16 volume of air (-1000) with bone (+1000) in the voxel boxes given ([lo, hi] inclusive).
volume::Volume airWithBone(glm::ivec3 dims,
                           const std::vector<std::pair<glm::ivec3, glm::ivec3>>& bone) {
    volume::Volume v(dims, volume::VoxelType::Int16);
    std::int16_t* voxels = v.dataAs<std::int16_t>();
    std::fill(voxels, voxels + v.voxelCount(), std::int16_t(-1000));
    for (const auto& [lo, hi] : bone)
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    voxels[v.index(x, y, z)] = 1000;
    return v;
}

TEST(SlabCrop, KeepsOnlyTheRowsAndSlabsThatCanHoldTheSurface) {
    // Bone in voxel rows y 5..7 of slices 3..4 and in row 1 of slice 8.
    const volume::Volume v =
        airWithBone({20, 12, 10}, {{{2, 5, 3}, {9, 7, 4}}, {{0, 1, 8}, {3, 1, 8}}});
    const VoxelRowRanges rows(v);
    const std::vector<glm::ivec2> layers = {{0, 2}, {2, 5}, {5, 7}, {7, 9}};
    const std::vector<kernels::CellSlab> slabs = cropSlabsToSurface(layers, rows, 300.5);
    // Cells whose corners touch a bone voxel row: y rows 4..7, layers 2..4; y rows 0..1, layers
    // 7..8. Layers 0..1 and 5..6 hold none: their slabs are left out.
    ASSERT_EQ(slabs.size(), 2u);
    EXPECT_EQ(slabs[0].layers, glm::ivec2(2, 5));
    EXPECT_EQ(slabs[0].rows, glm::ivec2(4, 8));
    EXPECT_EQ(slabs[1].layers, glm::ivec2(7, 9));
    EXPECT_EQ(slabs[1].rows, glm::ivec2(0, 2));
    // Below every voxel or above every voxel: nothing to stream.
    EXPECT_TRUE(cropSlabsToSurface(layers, rows, -2000.0).empty());
    EXPECT_TRUE(cropSlabsToSurface(layers, rows, 1000.5).empty());
    // All bone: no cell has a corner outside, so no surface and nothing to stream.
    const volume::Volume solid = airWithBone({8, 6, 5}, {{{0, 0, 0}, {7, 5, 4}}});
    EXPECT_TRUE(cropSlabsToSurface({{0, 4}}, VoxelRowRanges(solid), 300.5).empty());
}

// Every cell that can hold the surface (min < iso <= max over its 8 corners) lies in a kept slab
// and inside its rows, on random volumes and iso-values.
TEST(SlabCrop, NeverDropsACellThatCanHoldTheSurface) {
    std::mt19937 random(7);
    for (int trial = 0; trial < 20; ++trial) {
        const glm::ivec3 dims(3 + int(random() % 9), 3 + int(random() % 9), 3 + int(random() % 9));
        std::vector<std::pair<glm::ivec3, glm::ivec3>> bone;
        for (int b = 0; b < 2; ++b) {
            const glm::ivec3 lo(int(random() % dims.x), int(random() % dims.y),
                                int(random() % dims.z));
            bone.push_back({lo, glm::min(lo + glm::ivec3(int(random() % 3)), dims - 1)});
        }
        const volume::Volume v = airWithBone(dims, bone);
        const std::vector<glm::ivec2> layers = planSlabs(dims, 2, std::size_t(1) << 30, 0, 2);
        const std::vector<kernels::CellSlab> slabs =
            cropSlabsToSurface(layers, VoxelRowRanges(v), 0.0);
        for (int k = 0; k + 1 < dims.z; ++k)
            for (int j = 0; j + 1 < dims.y; ++j)
                for (int i = 0; i + 1 < dims.x; ++i) {
                    double lo = 1e9, hi = -1e9;
                    for (int c = 0; c < 8; ++c) {
                        const double value =
                            v.storedValue(i + (c & 1), j + (c >> 1 & 1), k + (c >> 2));
                        lo = std::min(lo, value);
                        hi = std::max(hi, value);
                    }
                    if (!(lo < 0.0 && 0.0 <= hi))
                        continue;
                    const bool kept =
                        std::any_of(slabs.begin(), slabs.end(), [&](const kernels::CellSlab& s) {
                            return s.layers.x <= k && k < s.layers.y && s.rows.x <= j &&
                                   j < s.rows.y;
                        });
                    EXPECT_TRUE(kept) << "trial " << trial << " cell " << i << "," << j << "," << k;
                }
    }
}

TEST(GpuMemoryPlan, OutOfMemoryGoesToSlabsThenToTheCpu) {
    EXPECT_EQ(afterOutOfMemory(GpuResidency::WholeVolume), GpuResidency::Slabs);
    EXPECT_EQ(afterOutOfMemory(GpuResidency::Slabs), GpuResidency::Cpu);
    EXPECT_EQ(afterOutOfMemory(GpuResidency::Cpu), GpuResidency::Cpu);
}

TEST(GpuMemoryPlan, DefaultBudgetLeavesAMargin) {
    EXPECT_EQ(defaultGpuBudget(0), 0u);
    EXPECT_EQ(defaultGpuBudget(std::size_t(256) << 20), 0u) << "less than the 512 MiB margin";
    const std::size_t free = std::size_t(80) << 30;
    EXPECT_EQ(defaultGpuBudget(free), free - free / 10);
    EXPECT_EQ(defaultGpuBudget(std::size_t(2) << 30),
              (std::size_t(2) << 30) - (std::size_t(512) << 20));
}

} // namespace
} // namespace lw::render
