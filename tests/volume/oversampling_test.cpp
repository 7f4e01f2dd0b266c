// Oversampling (volume/oversampling.h): finer samples of the same trilinear field, on every
// voxel type, with the geometry of the original grid (uniform, uneven and tilted stacks).
#include "filled_volume.h"
#include "lw/core/error.h"
#include "lw/volume/oversampling.h"
#include "lw/volume/volume.h"
#include "lw/volume/volume_geometry.h"

#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <utility>
#include <vector>

namespace lw::volume {
namespace {

// A trilinear function of the index (i, j, k): its samples on any finer grid are its linear
// interpolation, so an oversampled volume of it must hold it exactly (up to float rounding).
double trilinear(double i, double j, double k) {
    return 3.0 + 2.0 * i - 1.5 * j + 4.0 * k + 0.25 * i * j - 0.5 * j * k + 0.125 * i * j * k;
}

Volume floatVolumeOf(glm::ivec3 dims) {
    return lw::test::makeFilledVolume<float>(
        dims, [](int i, int j, int k) { return trilinear(i, j, k); },
        VolumeGeometry::regular({0, 0, 0}, {0.5, 0.5, 5.0}));
}

void expectNear(glm::dvec3 a, glm::dvec3 b) {
    EXPECT_NEAR(a.x, b.x, 1e-9);
    EXPECT_NEAR(a.y, b.y, 1e-9);
    EXPECT_NEAR(a.z, b.z, 1e-9);
}

TEST(Oversampling, DimsSplitEachGapAndKeepSingleSamples) {
    EXPECT_EQ(oversampledDims({5, 4, 3}, {1, 2, 3}), glm::ivec3(5, 7, 7));
    EXPECT_EQ(oversampledDims({1, 4, 2}, {4, 1, 2}), glm::ivec3(1, 4, 3));
    EXPECT_THROW(oversampled(floatVolumeOf({2, 2, 2}), {1, 0, 1}), core::Error);
}

class OversamplingFactors : public ::testing::TestWithParam<glm::ivec3> {};

TEST_P(OversamplingFactors, HoldsTheTrilinearFieldExactly) {
    const glm::ivec3 factors = GetParam();
    const Volume coarse = floatVolumeOf({5, 4, 3});
    const Volume fine = oversampled(coarse, factors, 2);
    ASSERT_EQ(fine.dims(), oversampledDims(coarse.dims(), factors));
    ASSERT_EQ(fine.voxelType(), VoxelType::Float32);
    for (int k = 0; k < fine.dims().z; ++k)
        for (int j = 0; j < fine.dims().y; ++j)
            for (int i = 0; i < fine.dims().x; ++i)
                ASSERT_NEAR(
                    fine.storedValue(i, j, k),
                    trilinear(double(i) / factors.x, double(j) / factors.y, double(k) / factors.z),
                    1e-4)
                    << i << "," << j << "," << k;
}

INSTANTIATE_TEST_SUITE_P(Axes, OversamplingFactors,
                         ::testing::Values(glm::ivec3(1, 1, 1), glm::ivec3(1, 1, 2),
                                           glm::ivec3(3, 1, 1), glm::ivec3(1, 4, 1),
                                           glm::ivec3(2, 3, 4)));

TEST(Oversampling, IntegerTypesKeepTheirSamplesAndRoundTheNewOnes) {
    Volume v({2, 1, 3}, VoxelType::Int16);
    std::int16_t* data = v.dataAs<std::int16_t>();
    const std::int16_t values[] = {-1000, 7, 1, 2, 400, 401};
    std::copy(std::begin(values), std::end(values), data);
    v.setValueMapping({1.0, -1024.0});
    v.setDescription("head");
    const Volume fine = oversampled(v, {2, 1, 2});
    ASSERT_EQ(fine.dims(), glm::ivec3(3, 1, 5));
    EXPECT_EQ(fine.voxelType(), VoxelType::Int16);
    EXPECT_EQ(fine.valueMapping().intercept, -1024.0);
    EXPECT_EQ(fine.description(), "head");
    // The original samples exactly, at every second index.
    for (int k = 0; k < 3; ++k)
        for (int i = 0; i < 2; ++i)
            EXPECT_EQ(fine.storedValue(2 * i, 0, 2 * k), v.storedValue(i, 0, k));
    // Between them the mean, rounded to the nearest value: (-1000 + 7) / 2 = -496.5 -> -497
    // (half away from zero), (1 + 400) / 2 = 200.5 -> 201, the cell centre (1+2+400+401)/4.
    EXPECT_EQ(fine.storedValue(1, 0, 0), -497.0);
    EXPECT_EQ(fine.storedValue(0, 0, 3), 201.0);
    EXPECT_EQ(fine.storedValue(1, 0, 3), 201.0);
    for (VoxelType type : {VoxelType::UInt8, VoxelType::UInt16}) {
        Volume u({2, 1, 1}, type);
        dispatchVoxelType(type, [&](auto tag) {
            using T = decltype(tag);
            u.dataAs<T>()[0] = T(0);
            u.dataAs<T>()[1] = T(255);
        });
        const Volume f = oversampled(u, {4, 1, 1});
        EXPECT_EQ(f.storedValue(1, 0, 0), 64.0);  // 63.75
        EXPECT_EQ(f.storedValue(2, 0, 0), 128.0); // 127.5
        EXPECT_EQ(f.storedValue(4, 0, 0), 255.0);
    }
}

// Refined index n * factor lies where original index n did, on every kind of stack.
void expectSamePlaces(const VolumeGeometry& coarse, const VolumeGeometry& fine, glm::ivec3 factors,
                      glm::ivec3 dims) {
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; j += dims.y - 1)
            for (int i = 0; i < dims.x; i += dims.x - 1)
                expectNear(fine.indexToPatient(glm::dvec3(i, j, k) * glm::dvec3(factors)),
                           coarse.indexToPatient({i, j, k}));
}

TEST(Oversampling, GeometryOfUniformUnevenAndTiltedStacks) {
    const glm::ivec3 dims(4, 3, 4);
    const glm::ivec3 factors(2, 1, 3);
    const VolumeGeometry uniform = VolumeGeometry::regular({10, -5, 2}, {0.5, 0.7, 5.0});
    // Uneven gaps (2, 7, 3 mm) on a stack tilted 18.5 degrees, as the demo CT.
    const double tilt = 18.5 * 3.14159265358979323846 / 180.0;
    const glm::dvec3 stack(0.0, std::sin(tilt), std::cos(tilt));
    std::vector<glm::dvec3> positions;
    for (double offset : {0.0, 2.0, 9.0, 12.0})
        positions.push_back(glm::dvec3(1, 2, 3) + offset * stack);
    const VolumeGeometry uneven =
        VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 0.5, 0.5, positions);
    ASSERT_FALSE(uneven.hasUniformSlices());
    ASSERT_TRUE(uneven.isTilted());
    for (const VolumeGeometry* g : {&uniform, &uneven}) {
        const VolumeGeometry fine = g->refined(factors, dims.z);
        expectSamePlaces(*g, fine, factors, dims);
        EXPECT_NEAR(fine.spacingI(), g->spacingI() / 2.0, 1e-12);
        EXPECT_NEAR(fine.spacingJ(), g->spacingJ(), 1e-12);
        EXPECT_NEAR(fine.sliceStep(), g->sliceStep() / 3.0, 1e-12);
        EXPECT_NEAR(fine.tiltDegrees(), g->tiltDegrees(), 1e-9);
        EXPECT_EQ(fine.refinement(), factors);
        EXPECT_EQ(fine.refined({2, 2, 2}, 10).refinement(), factors * 2);
    }
    // Each uneven gap is split into equal parts: 2 mm into 3 of 2/3, 7 mm into 3 of 7/3.
    const VolumeGeometry fine = uneven.refined(factors, dims.z);
    EXPECT_NEAR(fine.sliceGap(0), 2.0 / 3.0, 1e-9);
    EXPECT_NEAR(fine.sliceGap(4), 7.0 / 3.0, 1e-9);
    EXPECT_EQ(uniform.refinement(), glm::ivec3(1));
    EXPECT_THROW(uniform.refined({1, 1, 0}, 4), core::Error);
}

