// Volume, VolumeGeometry and BrickGrid on synthetic data.
#include "lw/core/error.h"
#include "lw/volume/bricks.h"
#include "lw/volume/volume.h"
#include "lw/volume/volume_geometry.h"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <numeric>
#include <random>

namespace lw::volume {
namespace {

constexpr double kTol = 1e-9;

void expectNear(glm::dvec3 a, glm::dvec3 b, double tol = kTol) {
    EXPECT_NEAR(a.x, b.x, tol);
    EXPECT_NEAR(a.y, b.y, tol);
    EXPECT_NEAR(a.z, b.z, tol);
}

// ---------------------------------------------------------------- Volume

TEST(Volume, TypesSizesAndTypedAccess) {
    for (VoxelType type :
         {VoxelType::UInt8, VoxelType::Int16, VoxelType::UInt16, VoxelType::Float32}) {
        Volume v({3, 4, 5}, type);
        EXPECT_EQ(v.voxelCount(), 60u);
        EXPECT_EQ(v.byteSize(), 60u * voxelSize(type));
        EXPECT_EQ(v.voxelType(), type);
        EXPECT_FALSE(v.isEmpty());
        EXPECT_EQ(v.index(2, 3, 4), 59u);
    }
    Volume v({2, 2, 2}, VoxelType::Int16);
    EXPECT_NO_THROW(v.dataAs<std::int16_t>());
    EXPECT_THROW(v.dataAs<std::uint16_t>(), core::Error);
    EXPECT_THROW(v.dataAs<float>(), core::Error);
    EXPECT_THROW(Volume({0, 2, 2}, VoxelType::UInt8), core::Error);
    EXPECT_THROW(Volume({2, -1, 2}, VoxelType::UInt8), core::Error);
    EXPECT_TRUE(Volume().isEmpty());
    EXPECT_EQ(parseVoxelType("i16"), VoxelType::Int16);
    EXPECT_EQ(parseVoxelType("float32"), VoxelType::Float32);
    EXPECT_THROW(parseVoxelType("int64"), core::Error);
}

TEST(Volume, StoredRangeFindsExtremesInAnySlice) {
    Volume v({7, 5, 9}, VoxelType::Int16);
    auto* p = v.dataAs<std::int16_t>();
    for (std::size_t i = 0; i < v.voxelCount(); ++i)
        p[i] = std::int16_t(i % 100);
    p[v.index(6, 4, 8)] = -1024; // last voxel
    p[v.index(3, 2, 4)] = 3071;  // middle slice
    const ValueRange r = v.storedRange();
    EXPECT_EQ(r.min, -1024);
    EXPECT_EQ(r.max, 3071);
    EXPECT_EQ(v.storedValue(3, 2, 4), 3071);
    EXPECT_EQ(v.storedValue(0, 0, 0), 0);
}

TEST(Volume, RealRangeAppliesMappingIncludingNegativeSlope) {
    Volume v({4, 1, 1}, VoxelType::UInt16);
    auto* p = v.dataAs<std::uint16_t>();
    p[0] = 0, p[1] = 100, p[2] = 4095, p[3] = 50;
    v.setValueMapping({1.0, -1024.0});
    EXPECT_DOUBLE_EQ(v.realRange().min, -1024.0);
    EXPECT_DOUBLE_EQ(v.realRange().max, 3071.0);
    v.setValueMapping({-2.0, 10.0});
    EXPECT_DOUBLE_EQ(v.realRange().min, 10.0 - 2.0 * 4095);
    EXPECT_DOUBLE_EQ(v.realRange().max, 10.0);
    EXPECT_DOUBLE_EQ(v.valueMapping().toStored(v.valueMapping().toReal(77.0)), 77.0);
}

TEST(Volume, HistogramCountsEveryVoxelInTheRightBin) {
    Volume v({10, 10, 1}, VoxelType::UInt8);
    auto* p = v.dataAs<std::uint8_t>();
    // 10 zeros, 20 ones, 30 twos, 40 threes.
    for (int i = 0; i < 100; ++i)
        p[i] = std::uint8_t(i < 10 ? 0 : i < 30 ? 1 : i < 60 ? 2 : 3);
    v.setValueMapping({10.0, 5.0}); // real values 5, 15, 25, 35
    const Histogram h = v.histogram(4);
    ASSERT_EQ(h.counts.size(), 4u);
    EXPECT_DOUBLE_EQ(h.min, 5.0);
    EXPECT_DOUBLE_EQ(h.binWidth, 7.5);
    EXPECT_EQ(h.counts[0], 10u);
    EXPECT_EQ(h.counts[1], 20u);
    EXPECT_EQ(h.counts[2], 30u);
    EXPECT_EQ(h.counts[3], 40u);
    EXPECT_EQ(std::accumulate(h.counts.begin(), h.counts.end(), std::uint64_t(0)), 100u);
    EXPECT_TRUE(v.histogram(0).counts.empty());
}

TEST(Volume, CloneIsDeepAndKeepsMetadata) {
    Volume v({3, 3, 3}, VoxelType::Float32, VolumeGeometry::regular({1, 2, 3}, {0.5, 0.5, 2.0}));
    auto* p = v.dataAs<float>();
    for (std::size_t i = 0; i < v.voxelCount(); ++i)
        p[i] = float(i) * 0.25f;
    v.setValueMapping({2.0, 1.0});
    v.setDescription("phantom");
    Volume c = v.clone();
    EXPECT_EQ(c.dims(), v.dims());
    EXPECT_EQ(c.voxelType(), VoxelType::Float32);
    EXPECT_NE(c.data(), v.data());
    EXPECT_EQ(std::memcmp(c.data(), v.data(), v.byteSize()), 0);
    c.dataAs<float>()[5] = -9.0f;
    EXPECT_FLOAT_EQ(v.dataAs<float>()[5], 1.25f);
    EXPECT_EQ(c.description(), "phantom");
    EXPECT_DOUBLE_EQ(c.valueMapping().slope, 2.0);
    expectNear(c.geometry().origin(), {1, 2, 3});
    EXPECT_DOUBLE_EQ(c.geometry().sliceStep(), 2.0);
}

// ---------------------------------------------------------------- VolumeGeometry

TEST(VolumeGeometry, RegularGridMapsIndices) {
    const auto g =
        VolumeGeometry::regular({10, 20, 30}, {0.5, 0.75, 2.0}, {0, 1, 0}, {-1, 0, 0}, {0, 0, 1});
    expectNear(g.indexToPatient({0, 0, 0}), {10, 20, 30});
    expectNear(g.indexToPatient({2, 4, 3}), {10 - 3.0, 20 + 1.0, 36});
    expectNear(g.spacing(), {0.5, 0.75, 2.0});
    EXPECT_NEAR(g.tiltDegrees(), 0.0, 1e-9);
    EXPECT_TRUE(g.hasUniformSlices());
    EXPECT_TRUE(g.sliceOffsets().empty());
    const glm::dmat4 a = g.affine();
    const glm::dvec4 p = a * glm::dvec4(2, 4, 3, 1);
    expectNear(glm::dvec3(p), g.indexToPatient({2, 4, 3}));
    // Axes given unnormalised come back as unit vectors.
    const auto h = VolumeGeometry::regular({0, 0, 0}, {1, 1, 1}, {3, 0, 0}, {0, 2, 0}, {0, 0, 5});
    expectNear(h.axisI(), {1, 0, 0});
    expectNear(h.indexToPatient({1, 1, 1}), {1, 1, 1});
}

TEST(VolumeGeometry, UniformSlicePositionsBecomeAUniformStep) {
    std::vector<glm::dvec3> positions;
    for (int k = 0; k < 6; ++k)
        positions.push_back({-100, -120, 40 + 2.5 * k});
    const auto g = VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 0.7, 0.8, positions);
    EXPECT_TRUE(g.sliceOffsets().empty());
    EXPECT_NEAR(g.sliceStep(), 2.5, 1e-12);
    EXPECT_NEAR(g.tiltDegrees(), 0.0, 1e-9);
    for (int k = 0; k < 6; ++k)
        expectNear(g.indexToPatient({0, 0, double(k)}), positions[std::size_t(k)]);
    expectNear(g.indexToPatient({10, 20, 1}), {-100 + 7.0, -120 + 16.0, 42.5});
}

TEST(VolumeGeometry, UnevenSlicesKeepEveryPosition) {
    const std::vector<glm::dvec3> positions = {{0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {0, 0, 6}};
    const auto g = VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 1.0, 1.0, positions);
    EXPECT_FALSE(g.hasUniformSlices());
    ASSERT_EQ(g.sliceOffsets().size(), 4u);
    EXPECT_DOUBLE_EQ(g.sliceOffset(2), 3.0);
    EXPECT_DOUBLE_EQ(g.sliceOffset(2.5), 4.5);
    EXPECT_DOUBLE_EQ(g.sliceGap(0), 1.0);
    EXPECT_DOUBLE_EQ(g.sliceGap(2), 3.0);
    EXPECT_DOUBLE_EQ(g.sliceStep(), 2.0); // mean
    for (int k = 0; k < 4; ++k)
        expectNear(g.indexToPatient({0, 0, double(k)}), positions[std::size_t(k)]);
    const glm::dmat3 j = g.jacobian(2.5);
    expectNear(j[2], {0, 0, 3});
    expectNear(g.jacobian(0.2)[2], {0, 0, 1});
    expectNear(j[0], {1, 0, 0});

    const VolumeGeometry sub = g.subStack(1, 3);
    expectNear(sub.origin(), positions[1]);
    ASSERT_EQ(sub.sliceOffsets().size(), 3u);
    EXPECT_DOUBLE_EQ(sub.sliceOffsets()[1], 2.0);
    EXPECT_DOUBLE_EQ(sub.sliceOffsets()[2], 5.0);
    expectNear(sub.indexToPatient({0, 0, 2}), positions[3]);
}

TEST(VolumeGeometry, GantryTiltOf18Point5Degrees) {
    const double t = 18.5 * M_PI / 180.0;
    // Tilted image rows, slices still advancing along the table (z): the GE HiSpeed case.
    const glm::dvec3 axisI(1, 0, 0), axisJ(0, std::cos(t), -std::sin(t));
    std::vector<glm::dvec3> positions;
    for (int k = 0; k < 5; ++k)
        positions.push_back({-50, -60, 5.0 * k});
    const auto g = VolumeGeometry::fromSlicePositions(axisI, axisJ, 0.49, 0.49, positions);
    EXPECT_NEAR(g.tiltDegrees(), 18.5, 1e-9);
    EXPECT_TRUE(g.isTilted());
    EXPECT_NEAR(g.sliceStep(), 5.0, 1e-12);
    EXPECT_NEAR(g.sliceStepAlongNormal(), 5.0 * std::cos(t), 1e-12);
    expectNear(g.stackAxis(), {0, 0, 1});
    expectNear(g.sliceNormal(), {0, std::sin(t), std::cos(t)});
    expectNear(g.indexToPatient({10, 20, 3}), positions[3] + 10 * 0.49 * axisI + 20 * 0.49 * axisJ);
    const glm::dmat3 j = g.jacobian(1.0);
    expectNear(j[1], 0.49 * axisJ);
    expectNear(j[2], {0, 0, 5});
    const auto sub = g.subStack(2, 2);
    expectNear(sub.origin(), positions[2]);
    EXPECT_NEAR(sub.tiltDegrees(), 18.5, 1e-9);
}

TEST(VolumeGeometry, SingleSliceAndInvalidStacks) {
    const auto g =
        VolumeGeometry::fromSlicePositions({0, 1, 0}, {0, 0, -1}, 1, 1, {{5, 6, 7}}, 3.0);
    expectNear(g.stackAxis(), glm::cross(glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1)));
    EXPECT_DOUBLE_EQ(g.sliceStep(), 3.0);
    EXPECT_THROW(VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 1, 1, {}), core::Error);
    EXPECT_THROW(
        VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 1, 1, {{1, 1, 1}, {1, 1, 1}}),
        core::Error);
}

