#pragma once

// The arithmetic of the thick-slice field (volume/slice_distance.h and volume/oversampling.h),
// shared by the CPU (lw_volume) and the CUDA back-end so that both make the same int16 field bit
// for bit: every expression here is evaluated in the same order and precision on both sides (nvcc
// builds without contraction, see kernels/cuda/CMakeLists.txt).
//
// The signed distance to a slice's iso contour. The contour points are the crossings of the iso
// value along rows and columns (where linear interpolation puts the contour in the slice):
//
//        x      x+1                 a row crossing lies on the row, at column x + t;
//   y    +---o---+                  a column crossing lies on the column, at row y + t;
//        |       |                  t = a / (a - b), a and b the values less the iso-value
//   y+1  o       +                  at the two pixels.
//
// A pixel's distance is the smallest over all crossings, found separably: within one row the
// nearest row crossing is the one nearest along the row (the row's distance is the same for all
// of them), so the squared distance to the row crossings is the minimum over rows r of
// scaleI * near(r)^2 + scaleJ * (y - r)^2 -- and likewise for the column crossings with the axes
// swapped. Minima are exact whatever order they are taken in, so a CPU that scans and a GPU that
// searches a window (both covering every crossing nearer than the limit) agree exactly.

#include "lw/kernels/host_device.h"

#include <cmath>
#include <cstdint>
#include <limits>

namespace lw::kernels {

// Where the straight line from `a` (at 0) to `b` (at 1) crosses zero; a and b of opposite signs
// (zero counts as inside, with the positive values).
LW_HOST_DEVICE inline bool crossesIso(float a, float b) {
    return (a >= 0.0f) != (b >= 0.0f);
}
LW_HOST_DEVICE inline float crossingOffset(float a, float b) {
    return a / (a - b);
}

// Whole pixels along an axis of `spacing` (mm) that cover `limitMm`, at most `length`: the rows
// and columns a pixel's minimum looks at. A crossing further away is beyond the limit.
LW_HOST_DEVICE inline int sliceDistanceReach(double limitMm, double spacing, int length) {
    const double cap = double(length > 1 ? length : 1);
    const double pixels = spacing > 0.0 ? floor(limitMm / spacing) + 1.0 : cap;
    return int(pixels < cap ? pixels : cap);
}

// The squared distance (mm^2) of one candidate: `near` pixels along one axis (scale: that axis's
// spacing squared) and `steps` whole pixels along the other.
LW_HOST_DEVICE inline float nearTerm(float scale, float near) {
    return scale * (near * near);
}
LW_HOST_DEVICE inline float stepTerm(float scale, int steps) {
    return scale * float(steps * steps);
}

// Steps rounded half away from zero (std::lround's rule). The whole part is taken as an int
// (the field's values are at most 32767 steps, so it is exact), which a CPU vectorises.
LW_HOST_DEVICE inline int roundedSteps(double scaled) {
    const int wholeSteps = static_cast<int>(scaled);
    const double fraction = scaled - double(wholeSteps);
    return wholeSteps + (fraction >= 0.5 ? 1 : 0) - (fraction <= -0.5 ? 1 : 0);
}

// The stored int16 of a distance: mm limited to `limitMm` (limitMm * stepsPerMm is at most
// 32767), signed (+ inside), in 1/stepsPerMm mm, rounded by roundedSteps.
LW_HOST_DEVICE inline std::int16_t storedSliceDistance(float squaredMm, bool inside, double limitMm,
                                                       double stepsPerMm) {
    const double mm = double(sqrtf(squaredMm));
    const double limited = mm < limitMm ? mm : limitMm;
    return std::int16_t(roundedSteps((inside ? limited : -limited) * stepsPerMm));
}

// The smallest float square whose distance reaches the limit: every squared distance of at least
// this much is stored as the limit (storedSliceDistance takes sqrtf, which is monotone), so a
// candidate that large can be left out of a minimum without changing any stored value. (Host
// code: the device takes it as an argument.)
inline float squaredReachingLimit(double limitMm) {
    float value = float(limitMm * limitMm);
    const auto reaches = [limitMm](float v) { return double(std::sqrt(v)) >= limitMm; };
    while (value > 0.0f && reaches(std::nextafter(value, 0.0f)))
        value = std::nextafter(value, 0.0f);
    while (!reaches(value))
        value = std::nextafter(value, std::numeric_limits<float>::infinity());
    return value;
}

// The stored value of a distance at the limit (storedSliceDistance's of limitMm, inside): what
// the field holds wherever a slice has no contour within the limit.
LW_HOST_DEVICE inline float storedSliceLimit(double limitMm, double stepsPerMm) {
    return float(roundedSteps(limitMm * stepsPerMm));
}

// Along the slices, the monotone cubic (volume/oversampling.h): Fritsch-Butland tangents (the
// harmonic mean of the two secants where they agree in sign, else 0), written without a branch so
// that the CPU's loop over a plane vectorises; the quotient is only used where both secants share
// a sign (their sum is then not zero).
LW_HOST_DEVICE inline float monotoneTangent(float before, float after) {
    const float product = before * after;
    const float sum = before + after;
    const float harmonic = 2.0f * product / (sum != 0.0f ? sum : 1.0f);
    return product > 0.0f ? harmonic : 0.0f;
}

// The cubic Hermite basis at t: the weights of y(k), m(k), y(k + 1), m(k + 1).
struct HermiteWeights {
    float y0, m0, y1, m1;
    LW_HOST_DEVICE explicit HermiteWeights(float t)
        : y0(2.0f * t * t * t - 3.0f * t * t + 1.0f), m0(t * t * t - 2.0f * t * t + t),
          y1(-2.0f * t * t * t + 3.0f * t * t), m1(t * t * t - t * t) {}
};

LW_HOST_DEVICE inline float hermiteBlend(const HermiteWeights& w, float y1, float m1, float y2,
                                         float m2) {
    return w.y0 * y1 + w.m0 * m1 + w.y1 * y2 + w.m1 * m2;
}

LW_HOST_DEVICE inline float linearBlend(float lower, float upperWeight, float upper) {
    return lower + upperWeight * (upper - lower);
}

// std::lround's rounding (halves away from zero), written out so that it inlines: the integer
// part by truncation and the fraction compared with one half -- both exact for the 8- and 16-bit
// ranges of the integer voxel types (a float holds every integer up to 2^24 and its fraction).
LW_HOST_DEVICE inline int roundHalfAway(float value) {
    const int whole = int(value);
    const float fraction = value - float(whole);
    return whole + int(fraction >= 0.5f) - int(fraction <= -0.5f);
}

} // namespace lw::kernels