TEST(Oversampling, VolumeCarriesTheRefinedGeometry) {
    Volume v({3, 3, 3}, VoxelType::UInt8, VolumeGeometry::regular({1, 2, 3}, {1.0, 1.0, 4.0}));
    const Volume fine = oversampled(v, {1, 1, 4});
    EXPECT_EQ(fine.dims(), glm::ivec3(3, 3, 9));
    EXPECT_EQ(fine.geometry().refinement(), glm::ivec3(1, 1, 4));
    expectNear(fine.geometry().indexToPatient({2, 2, 8}), v.geometry().indexToPatient({2, 2, 2}));
}

// The monotone cubic along the slices (SliceInterpolation::MonotoneCubic): a field linear in k
// stays exactly linear (ends included), rows and columns stay linear, the slices themselves
// are kept.
TEST(OversamplingMonotone, ReproducesAFieldLinearAlongTheSlices) {
    const glm::ivec3 coarseDims(4, 3, 7);
    const auto linear = [](double i, double j, double k) { return 5.0 + 2.0 * i - j + 3.0 * k; };
    const Volume coarse = lw::test::makeFilledVolume<float>(
        coarseDims, [&](int i, int j, int k) { return linear(i, j, k); },
        VolumeGeometry::regular({0, 0, 0}, {0.5, 0.5, 5.0}));
    const glm::ivec3 factors(2, 1, 4);
    const Volume fine = oversampled(coarse, factors, 2, SliceInterpolation::MonotoneCubic);
    ASSERT_EQ(fine.dims(), oversampledDims(coarseDims, factors));
    for (int k = 0; k < fine.dims().z; ++k)
        for (int j = 0; j < fine.dims().y; ++j)
            for (int i = 0; i < fine.dims().x; ++i)
                ASSERT_NEAR(fine.storedValue(i, j, k),
                            linear(double(i) / factors.x, j, double(k) / factors.z), 1e-4)
                    << i << "," << j << "," << k;
}

