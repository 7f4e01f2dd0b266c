#pragma once

// Thin walls sliding between thick slices: the arithmetic shared by the CPU
// (volume/slice_bridging.h) and the CUDA back-end (kernels/cuda/thick_slice_field_cuda.h), so that
// both raise the thick-slice field the same, bit for bit (every expression in the same order and
// precision; nvcc builds without contraction).
//
// Where a thin wall (a skull's top) runs shallow to the slices, its cut in slice k and its cut in
// slice k + 1 lie side by side in plane, overlapping little or not at all. Interpolating the two
// slices' signed distances point by point is negative between the cuts at every depth, so the
// wall breaks into one lip per slice (slits and ridge lines in the drawing). Here the cut is taken
// to slide straight from one slice's place to the other's:
//
//   slice k      .....######.....     u: the line through pixel x across the nearer contour
//                  x  |<-w0->|        (its distance gradient); each slice's cut on that line is
//   slice k+1   ##..............      an interval [lo, hi]: the near edge at -d along the
//               |w1|                  slice's own gradient, the far edge w (the wall's width,
//                                     read from one sample of the same slice) beyond it.
//
// At depth t between the slices the interval is [(1 - t) lo0 + t lo1, (1 - t) hi0 + t hi1], and
// x (at 0 on u) lies min(-lo, hi) inside it. The field is raised to that where it is larger,
// never lowered, and only where both cuts are thin walls, both slices have a contour within the
// limit and their gradients are near parallel (the same wall in both). Walls up to `widthMm` are
// slid whole; the raise fades out over walls up to half as wide again (kThinShellFade).

#include "lw/kernels/host_device.h"
#include "lw/kernels/slice_field_rules.h"

#include <cstddef>
#include <cstdint>

