#pragma once

// Stroke pruning's groups of line pixels as a union-find over pixel labels: the rules the CUDA
// kernels run once per pixel in parallel (kernels/cuda/src/stroke_kernels.cuh), and that a test
// runs pixel by pixel on the host against PixelMask's flood fill (which the CPU back-ends use).
//
// A group is what PixelMask::removeComponentsSmallerThan calls one: line pixels joined through
// steps of Chebyshev distance <= reach (reach 1: 8-connected; reach 2: a one-pixel gap bridged).
// Labels are pixel indices y * width + x; every line pixel's label points to a line pixel of its
// group with an index no larger than its own, so following labels ends at the group's smallest
// index, its root:
//
//     pixel:  0  1  2  3  4  5          labels only ever decrease (atomicMin), so a label read
//     label:  0  0  .  1  3  .          before another thread lowered it still names an ancestor.
//
// Each pixel unites itself with the line pixels among its earlier neighbours (the rows above
// within reach, and the pixels to its left in its own row): every pair of neighbours is united
// once, by the later of the two.

#include "lw/kernels/host_device.h"

#include <cstdint>

namespace lw::kernels {

inline constexpr std::uint32_t kNotAStrokePixel = 0xffffffffu;

// min-exchange on a label: atomic on the device, plain on the host (the host runs in sequence).
struct LabelMinExchange {
    LW_HOST_DEVICE std::uint32_t operator()(std::uint32_t* label, std::uint32_t value) const {
#if defined(__CUDA_ARCH__)
        return atomicMin(label, value);
#else
        const std::uint32_t old = *label;
        if (value < old)
            *label = value;
        return old;
#endif
    }
};

LW_HOST_DEVICE inline std::uint32_t strokeRoot(const std::uint32_t* labels, std::uint32_t pixel) {
    std::uint32_t parent = labels[pixel];
    while (parent != pixel) {
        pixel = parent;
        parent = labels[pixel];
    }
    return pixel;
}

// Joins the groups of line pixels `a` and `b`: the larger root is linked to the smaller. When
// another thread linked that root first, the exchange returns its new parent and the join goes
// on from there.
template <typename MinExchange>
LW_HOST_DEVICE void uniteStrokes(std::uint32_t* labels, std::uint32_t a, std::uint32_t b,
                                 MinExchange exchange) {
    for (;;) {
        a = strokeRoot(labels, a);
        b = strokeRoot(labels, b);
        if (a == b)
            return;
        if (a < b) {
            const std::uint32_t t = a;
            a = b;
            b = t;
        }
        const std::uint32_t old = exchange(labels + a, b);
        if (old == a)
            return;
        a = old;
    }
}

// Pixel (x, y) of a width x height mask (1 byte a pixel, non-zero: line): united with the line
// pixels among its earlier neighbours within `reach`.
template <typename MinExchange>
LW_HOST_DEVICE void uniteWithEarlierNeighbours(const std::uint8_t* mask, std::uint32_t* labels,
                                               int width, int height, int reach, int x, int y,
                                               MinExchange exchange) {
    const std::uint32_t self = std::uint32_t(y) * std::uint32_t(width) + std::uint32_t(x);
    if (x < 0 || y < 0 || x >= width || y >= height || !mask[self])
        return;
    for (int dy = -reach; dy <= 0; ++dy) {
        const int ny = y + dy;
        if (ny < 0)
            continue;
        const int lastDx = dy < 0 ? reach : -1;
        for (int dx = -reach; dx <= lastDx; ++dx) {
            const int nx = x + dx;
            if (nx < 0 || nx >= width)
                continue;
            const std::uint32_t other =
                std::uint32_t(ny) * std::uint32_t(width) + std::uint32_t(nx);
            if (mask[other])
                uniteStrokes(labels, self, other, exchange);
        }
    }
}

} // namespace lw::kernels
