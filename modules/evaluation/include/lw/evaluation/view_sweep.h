#pragma once

#include <cstdint>
#include <vector>

namespace lw::evaluation {

// A view direction in the convention of render::CameraSetup (degrees; the eye direction from the
// box centre is (sin az cos el, -cos az cos el, sin el)).
struct View {
    double azimuthDeg = 0.0;
    double elevationDeg = 0.0;
    bool operator==(const View&) const = default;
};

// The 6 faces, 12 edges and 8 corners of a cube seen from its centre.
inline constexpr int kCubeViewCount = 26;
// The default sweep: the cube's 26 directions and 6 seeded random ones.
inline constexpr int kDefaultSweepViewCount = 32;
inline constexpr std::uint32_t kDefaultSweepSeed = 20261123;

// `count` views spread over the sphere, so an accuracy score holds at every view rather than at
// a chosen one: first the directions toward the cube's 6 face centres (the standard views,
// poles included), 12 edge midpoints and 8 corners, then directions uniform on the sphere drawn
// from `seed` (std::mt19937's raw output, the same on every platform). Angles are rounded to
// 0.1 degree so that `accuracy --view AZ,EL` repeats any view of the sweep exactly; az is in
// (-180, 180] and is 0 at the poles. Throws core::Error for count < 1.
std::vector<View> viewSweep(int count = kDefaultSweepViewCount,
                            std::uint32_t seed = kDefaultSweepSeed);

} // namespace lw::evaluation
