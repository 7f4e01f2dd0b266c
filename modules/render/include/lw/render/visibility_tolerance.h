#pragma once

// The depth tolerance of the two per-pixel visibility tests: method 3's colour pass
// (lw/kernels/zbuffer_rules.h resolvePixel) and method 1's resolve pass
// (SilhouetteGlRenderer). Both draw a line pixel when its depth is not behind the farthest
// surface depth of its 3x3 neighbourhood by more than this tolerance, so the two methods agree
// wherever they hold the same surface and the same contour.
//
// It is a share of the depth range that the volume's box spans for the camera: about one voxel
// of a 512-voxel-deep volume. It only absorbs float rounding between the surface and line
// buffers and the sampling of the surface near a contour; the steep depth at the contour itself
// is what the neighbourhood handles.

#include "lw/render/aabb.h"
#include "lw/render/camera.h"

namespace lw::render {

inline constexpr double kRelativeDepthTolerance = 0.002;

// The tolerance in depth keys (1 - NDC depth, method 3's z-buffers) for `camera` and `box`.
float depthKeyTolerance(const Camera& camera, const Aabb& box);

// The same in GL window depth ([0, 1], depth = (NDC + 1) / 2): half the key tolerance.
inline float windowDepthTolerance(const Camera& camera, const Aabb& box) {
    return 0.5f * depthKeyTolerance(camera, box);
}

} // namespace lw::render
