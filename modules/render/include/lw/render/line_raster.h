#pragma once

#include "lw/kernels/pixel_camera.h"
#include "lw/render/pixel_mask.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace lw::render {

// Draws a 2D segment between pixel-space points (pixel centres at x + 0.5) into `mask` with a
// DDA that sets one pixel per step along the major axis, clipped to the mask (kernels/common's
// forEachLinePixel, which the CUDA method 2 calls too). Used by the CPU
// methods 2 and 3 so their line drawings are pixel-identical for identical segments.
inline void rasterizeLine(PixelMask& mask, glm::dvec2 a, glm::dvec2 b) {
    kernels::forEachLinePixel(a, b, mask.width(), mask.height(),
                              [&](int x, int y) { mask.set(x, y); });
}

} // namespace lw::render
