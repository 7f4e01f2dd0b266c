#pragma once

// How clean a line drawing of a real CT is, where no analytic truth exists (issue 7's goals on
// real CT): the shaded panel's outer outline covered by the lines, the share of line pixels in
// speckle, and how far two methods' drawings agree. Distances are Chebyshev, as in the contour
// score (contour_score.h): a pixel's 8 neighbours are 1 px away.

#include "lw/render/pixel_mask.h"

#include <cstddef>

namespace lw::evaluation {

// The goals of issue 7 on real CT, each at every view measured.
inline constexpr double kOutlineCoverageGoal = 0.98; // outer outline within 1 px of a line
inline constexpr double kFragmentShareGoal = 0.02;   // at most, in groups under 10 px
inline constexpr int kFragmentPixels = 10;
inline constexpr double kAgreementGoalMethods13 = 0.98;
inline constexpr double kAgreementGoalMethods23 = 0.95; // method 2 with its along-segment test

// The outer outline of a filled silhouette (on = surface drawn, off = background): the on
// pixels with a 4-neighbour in the outer background, the off pixels 4-connected to the image's
// frame. Background enclosed by the surface (seen through a hole) is not outer, so its rim does
// not count; nor does the frame itself (a surface cut by the image's edge shows no outline
// there). The result is an 8-connected curve one pixel thick.
render::PixelMask outerOutline(const render::PixelMask& foreground);

struct OutlineCoverage {
    std::size_t outlinePixels = 0;
    std::size_t covered = 0; // outline pixels with a line pixel within the tolerance
    double coverage = 0.0;
};

// The share of `outline`'s pixels with a pixel of `lines` within `tolerancePx`. An empty
// drawing covers nothing (0). Throws core::Error when the outline is empty (a blank panel, so
// there is nothing to measure), the sizes differ or the tolerance is negative.
OutlineCoverage outlineCoverage(const render::PixelMask& outline, const render::PixelMask& lines,
                                int tolerancePx = 1);

struct FragmentShare {
    std::size_t linePixels = 0;
    std::size_t fragmentPixels = 0; // in 8-connected groups under the size
    double share = 0.0;             // 0 for an empty drawing (there is no speckle in it)
};

// The share of the line pixels lying in 8-connected groups of fewer than `minPixels` pixels:
// the speckle voxel-scale noise leaves. Throws core::Error for minPixels < 1.
FragmentShare fragmentShare(const render::PixelMask& lines, int minPixels = kFragmentPixels);

struct LineAgreement {
    std::size_t firstPixels = 0;
    std::size_t secondPixels = 0;
    double firstNearSecond = 0.0; // share of the first drawing's pixels near the second's
    double secondNearFirst = 0.0;
    double minimum = 0.0; // the smaller of the two: agreement must hold both ways
};

// How far two drawings of the same view agree: each direction is the share of one drawing's
// pixels with a pixel of the other within `tolerancePx`. A blank drawing agrees with nothing,
// itself included (0 both ways): two methods that both fail to draw must not pass. Throws
// core::Error when the sizes differ or the tolerance is negative.
LineAgreement lineAgreement(const render::PixelMask& first, const render::PixelMask& second,
                            int tolerancePx = 1);

} // namespace lw::evaluation
