// Thick slices made from thin ones (evaluation/thick_slices.h): the mean of each slab's thin
// slices at their mean position, on uniform, uneven and tilted stacks.
#include "filled_volume.h"
#include "lw/core/error.h"
#include "lw/evaluation/thick_slices.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <vector>

namespace lw::evaluation {
namespace {

using volume::Volume;
using volume::VolumeGeometry;

TEST(ThickSlabs, EachSlabIsTheMeanOfItsThinSlices) {
    const Volume thin = lw::test::makeFilledVolume<std::int16_t>(
        {3, 2, 11}, [](int i, int j, int k) { return 100 * k + 10 * j + i; },
        VolumeGeometry::regular({1, 2, 3}, {0.5, 0.5, 1.0}));
    const Volume thick = thickSlabsOf(thin, 5);
    ASSERT_EQ(thick.dims(), glm::ivec3(3, 2, 2)); // slice 10 makes no whole slab: dropped
    EXPECT_EQ(thick.voxelType(), thin.voxelType());
    // Slab 0: slices 0..4, mean k = 2; slab 1: slices 5..9, mean k = 7.
    EXPECT_EQ(thick.storedValue(2, 1, 0), 200.0 + 10.0 + 2.0);
    EXPECT_EQ(thick.storedValue(0, 0, 1), 700.0);
    EXPECT_NEAR(thick.geometry().sliceStep(), 5.0, 1e-9);
    const glm::dvec3 first = thick.geometry().indexToPatient({0, 0, 0});
    EXPECT_NEAR(first.z, 3.0 + 2.0, 1e-9);
    EXPECT_NEAR(thick.geometry().spacingI(), 0.5, 1e-12);
}

TEST(ThickSlabs, IntegerMeansRoundAndFloatMeansDoNot) {
    const Volume thin = lw::test::makeFilledVolume<std::int16_t>(
        {1, 1, 4}, [](int, int, int k) { return k == 0 ? 1 : 0; }, VolumeGeometry());
    EXPECT_EQ(thickSlabsOf(thin, 2).storedValue(0, 0, 0), 1.0); // 0.5 away from zero
    const Volume thinFloat = lw::test::makeFilledVolume<float>(
        {1, 1, 4}, [](int, int, int k) { return k == 0 ? 1.0 : 0.0; }, VolumeGeometry());
    EXPECT_NEAR(thickSlabsOf(thinFloat, 2).storedValue(0, 0, 0), 0.5, 1e-7);
}

// A tilted, unevenly spaced thin stack: the thick slices lie at the mean of their thin ones'
// positions, tilt kept, gaps uneven where the thin ones were.
TEST(ThickSlabs, KeepTiltAndUnevenGaps) {
    const double tilt = 18.5 * 3.14159265358979323846 / 180.0;
    const glm::dvec3 stack(0.0, std::sin(tilt), std::cos(tilt));
    std::vector<glm::dvec3> positions;
    for (double offset : {0.0, 1.0, 2.0, 3.0, 5.0, 7.0})
        positions.push_back(offset * stack);
    const VolumeGeometry geometry =
        VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 0.5, 0.5, positions);
    const Volume thin({2, 2, 6}, volume::VoxelType::Int16, geometry);
    const Volume thick = thickSlabsOf(thin, 2);
    ASSERT_EQ(thick.dims().z, 3);
    EXPECT_NEAR(thick.geometry().tiltDegrees(), 18.5, 1e-6);
    EXPECT_NEAR(thick.geometry().sliceGap(0), 2.0, 1e-9); // 0.5 -> 2.5
    EXPECT_NEAR(thick.geometry().sliceGap(1), 3.5, 1e-9); // 2.5 -> 6
}

// The bound's slabs start at every thin slice: slab s is the mean of slices s .. s + 4 at their
// mean position, the thin spacing kept.
TEST(ThickSlabs, AtEverySliceSlideByOneThinSlice) {
    const Volume thin = lw::test::makeFilledVolume<std::int16_t>(
        {3, 2, 11}, [](int i, int j, int k) { return 100 * k + 10 * j + i; },
        VolumeGeometry::regular({1, 2, 3}, {0.5, 0.5, 1.0}));
    const Volume dense = slabMeansAtEverySlice(thin, 5);
    ASSERT_EQ(dense.dims(), glm::ivec3(3, 2, 7)); // slabs 0-4 .. 6-10
    for (int k = 0; k < 7; ++k)
        EXPECT_EQ(dense.storedValue(1, 1, k), 100.0 * (k + 2) + 11.0) << k;
    EXPECT_NEAR(dense.geometry().sliceStep(), 1.0, 1e-9);
    EXPECT_NEAR(dense.geometry().indexToPatient({0, 0, 0}).z, 3.0 + 2.0, 1e-9);
    EXPECT_THROW(slabMeansAtEverySlice(thin, 11), core::Error); // one slab only
}

TEST(ThickSlabs, RefusesTooFewSlices) {
    const Volume thin({2, 2, 9}, volume::VoxelType::Int16);
    EXPECT_THROW(thickSlabsOf(thin, 5), core::Error);
    EXPECT_THROW(thickSlabsOf(thin, 0), core::Error);
    EXPECT_NO_THROW(thickSlabsOf(thin, 4));
}

} // namespace
} // namespace lw::evaluation

namespace lw::evaluation {
namespace {

// Scanner-like noise: zero mean and the asked deviation (in real units: a slope of 2 halves it in
// stored units), the same from the same seed, clamped to the voxel type.
TEST(VoxelNoise, HasTheAskedDeviationAndRepeats) {
    volume::Volume a({64, 64, 16}, volume::VoxelType::Int16);
    a.setValueMapping({2.0, -1024.0});
    std::fill_n(a.dataAs<std::int16_t>(), a.voxelCount(), std::int16_t(700));
    volume::Volume b = a.clone();
    addVoxelNoise(a, 40.0, 7);
    addVoxelNoise(b, 40.0, 7);
    double sum = 0.0, squares = 0.0;
    for (std::size_t v = 0; v < a.voxelCount(); ++v) {
        ASSERT_EQ(a.dataAs<std::int16_t>()[v], b.dataAs<std::int16_t>()[v]);
        const double stored = a.dataAs<std::int16_t>()[v] - 700.0;
        sum += stored;
        squares += stored * stored;
    }
    const double n = double(a.voxelCount());
    EXPECT_NEAR(sum / n, 0.0, 0.1);
    EXPECT_NEAR(std::sqrt(squares / n), 20.0, 0.3); // 40 HU at 2 HU a stored unit
    volume::Volume bytes({256, 1, 1}, volume::VoxelType::UInt8);
    std::fill_n(bytes.dataAs<std::uint8_t>(), 256, std::uint8_t(250));
    addVoxelNoise(bytes, 50.0);
    EXPECT_EQ(*std::max_element(bytes.dataAs<std::uint8_t>(), bytes.dataAs<std::uint8_t>() + 256),
              255);
    EXPECT_THROW(addVoxelNoise(bytes, -1.0), core::Error);
}

} // namespace
} // namespace lw::evaluation