// A step between two slices (air, then bone) rises monotonically from one plateau to the other,
// through the slices' own values, and never overshoots either: no value is invented, no speck
// of surface in the air.
TEST(OversamplingMonotone, AStepRisesWithoutOvershoot) {
    Volume v({1, 1, 6}, VoxelType::Int16);
    const std::int16_t values[] = {-1000, -1000, -900, 1100, 1200, 1200};
    std::copy(std::begin(values), std::end(values), v.dataAs<std::int16_t>());
    const Volume fine = oversampled(v, {1, 1, 8}, 1, SliceInterpolation::MonotoneCubic);
    ASSERT_EQ(fine.dims().z, 41);
    double previous = -1000.0;
    for (int k = 0; k < fine.dims().z; ++k) {
        const double value = fine.storedValue(0, 0, k);
        EXPECT_GE(value, previous) << k;
        EXPECT_LE(value, 1200.0) << k;
        if (k % 8 == 0) {
            EXPECT_EQ(value, double(values[k / 8])) << k;
        }
        previous = value;
    }
    // Flat where the plateau is flat: both ends of a segment between equal slices.
    EXPECT_EQ(fine.storedValue(0, 0, 4), -1000.0);
    EXPECT_EQ(fine.storedValue(0, 0, 36), 1200.0);
}

// Unlike linear interpolation the cubic has no crease at a slice: its slope on either side of
// slice 2 agrees (a smooth profile), where straight lines turn from one slope to the other.
TEST(OversamplingMonotone, HasNoCreaseAtASlice) {
    Volume v({1, 1, 5}, VoxelType::Float32);
    const float values[] = {0.0f, 1.0f, 4.0f, 9.0f, 16.0f}; // k^2: slopes 1, 3, 5, 7
    std::copy(std::begin(values), std::end(values), v.dataAs<float>());
    const int factor = 16;
    const Volume cubic = oversampled(v, {1, 1, factor}, 1, SliceInterpolation::MonotoneCubic);
    const Volume straight = oversampled(v, {1, 1, factor}, 1, SliceInterpolation::Linear);
    const auto slopes = [&](const Volume& f) {
        const int at = 2 * factor;
        const double before = (f.storedValue(0, 0, at) - f.storedValue(0, 0, at - 1)) * factor;
        const double after = (f.storedValue(0, 0, at + 1) - f.storedValue(0, 0, at)) * factor;
        return std::pair(before, after);
    };
    const auto [cubicBefore, cubicAfter] = slopes(cubic);
    EXPECT_NEAR(cubicBefore, cubicAfter, 0.6); // both near the tangent 2*3*5/8 = 3.75
    const auto [straightBefore, straightAfter] = slopes(straight);
    EXPECT_NEAR(straightBefore, 3.0, 1e-4);
    EXPECT_NEAR(straightAfter, 5.0, 1e-4);
}

} // namespace
} // namespace lw::volume
