// Thin walls sliding between thick slices (volume/slice_bridging.h): where a thin wall's cuts in
// two slices lie side by side, the shape-based field pinches it to nothing between them; the
// pass raises the slices between to the wall slid straight from one cut to the other.
#include "filled_volume.h"
#include "lw/core/error.h"
#include "lw/kernels/thin_shell_bridge.h"
#include "lw/volume/oversampling.h"
#include "lw/volume/phantom.h"
#include "lw/volume/slice_bridging.h"
#include "lw/volume/slice_distance.h"
#include "lw/volume/volume.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <gtest/gtest.h>
#include <vector>

namespace lw::volume {
namespace {

constexpr double kIso = 300.0;
constexpr double kPixelMm = 0.5;
constexpr double kSliceMm = 5.0;
constexpr double kLimitMm = kSliceMm; // one slice step, as the renderer limits it
constexpr double kThinWallMm = 6.0;
constexpr int kFactor = 4;

// Three slices of a wall along j, `widthMm` wide, its centre at 10 mm in slice 0 and `shiftMm`
// further along i in each next slice (a wall slanted across the slices), bone (1000) inside,
// water outside, with a pixel of partial volume at each edge.
Volume slantedWall(double widthMm, double shiftMm) {
    return lw::test::makeFilledVolume<std::int16_t>(
        {96, 8, 3},
        [&](int i, int, int k) {
            const double centre = 10.0 + shiftMm * k;
            const double inside = std::clamp(
                0.5 + (0.5 * widthMm - std::abs(i * kPixelMm - centre)) / kPixelMm, 0.0, 1.0);
            return std::lround(1000.0 * inside);
        },
        VolumeGeometry::regular({0, 0, 0}, {kPixelMm, kPixelMm, kSliceMm}));
}

// The shape-based field of `slices`, refined kFactor times along k: what the renderer draws
// before the bridge.
Volume refinedField(const Volume& slices) {
    Volume field({slices.dims().x, slices.dims().y, (slices.dims().z - 1) * kFactor + 1},
                 VoxelType::Int16, slices.geometry().refined({1, 1, kFactor}, slices.dims().z));
    writeSignedSliceDistance(slices, kIso, kLimitMm, kFactor, field, 1);
    refineBetweenSlices(field, kFactor, 1, SliceInterpolation::MonotoneCubic);
    return field;
}

double mm(const Volume& field, double iMm, int refinedSlice) {
    return field.dataAs<std::int16_t>()[field.index(int(std::lround(iMm / kPixelMm)), 4,
                                                    refinedSlice)] /
           kSliceDistanceStepsPerMm;
}

TEST(SliceBridging, SlidesAThinWallAcrossTheGapBetweenItsCuts) {
    // 2 mm wide, 5 mm further each slice: the cuts do not overlap.
    const Volume pointwise = refinedField(slantedWall(2.0, 5.0));
    Volume bridged = pointwise.clone();
    bridgeThinWalls(bridged, kFactor, kLimitMm, kThinWallMm, 1);
    // The iso contour runs 0.2 mm outside each edge (300 of the rim's 0-500 ramp over half a
    // millimetre): the cut is 2.4 mm wide. Half-way between slices 0 and 1 the wall lies at
    // 11.3-13.7 mm. Point by point the field is outside there at every depth (the pinch);
    // bridged, the wall's middle is 1.2 mm inside.
    EXPECT_LT(mm(pointwise, 12.5, kFactor / 2), 0.0);
    EXPECT_NEAR(mm(bridged, 12.5, kFactor / 2), 1.2, 0.05);
    EXPECT_NEAR(mm(bridged, 11.0, kFactor / 2), -0.3, 0.05);
    EXPECT_NEAR(mm(bridged, 14.0, kFactor / 2), -0.3, 0.05);
    // A quarter of the way, 10.05-12.45 mm (the pixel at 11.5 mm 0.95 mm inside); between
    // slices 1 and 2 the same as between 0 and 1, 5 mm on.
    EXPECT_NEAR(mm(bridged, 11.5, 1), 0.95, 0.05);
    EXPECT_NEAR(mm(bridged, 17.5, kFactor + kFactor / 2), 1.2, 0.05);
    // Far from the wall (beyond the limit) nothing changes.
    EXPECT_EQ(mm(bridged, 40.0, kFactor / 2), mm(pointwise, 40.0, kFactor / 2));
}

// Two walls 1 mm wide along j: one staying at 20 mm, the other at 30 mm in slice 0 sliding to
// 25 mm in slice 1 (and staying there in slice 2). Between slices 0 and 1 the gap between them
// narrows; a pixel in it at 23 mm is nearer the first in slice 0 and the second in slice 1.
Volume wallBesideASlidingOne() {
    return lw::test::makeFilledVolume<std::int16_t>(
        {96, 8, 3},
        [&](int i, int, int k) {
            const auto inside = [&](double centre) {
                return std::clamp(0.5 + (0.5 - std::abs(i * kPixelMm - centre)) / kPixelMm, 0.0,
                                  1.0);
            };
            return std::lround(1000.0 * (inside(20.0) + inside(k == 0 ? 30.0 : 25.0)));
        },
        VolumeGeometry::regular({0, 0, 0}, {kPixelMm, kPixelMm, kSliceMm}));
}

TEST(SliceBridging, PutsNoWallIntoTheGapBetweenTwoWalls) {
    const Volume pointwise = refinedField(wallBesideASlidingOne());
    Volume bridged = pointwise.clone();
    bridgeThinWalls(bridged, kFactor, kLimitMm, kThinWallMm, 1);
    // At 23 mm, in the gap, the gradients point apart: to the staying wall in slice 0 (2.3 mm
    // off) and to the sliding one in slice 1 (1.3 mm off). Sliding "one wall" from the first
    // cut to the second would cross the gap half-way between the slices; the field must stay
    // outside there, as it is point by point.
    for (const double gapMm : {22.0, 22.5, 23.0, 23.5}) {
        ASSERT_LT(mm(pointwise, gapMm, kFactor / 2), 0.0) << gapMm << " mm";
        EXPECT_LT(mm(bridged, gapMm, kFactor / 2), 0.0) << gapMm << " mm";
        EXPECT_LT(mm(bridged, gapMm, 1), 0.0) << gapMm << " mm";
        EXPECT_LT(mm(bridged, gapMm, kFactor - 1), 0.0) << gapMm << " mm";
    }
}

TEST(SliceBridging, NeverLowersTheFieldAndLeavesTheSlicesAsTheyAre) {
    const Volume pointwise = refinedField(slantedWall(2.0, 5.0));
    Volume bridged = pointwise.clone();
    bridgeThinWalls(bridged, kFactor, kLimitMm, kThinWallMm, 2);
    const std::int16_t* before = pointwise.dataAs<std::int16_t>();
    const std::int16_t* after = bridged.dataAs<std::int16_t>();
    const std::size_t plane = std::size_t(pointwise.dims().x) * std::size_t(pointwise.dims().y);
    std::size_t raised = 0;
    for (std::size_t v = 0; v < pointwise.voxelCount(); ++v) {
        ASSERT_GE(after[v], before[v]) << "voxel " << v;
        if ((v / plane) % kFactor == 0) {
            ASSERT_EQ(after[v], before[v]) << "slice voxel " << v;
        }
        raised += after[v] > before[v] ? 1 : 0;
    }
    EXPECT_GT(raised, 0u);
}

TEST(SliceBridging, FadesOutOverWallsALittleWiderThanTheWidest) {
    // Walls slid by their width and 1 mm more (the cuts apart, so point by point the wall pinches
    // half-way), from under kThinWallMm (6 mm) to past its fade (cuts of 6 to 9 mm): half-way
    // between the slices the slid wall's middle lies half its cut inside where the wall is slid
    // whole, and where it fades out it gets 1 - (cut - 6 mm) / 3 mm of that raise.
    struct Wall {
        double widthMm, raisedShare;
    };
    const double cutOverWall = 0.4; // the iso contour 0.2 mm outside each edge (first test)
    double previousRaise = 1e9;
    for (const Wall wall : {Wall{5.2, 1.0}, Wall{6.2, 0.8}, Wall{7.2, 7.0 / 15.0},
                            Wall{8.2, 2.0 / 15.0}, Wall{9.2, 0.0}}) {
        const double shiftMm = wall.widthMm + 1.0;
        const Volume pointwise = refinedField(slantedWall(wall.widthMm, shiftMm));
        Volume bridged = pointwise.clone();
        bridgeThinWalls(bridged, kFactor, kLimitMm, kThinWallMm, 1);
        const double middleMm = 10.0 + 0.5 * shiftMm;
        const double pixelMm = kPixelMm * std::round(middleMm / kPixelMm); // what mm() reads
        const double before = mm(pointwise, pixelMm, kFactor / 2);
        const double after = mm(bridged, pixelMm, kFactor / 2);
        const double slidWhole = 0.5 * (wall.widthMm + cutOverWall) - std::abs(pixelMm - middleMm);
        ASSERT_LT(before, 0.0) << wall.widthMm << " mm: pinched point by point";
        EXPECT_NEAR(after, before + wall.raisedShare * (slidWhole - before), 0.1)
            << wall.widthMm << " mm";
        if (wall.raisedShare == 0.0) {
            EXPECT_TRUE(std::equal(pointwise.dataAs<std::int16_t>(),
                                   pointwise.dataAs<std::int16_t>() + pointwise.voxelCount(),
                                   bridged.dataAs<std::int16_t>()))
                << wall.widthMm << " mm: past the fade, nothing raised";
        }
        EXPECT_LT(after - before, previousRaise) << wall.widthMm << " mm: the raise shrinks";
        previousRaise = after - before;
    }
}

TEST(SliceBridging, LeavesWallsWiderThanTheLimitAlone) {
    // 10 mm wide, 4 mm further each slice: a wall wider than kThinWallMm and its fade (9 mm),
    // which the pointwise field already moves straight (the cuts overlap); and the thin wall
    // bridged with a width of 0 (off).
    const Volume wide = refinedField(slantedWall(10.0, 4.0));
    Volume bridged = wide.clone();
    bridgeThinWalls(bridged, kFactor, kLimitMm, kThinWallMm, 1);
    EXPECT_TRUE(std::equal(wide.dataAs<std::int16_t>(),
                           wide.dataAs<std::int16_t>() + wide.voxelCount(),
                           bridged.dataAs<std::int16_t>()));
    const Volume thin = refinedField(slantedWall(2.0, 5.0));
    Volume off = thin.clone();
    bridgeThinWalls(off, kFactor, kLimitMm, 0.0, 1);
    EXPECT_TRUE(std::equal(thin.dataAs<std::int16_t>(),
                           thin.dataAs<std::int16_t>() + thin.voxelCount(),
                           off.dataAs<std::int16_t>()));
}

// The rule at every inner pixel with none of the pass's shortcuts (the candidate mask made in
// integers, the tests from the central differences before the gradients' lengths): the
// candidate test, both unit gradients, the cuts, the raise.
void bridgeByTheFullRule(Volume& field, int factor, double limitMm, double widthMm) {
    const glm::ivec3 dims = field.dims();
    kernels::ThinShellSlices s = kernels::thinShellSlices(
        dims.x, dims.y, field.geometry().spacingI(), field.geometry().spacingJ(),
        kSliceDistanceStepsPerMm, limitMm, widthMm);
    std::int16_t* voxels = field.dataAs<std::int16_t>();
    const std::size_t plane = std::size_t(dims.x) * std::size_t(dims.y);
    for (int gap = 0; gap < (dims.z - 1) / factor; ++gap) {
        s.lower = voxels + plane * std::size_t(gap * factor);
        s.upper = s.lower + plane * std::size_t(factor);
        std::int16_t* between = voxels + plane * std::size_t(gap * factor + 1);
        for (int y = 1; y + 1 < dims.y; ++y)
            for (int x = 1; x + 1 < dims.x; ++x) {
                const std::size_t at = std::size_t(y) * std::size_t(dims.x) + std::size_t(x);
                const float lowerD = float(s.lower[at]), upperD = float(s.upper[at]);
                float lgx, lgy, ugx, ugy;
                kernels::thinShellDifferences(s.lower, s, x, y, lgx, lgy);
                kernels::thinShellDifferences(s.upper, s, x, y, ugx, ugy);
                kernels::ThinShellCuts cuts{};
                if (kernels::thinShellCandidate(s.lower[at], s.upper[at], int(s.limitSteps)) &&
                    kernels::thinShellUnit(lgx, lgy) && kernels::thinShellUnit(ugx, ugy) &&
                    kernels::thinShellCuts(s, x, y, lowerD, upperD, lgx, lgy, ugx, ugy, cuts))
                    kernels::raiseToSlidWall(between, plane, at, factor, s, cuts);
            }
    }
}

// The CT phantom (1 mm) with every `thickness` slices averaged into one, as a scanner's thick
// reconstruction integrates them: a skull-like shell, thin walls slanted to the slices.
Volume thickCtPhantom(int thickness) {
    const Volume thin = makePhantom({128, 128, 128}, PhantomKind::Ct, 2);
    const std::int16_t* voxels = thin.dataAs<std::int16_t>();
    return lw::test::makeFilledVolume<std::int16_t>(
        {128, 128, 128 / thickness},
        [&](int i, int j, int k) {
            long sum = 0;
            for (int n = 0; n < thickness; ++n)
                sum += voxels[thin.index(i, j, k * thickness + n)];
            return std::lround(double(sum) / thickness);
        },
        VolumeGeometry::regular({0, 0, 0}, {1.0, 1.0, double(thickness)}));
}

class SliceBridgingShortcuts : public ::testing::TestWithParam<double> {};

TEST_P(SliceBridgingShortcuts, ChangeNothingOnAThickCtPhantom) {
    const double iso = GetParam();
    const Volume slices = thickCtPhantom(5);
    const double limitMm = 5.0;
    Volume pointwise({slices.dims().x, slices.dims().y, (slices.dims().z - 1) * 3 + 1},
                     VoxelType::Int16, slices.geometry().refined({1, 1, 3}, slices.dims().z));
    writeSignedSliceDistance(slices, iso, limitMm, 3, pointwise, 2);
    refineBetweenSlices(pointwise, 3, 2, SliceInterpolation::MonotoneCubic);
    Volume fast = pointwise.clone();
    bridgeThinWalls(fast, 3, limitMm, 10.0, 2);
    Volume full = pointwise.clone();
    bridgeByTheFullRule(full, 3, limitMm, 10.0);
    const std::int16_t* expected = full.dataAs<std::int16_t>();
    const std::int16_t* got = fast.dataAs<std::int16_t>();
    std::size_t raised = 0;
    for (std::size_t v = 0; v < full.voxelCount(); ++v) {
        ASSERT_EQ(got[v], expected[v]) << "voxel " << v;
        raised += expected[v] != pointwise.dataAs<std::int16_t>()[v] ? 1 : 0;
    }
    EXPECT_GT(raised, 100u) << "the phantom should hold thin walls the rule raises";
}

INSTANTIATE_TEST_SUITE_P(IsoValues, SliceBridgingShortcuts, ::testing::Values(150.0, 300.0, 700.0));

TEST(SliceBridging, RoundsAboveIsRoundingThenComparing) {
    // Whole numbers, halves and the floats either side of them, for voxels of both signs.
    std::vector<float> values;
    for (int n = -40; n <= 40; ++n)
        for (const float base : {float(n), float(n) + 0.5f, float(n) - 0.5f, float(n) + 0.25f})
            for (const float value :
                 {base, std::nextafter(base, -1e9f), std::nextafter(base, 1e9f)})
                values.push_back(value);
    for (int voxel = -30; voxel <= 30; ++voxel)
        for (const float value : values)
            ASSERT_EQ(kernels::roundsAbove(value, voxel), kernels::roundHalfAway(value) > voxel)
                << value << " against " << voxel;
}

TEST(SliceBridging, RefusesAFieldOfAnotherTypeOrSliceCount) {
    Volume floats({8, 8, 9}, VoxelType::Float32);
    EXPECT_THROW(bridgeThinWalls(floats, kFactor, kLimitMm, kThinWallMm), core::Error);
    Volume uneven({8, 8, 8}, VoxelType::Int16);
    EXPECT_THROW(bridgeThinWalls(uneven, kFactor, kLimitMm, kThinWallMm), core::Error);
}

} // namespace
} // namespace lw::volume
