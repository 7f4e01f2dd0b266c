#pragma once

#include "lw/render/pixel_mask.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

namespace lw::render {

// Draws a 2D segment between pixel-space points (pixel centres at x + 0.5) into `mask` with a
// DDA that sets one pixel per step along the major axis, clipped to the mask. Used by the CPU
// methods 2 and 3 so their line drawings are pixel-identical for identical segments.
inline void rasterizeLine(PixelMask& mask, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 delta = b - a;
    const double steps = std::max(std::abs(delta.x), std::abs(delta.y));
    const int count = int(std::ceil(steps));
    for (int i = 0; i <= count; ++i) {
        const double t = count == 0 ? 0.0 : double(i) / double(count);
        const glm::dvec2 p = a + t * delta;
        const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
        if (mask.contains(x, y))
            mask.set(x, y);
    }
}

} // namespace lw::render