namespace lw::kernels {

// One pair of neighbouring slices of the thick-slice field (int16, 1/stepsPerMm mm, x fastest)
// and what the bridge needs to know of them.
struct ThinShellSlices {
    const std::int16_t* lower = nullptr; // slice k
    const std::int16_t* upper = nullptr; // slice k + 1
    int width = 0, height = 0;
    float pixelsPerMmI = 1.0f, pixelsPerMmJ = 1.0f;
    float mmPerStep = 1.0f / 128.0f; // the field's unit
    float gradientScaleI = 1.0f;     // a central difference (steps) to mm per mm, along i
    float gradientScaleJ = 1.0f;     // and along j
    float stepsPerMm = 128.0f;
    float limitSteps = 0.0f; // the field's value at its distance limit (storedSliceLimit)
    float widthMm = 0.0f;    // the widest wall bridged
};

// The slices' constants, made from the same doubles by the host code of either back-end (so the
// floats are the same): reciprocals, so that the pixels' arithmetic multiplies.
LW_HOST_DEVICE inline ThinShellSlices thinShellSlices(int width, int height, double spacingI,
                                                      double spacingJ, double stepsPerMm,
                                                      double limitMm, double widthMm) {
    ThinShellSlices s;
    s.width = width;
    s.height = height;
    s.pixelsPerMmI = float(1.0 / spacingI);
    s.pixelsPerMmJ = float(1.0 / spacingJ);
    s.mmPerStep = float(1.0 / stepsPerMm);
    s.gradientScaleI = float(1.0 / (2.0 * spacingI * stepsPerMm));
    s.gradientScaleJ = float(1.0 / (2.0 * spacingJ * stepsPerMm));
    s.stepsPerMm = float(stepsPerMm);
    s.limitSteps = storedSliceLimit(limitMm, stepsPerMm);
    s.widthMm = float(widthMm);
    return s;
}

// The two cuts' intervals on the line u through one pixel (mm along u, the pixel at 0).
struct ThinShellCuts {
    float lowerLo, lowerHi, upperLo, upperHi;
    float weight; // the share of the raise: 1 for walls up to widthMm, less as they fade out
};

// Gradients of a signed distance have length 1; where the central difference is much shorter
// the pixel sits on a ridge between two contours and the direction means nothing.
inline constexpr float kThinShellMinGradient = 0.5f;
// The two slices' gradients must be within about 30 degrees of parallel or antiparallel.
inline constexpr float kThinShellMinAlignment = 0.866f;
// Walls wider than widthMm fade out over this share of it: a wall `over` mm wider is raised by
// 1 - over / (kThinShellFade * widthMm) of the slid wall's raise. Where the rule stopped at
// widthMm, a wall about that wide (its width read at each pixel) was slid at some pixels and left
// pinched at their neighbours, which drew rows of pixel-sized beads along the slices (the demo's
// skull top, walls of about 11 mm in the slice plane).
inline constexpr float kThinShellFade = 0.5f;

// One slice's central differences at an inner pixel, in mm per mm (a signed distance's gradient,
// not yet of unit length).
LW_HOST_DEVICE inline void thinShellDifferences(const std::int16_t* slice, const ThinShellSlices& s,
                                                int x, int y, float& gx, float& gy) {
    const int v = y * s.width + x;
    gx = float(int(slice[v + 1]) - int(slice[v - 1])) * s.gradientScaleI;
    gy = float(int(slice[v + s.width]) - int(slice[v - s.width])) * s.gradientScaleJ;
}

// (gx, gy) made of unit length; false on a ridge (much shorter than a distance's gradient).
LW_HOST_DEVICE inline bool thinShellUnit(float& gx, float& gy) {
    const float length = sqrtf(gx * gx + gy * gy);
    if (!(length >= kThinShellMinGradient))
        return false;
    const float inverse = 1.0f / length;
    gx = gx * inverse;
    gy = gy * inverse;
    return true;
}

// A slice's distance (stored units) at (fx, fy) pixels, bilinear; false outside the slice.
LW_HOST_DEVICE inline bool thinShellSample(const std::int16_t* slice, const ThinShellSlices& s,
                                           float fx, float fy, float& value) {
    if (!(fx >= 0.0f && fy >= 0.0f && fx <= float(s.width - 1) && fy <= float(s.height - 1)))
        return false;
    const int x0 = int(fx) < s.width - 2 ? int(fx) : s.width - 2;
    const int y0 = int(fy) < s.height - 2 ? int(fy) : s.height - 2;
    const float u = fx - float(x0), w = fy - float(y0);
    const int v = y0 * s.width + x0;
    const float top = (1.0f - u) * float(slice[v]) + u * float(slice[v + 1]);
    const float bottom = (1.0f - u) * float(slice[v + s.width]) + u * float(slice[v + s.width + 1]);
    value = (1.0f - w) * top + w * bottom;
    return true;
}

// One slice's cut on its own gradient's line through (x, y): the near edge at -d (mm), the far
// edge a wall's width beyond, the width read at widthMm past the near edge: there the distance
// is -(widthMm - wall) when the wall is thinner, and wall - widthMm (to the far edge) when it is
// wider but under twice as wide. `weight`: 1 up to widthMm, then fading out (kThinShellFade).
// False where the wall is wider than that or unreadable.
LW_HOST_DEVICE inline bool thinShellCut(const std::int16_t* slice, const ThinShellSlices& s, int x,
                                        int y, float gx, float gy, float& near, float& far,
                                        float& weight) {
    near = -float(slice[y * s.width + x]) * s.mmPerStep;
    const float reach = near + s.widthMm;
    float beyond;
    if (!thinShellSample(slice, s, float(x) + reach * gx * s.pixelsPerMmI,
                         float(y) + reach * gy * s.pixelsPerMmJ, beyond))
        return false;
    if (beyond > 0.0f) { // still inside: wider than widthMm
        const float over = beyond * s.mmPerStep;
        const float fade = kThinShellFade * s.widthMm;
        if (!(over < fade))
            return false;
        far = reach + over;
        weight = 1.0f - over / fade;
        return true;
    }
    const float wall = beyond * s.mmPerStep + s.widthMm;
    far = near + (wall > 0.0f ? wall : 0.0f);
    weight = 1.0f;
    return true;
}

// Whether a pixel whose two slices hold lowerD and upperD (stored units) may lie in a pinch:
// within the limit of a contour in both (the stored limit is a whole number of steps), and not
// inside both (the field is inside at every depth there already). In integers and without a
// branch, so that the CPU's loop over a row of pixels is vector code: about nine pixel-gaps in
// ten are not candidates, and a test with branches was half the pass.
LW_HOST_DEVICE inline bool thinShellCandidate(int lowerD, int upperD, int limitSteps) {
    return ((lowerD < 0) | (upperD < 0)) & (lowerD > -limitSteps) & (lowerD < limitSteps) &
           (upperD > -limitSteps) & (upperD < limitSteps);
}

// Whether `slice` is inside at the middle of the other slice's cut, `middle` mm along that
// slice's unit gradient (gx, gy) from (x, y). False where the place lies outside the slice.
LW_HOST_DEVICE inline bool thinShellInsideAt(const std::int16_t* slice, const ThinShellSlices& s,
                                             int x, int y, float gx, float gy, float middle) {
    float value;
    return thinShellSample(slice, s, float(x) + middle * gx * s.pixelsPerMmI,
                           float(y) + middle * gy * s.pixelsPerMmJ, value) &&
           value >= 0.0f;
}

// A pixel outside both cuts with the cuts on either side of it (the gradients apart) lies where
// one wall slid across it -- or in the gap between two walls whose nearer one changes from one
// slice to the next (where the gap's middle moves). Sliding would put a wall into that gap. The
// two differ in what each slice holds where the other's cut is: where one wall slid, nothing
// (the wall has left); in a gap, the other wall, which stays. Whether either slice is inside at
// the middle of the other's cut. (A looser test, either slice nearer than half the two cuts'
// distance to a contour there, also took slides the thin-slice drawings show: CT_AVM's recall
// fell by 0.012 against 0.002.)
LW_HOST_DEVICE inline bool thinShellGapBetweenWalls(const ThinShellSlices& s, int x, int y,
                                                    float lgx, float lgy, float ugx, float ugy,
                                                    float lowerMiddle, float upperMiddle) {
    return thinShellInsideAt(s.upper, s, x, y, lgx, lgy, lowerMiddle) ||
           thinShellInsideAt(s.lower, s, x, y, ugx, ugy, upperMiddle);
}

// Both cuts on the nearer slice's gradient line through the inner pixel (x, y), from the two
// slices' unit gradients: the other slice's interval flips where its gradient points the other
// way. False where the two are not near parallel (not one wall), the pixel is outside both cuts
// on the same side of them (the field already moves the near faces straight there), it lies in
// the gap between two walls (thinShellGapBetweenWalls), or a wall is too wide (thinShellCut).
// The cuts' weight is the smaller of the two walls'.
LW_HOST_DEVICE inline bool thinShellCuts(const ThinShellSlices& s, int x, int y, float lowerD,
                                         float upperD, float lgx, float lgy, float ugx, float ugy,
                                         ThinShellCuts& cuts) {
    const float alignment = lgx * ugx + lgy * ugy;
    if (!(fabsf(alignment) >= kThinShellMinAlignment))
        return false;
    const bool flip = alignment < 0.0f;
    if (!flip && lowerD < 0.0f && upperD < 0.0f)
        return false;
    float lowerNear, lowerFar, upperNear, upperFar, lowerWeight, upperWeight;
    if (!thinShellCut(s.lower, s, x, y, lgx, lgy, lowerNear, lowerFar, lowerWeight) ||
        !thinShellCut(s.upper, s, x, y, ugx, ugy, upperNear, upperFar, upperWeight))
        return false;
    cuts.weight = lowerWeight < upperWeight ? lowerWeight : upperWeight;
    if (flip && lowerD < 0.0f && upperD < 0.0f &&
        thinShellGapBetweenWalls(s, x, y, lgx, lgy, ugx, ugy, 0.5f * (lowerNear + lowerFar),
                                 0.5f * (upperNear + upperFar)))
        return false;
    if (fabsf(lowerD) <= fabsf(upperD)) {
        cuts.lowerLo = lowerNear;
        cuts.lowerHi = lowerFar;
        cuts.upperLo = flip ? -upperFar : upperNear;
        cuts.upperHi = flip ? -upperNear : upperFar;
    } else {
        cuts.upperLo = upperNear;
        cuts.upperHi = upperFar;
        cuts.lowerLo = flip ? -lowerFar : lowerNear;
        cuts.lowerHi = flip ? -lowerNear : lowerFar;
    }
    return true;
}

// A depth inside the slid interval (mm) in steps, within the limit, not yet rounded.
LW_HOST_DEVICE inline float thinShellLimitedSteps(const ThinShellSlices& s, float insideMm) {
    const float steps = insideMm * s.stepsPerMm;
    return steps < s.limitSteps ? (steps > -s.limitSteps ? steps : -s.limitSteps) : s.limitSteps;
}

// Whether roundHalfAway(limited) > voxel, without rounding: the values that round above a whole
// number v are those from v + 0.5 on where v >= 0 (v + 0.5 rounds up, away from 0) and those
// above v + 0.5 where v < 0 (there v + 0.5 rounds down to v). Exact, as v + 0.5 is a float for
// every stored value; most voxels the bridge looks at are not raised, and this spares their
// rounding.
LW_HOST_DEVICE inline bool roundsAbove(float limited, int voxel) {
    const float half = float(voxel) + 0.5f;
    return voxel >= 0 ? limited >= half : limited > half;
}

// The slid interval at depth t (0 < t < 1): how far the pixel lies inside it (mm).
LW_HOST_DEVICE inline float thinShellInside(const ThinShellCuts& cuts, float t) {
    const float lo = (1.0f - t) * cuts.lowerLo + t * cuts.upperLo;
    const float hi = (1.0f - t) * cuts.lowerHi + t * cuts.upperHi;
    return -lo < hi ? -lo : hi;
}

// Where the two cuts are not flipped, both intervals' near edges are the slices' own -d, so at
// depth t the pixel lies at most -lo(t) = (1 - t) d0 + t d1 inside, whatever the far edges (the
// straight field between the slices: the cuts' walls can only make it less). Whether that bound
// is above a voxel between: where it is not, the slid wall cannot raise the pixel, and neither
// gradient's length, the alignment nor the cuts need be found. The same floats as
// raiseToSlidWall's (the steps, their limit and rounding are monotone; a faded raise is a share
// of that), so leaving such pixels out changes nothing.
LW_HOST_DEVICE inline bool nearEdgesMayRaise(const ThinShellSlices& s, const std::int16_t* between,
                                             std::size_t plane, std::size_t at, int factor,
                                             float lowerD, float upperD) {
    const float lowerLo = -lowerD * s.mmPerStep, upperLo = -upperD * s.mmPerStep;
    for (int step = 1; step < factor; ++step) {
        const float t = float(step) / float(factor);
        const float lo = (1.0f - t) * lowerLo + t * upperLo;
        if (roundsAbove(thinShellLimitedSteps(s, -lo),
                        int(between[plane * std::size_t(step - 1) + at])))
            return true;
    }
    return false;
}

// The slices between a gap's two raised, at one pixel (`at` within a plane), to the wall slid
// from one cut to the other -- by the cuts' weight of the way where the walls fade out: `between`
// is the first slice after the gap's lower one, `plane` the voxels a slice, `factor` the steps
// from one slice to the next. Never lowers a voxel (a share of a raise is a raise).
LW_HOST_DEVICE inline void raiseToSlidWall(std::int16_t* between, std::size_t plane, std::size_t at,
                                           int factor, const ThinShellSlices& s,
                                           const ThinShellCuts& cuts) {
    for (int step = 1; step < factor; ++step) {
        const float t = float(step) / float(factor);
        float limited = thinShellLimitedSteps(s, thinShellInside(cuts, t));
        std::int16_t& voxel = between[plane * std::size_t(step - 1) + at];
        if (cuts.weight < 1.0f)
            limited = float(voxel) + cuts.weight * (limited - float(voxel));
        if (roundsAbove(limited, int(voxel)))
            voxel = std::int16_t(roundHalfAway(limited));
    }
}

// One inner pixel (x, y) of a gap that passed thinShellCandidate, its two slices holding lowerD
// and upperD: the slices between raised where the pixel lies between two thin cuts of one wall
// (thinShellCuts). The cheap tests first, each leaving out only pixels the full rule leaves
// alone: from the central differences alone, a pair outside both whose gradients do not point
// apart (never flipped, so on the same side) and a pair not flipped whose near edges cannot raise
// a voxel (nearEdgesMayRaise). Of the demo's 0.66 M candidates about a fifth pass them.
LW_HOST_DEVICE inline void bridgeThinShellCandidate(const ThinShellSlices& s, std::int16_t* between,
                                                    std::size_t plane, int factor, int x, int y,
                                                    float lowerD, float upperD) {
    const std::size_t at = std::size_t(y) * std::size_t(s.width) + std::size_t(x);
    float lgx, lgy, ugx, ugy;
    thinShellDifferences(s.lower, s, x, y, lgx, lgy);
    thinShellDifferences(s.upper, s, x, y, ugx, ugy);
    // The unit gradients' product has this sign wherever its size can pass the alignment test.
    const bool apart = lgx * ugx + lgy * ugy < 0.0f;
    if (!apart && ((lowerD < 0.0f && upperD < 0.0f) ||
                   !nearEdgesMayRaise(s, between, plane, at, factor, lowerD, upperD)))
        return;
    ThinShellCuts cuts{};
    if (!thinShellUnit(lgx, lgy) || !thinShellUnit(ugx, ugy) ||
        !thinShellCuts(s, x, y, lowerD, upperD, lgx, lgy, ugx, ugy, cuts))
        return;
    raiseToSlidWall(between, plane, at, factor, s, cuts);
}

// The same for any inner pixel: the candidate test first (of the demo's 7.1 M pixel-gaps about
// 0.66 M pass it).
LW_HOST_DEVICE inline void bridgeThinShellPixel(const ThinShellSlices& s, std::int16_t* between,
                                                std::size_t plane, int factor, int x, int y) {
    const int v = y * s.width + x;
    const int lowerD = s.lower[v], upperD = s.upper[v];
    if (thinShellCandidate(lowerD, upperD, int(s.limitSteps)))
        bridgeThinShellCandidate(s, between, plane, factor, x, y, float(lowerD), float(upperD));
}

} // namespace lw::kernels