// ---------------------------------------------------------------- BrickGrid

template <typename T>
Volume randomVolume(glm::ivec3 dims, VoxelType type, unsigned seed, int lo, int hi) {
    Volume v(dims, type);
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> dist(lo, hi);
    T* p = v.dataAs<T>();
    for (std::size_t i = 0; i < v.voxelCount(); ++i)
        p[i] = T(dist(rng));
    return v;
}

void checkGrid(const Volume& v, glm::ivec3 brickCells) {
    SCOPED_TRACE("brick " + std::to_string(brickCells.x) + "x" + std::to_string(brickCells.y) +
                 "x" + std::to_string(brickCells.z));
    const BrickGrid grid = BrickGrid::build(v, brickCells);
    const glm::ivec3 cells = v.dims() - 1;
    const glm::ivec3 gs = grid.gridSize();
    ASSERT_EQ(grid.bricks().size(), std::size_t(gs.x) * gs.y * gs.z);
    for (int a = 0; a < 3; ++a)
        EXPECT_EQ(gs[a], (cells[a] + std::min(brickCells[a], cells[a]) - 1) /
                             std::min(brickCells[a], cells[a]));
    std::vector<int> covered(std::size_t(cells.x) * cells.y * cells.z, 0);
    for (const Brick& b : grid.bricks()) {
        for (int a = 0; a < 3; ++a) {
            ASSERT_GE(b.cellBegin[a], 0);
            ASSERT_LE(b.cellEnd[a], cells[a]);
            ASSERT_LT(b.cellBegin[a], b.cellEnd[a]);
            ASSERT_LE(b.cellCount()[a], brickCells[a]);
        }
        double lo = 1e300, hi = -1e300;
        for (int z = b.cellBegin.z; z <= b.cellEnd.z; ++z)
            for (int y = b.cellBegin.y; y <= b.cellEnd.y; ++y)
                for (int x = b.cellBegin.x; x <= b.cellEnd.x; ++x) {
                    lo = std::min(lo, v.storedValue(x, y, z));
                    hi = std::max(hi, v.storedValue(x, y, z));
                }
        EXPECT_EQ(double(b.minValue), lo);
        EXPECT_EQ(double(b.maxValue), hi);
        for (int z = b.cellBegin.z; z < b.cellEnd.z; ++z)
            for (int y = b.cellBegin.y; y < b.cellEnd.y; ++y)
                for (int x = b.cellBegin.x; x < b.cellEnd.x; ++x)
                    ++covered[std::size_t(x) +
                              std::size_t(cells.x) * (std::size_t(y) + std::size_t(cells.y) * z)];
        // Read box: the corners plus one gradient voxel, clamped.
        for (int a = 0; a < 3; ++a) {
            EXPECT_EQ(b.readBegin()[a], std::max(b.cellBegin[a] - 1, 0));
            EXPECT_EQ(b.readEnd(v.dims())[a], std::min(b.cellEnd[a] + 2, v.dims()[a]));
        }
    }
    for (int count : covered)
        ASSERT_EQ(count, 1) << "every cell must belong to exactly one brick";
    for (double iso : {-5.0, 0.5, 17.0, 100.0, 199.5, 250.0}) {
        std::vector<int> expected;
        for (std::size_t i = 0; i < grid.bricks().size(); ++i) {
            const Brick& b = grid.bricks()[i];
            if (double(b.minValue) < iso && iso <= double(b.maxValue))
                expected.push_back(int(i));
        }
        EXPECT_EQ(grid.activeBricks(iso), expected);
    }
}

