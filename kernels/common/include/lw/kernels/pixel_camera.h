#pragma once

// Method 2's screen side, host+device: a patient point -> continuous pixel coordinates exactly as
// lw::render::Camera::project computes them, and the DDA of lw::render::rasterizeLine (one pixel
// per step along the major axis). The CPU renderer and the CUDA kernel draw the same pixels.

#include "lw/kernels/host_device.h"

#include <cmath>
#include <glm/glm.hpp>

namespace lw::kernels {

struct PixelCamera {
    glm::dvec3 eye{0.0}, right{1, 0, 0}, up{0, 1, 0}, forward{0, 0, 1};
    double halfWidth = 1.0, halfHeight = 1.0; // ortho: half extents; perspective: tan of half angles
    int width = 0, height = 0;
    bool orthographic = false;
};

LW_HOST_DEVICE inline glm::dvec2 projectPixel(const PixelCamera& c, glm::dvec3 world) {
    const glm::dvec3 v = world - c.eye;
    const double x = glm::dot(v, c.right);
    const double y = glm::dot(v, c.up);
    const double z = glm::dot(v, c.forward);
    double ndcX = 0.0, ndcY = 0.0;
    if (c.orthographic) {
        ndcX = x / c.halfWidth;
        ndcY = y / c.halfHeight;
    } else {
        ndcX = x / (z * c.halfWidth);
        ndcY = y / (z * c.halfHeight);
    }
    return {0.5 * (ndcX + 1.0) * c.width, 0.5 * (1.0 - ndcY) * c.height};
}

// A part of a segment, as parameters from a (0) to b (1).
struct SegmentSpan {
    double from = 0.0, to = 1.0;
};

// fn(x, y) for each pixel of the segment a -> b (pixel centres at x + 0.5) inside the
// width x height viewport: one pixel per step along the major axis. With `span`, only the steps
// whose parameter lies in it: a part of the segment is a subset of its whole line's pixels.
template <typename Fn>
LW_HOST_DEVICE inline void forEachLinePixel(glm::dvec2 a, glm::dvec2 b, int width, int height,
                                            Fn&& fn, SegmentSpan span = {}) {
    const glm::dvec2 delta = b - a;
    const double adx = delta.x < 0.0 ? -delta.x : delta.x, ady = delta.y < 0.0 ? -delta.y : delta.y;
    const double steps = adx > ady ? adx : ady;
    const int count = int(ceil(steps));
    for (int i = 0; i <= count; ++i) {
        const double t = count == 0 ? 0.0 : double(i) / double(count);
        if (t < span.from || t > span.to)
            continue;
        const glm::dvec2 p = a + t * delta;
        const int x = int(floor(p.x)), y = int(floor(p.y));
        if (x >= 0 && y >= 0 && x < width && y < height)
            fn(x, y);
    }
}

// Method 2's endpoint test (both back-ends): the part of a segment drawn from its endpoints'
// visibility. Both seen: all of it; neither: none. One: the visibility changes somewhere inside
// the segment, and the half next to the seen endpoint is the guess that is at most half a
// segment off. Drawing nothing there instead broke a contour at every endpoint whose ray grazes
// noise (short pieces that stroke pruning then drops: on the plastic head with 40 HU of noise,
// method 2 covered 0.952 of method 3's lines at the worst of 32 views, 0.964 with halves) and
// lost the rim of a sheet seen edge-on (0.960 of the outline, 0.995 with halves); drawing all of
// it drew hidden lines a segment long (analytic precision 0.987 at 32^3 against 1.000).
LW_HOST_DEVICE inline bool drawnSpanOfSegment(bool aVisible, bool bVisible, SegmentSpan& span) {
    span.from = aVisible ? 0.0 : 0.5;
    span.to = bVisible ? 1.0 : 0.5;
    return aVisible || bVisible;
}

} // namespace lw::kernels
