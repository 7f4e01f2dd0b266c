// The CUDA back-end's memory decisions (gpu_memory_plan.h), on any machine: slab schedules under a
// budget, whole volume or slabs, and the fallbacks after running out of device memory.

#include "lw/render/gpu_memory_plan.h"

#include <gtest/gtest.h>

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
        EXPECT_LE(kSlabOverhead * (thickest + 3) * slice + double(reserved), double(budget) * 1.0001);
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
    const std::vector<glm::ivec2> slabs =
        planSlabs({64, 64, 64}, 2, std::size_t(1) << 30, 0, 7);
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
    EXPECT_EQ(defaultGpuBudget(std::size_t(2) << 30), (std::size_t(2) << 30) - (std::size_t(512) << 20));
}

} // namespace
} // namespace lw::render