TEST(BrickGrid, PartitionAndMinMaxMatchBruteForce) {
    // 34x33x12 voxels = 33x32x11 cells: brick sizes below, at and above 32 and odd remainders.
    const Volume v8 = randomVolume<std::uint8_t>({34, 33, 12}, VoxelType::UInt8, 7, 0, 200);
    for (int s : {1, 7, 8, 9, 31, 32, 33})
        checkGrid(v8, glm::ivec3(s));
    checkGrid(v8, {5, 32, 2});
    const Volume v16 = randomVolume<std::int16_t>({19, 10, 23}, VoxelType::Int16, 11, -1024, 3000);
    for (int s : {1, 8, 9, 33})
        checkGrid(v16, glm::ivec3(s));
}

TEST(BrickGrid, OneBrickIsTheWholeVolume) {
    Volume v = randomVolume<float>({9, 8, 7}, VoxelType::Float32, 3, -100, 100);
    v.dataAs<float>()[v.index(8, 7, 6)] = 1000.0f; // the far corner belongs to the last cell
    const BrickGrid grid = BrickGrid::build(v, {64, 64, 64});
    ASSERT_EQ(grid.bricks().size(), 1u);
    EXPECT_EQ(grid.bricks()[0].cellEnd, glm::ivec3(8, 7, 6));
    EXPECT_EQ(grid.bricks()[0].maxValue, 1000.0f);
    EXPECT_EQ(grid.bricks()[0].minValue, float(v.storedRange().min));
    EXPECT_EQ(grid.activeBricks(999.0), std::vector<int>{0});
    EXPECT_TRUE(grid.activeBricks(1000.5).empty());
}

TEST(BrickGrid, ExtractionOverOneBrickDoesNotScanIt) {
    Volume v = randomVolume<float>({9, 8, 7}, VoxelType::Float32, 3, -100, 100);
    // One brick: the whole volume, bounds not read from the voxels, so it may hold any surface
    // (the extraction's own pass finds an empty one).
    for (const glm::ivec3 cells : {glm::ivec3(8, 7, 6), glm::ivec3(64)}) {
        const BrickGrid grid = BrickGrid::forExtraction(v, cells);
        ASSERT_EQ(grid.bricks().size(), 1u);
        EXPECT_EQ(grid.bricks()[0].cellBegin, glm::ivec3(0));
        EXPECT_EQ(grid.bricks()[0].cellEnd, glm::ivec3(8, 7, 6));
        EXPECT_EQ(grid.brickCells(), glm::ivec3(8, 7, 6));
        for (double iso : {-1e30, -100.0, 0.0, 100.5, 1e30})
            EXPECT_EQ(grid.activeBricks(iso), std::vector<int>{0}) << iso;
    }
    // More than one brick: build()'s grid, min and max scanned.
    v.dataAs<float>()[v.index(8, 7, 6)] = 1000.0f;
    const BrickGrid split = BrickGrid::forExtraction(v, {4, 7, 6});
    const BrickGrid built = BrickGrid::build(v, {4, 7, 6});
    ASSERT_EQ(split.bricks().size(), built.bricks().size());
    for (std::size_t b = 0; b < split.bricks().size(); ++b) {
        EXPECT_EQ(split.bricks()[b].minValue, built.bricks()[b].minValue);
        EXPECT_EQ(split.bricks()[b].maxValue, built.bricks()[b].maxValue);
    }
    EXPECT_EQ(split.bricks().back().maxValue, 1000.0f);
    EXPECT_TRUE(split.activeBricks(1000.5).empty());
    EXPECT_TRUE(BrickGrid::forExtraction(Volume({10, 10, 1}, VoxelType::UInt8), {8, 8, 8})
                    .bricks()
                    .empty());
}

TEST(BrickGrid, FlatVolumeHasNoCells) {
    const Volume v({10, 10, 1}, VoxelType::UInt8);
    EXPECT_TRUE(BrickGrid::build(v, {8, 8, 8}).bricks().empty());
}

} // namespace
} // namespace lw::volume
