#pragma once

// Stroke pruning's groups of line pixels as a union-find over pixel labels: the rules the CUDA
// kernels run once per pixel in parallel (kernels/cuda/src/stroke_kernels.cuh), and that a test
// runs pixel by pixel on the host against PixelMask's search. The CPU back-ends' search
// (PixelMask, modules/render/src/pixel_mask.cpp) applies the same rules in raster order to labels
// that number the mask's runs (a row's consecutive line pixels).
//
// A group is what PixelMask::removeComponentsSmallerThan calls one: line pixels joined through
// steps of Chebyshev distance <= reach (reach 1: 8-connected; reach 2: a one-pixel gap bridged).
// Labels are pixel indices y * width + x; every line pixel's label points to a line pixel of its
// group with an index no larger than its own, so following labels ends at the group's smallest
// index, its root:
//
//     pixel:  0  1  2  3  4  5          a label is the pixel itself (a root) or an ancestor
//     label:  0  0  .  1  3  .          with a smaller index (a hook or a halving step puts one
//                                       there), so a label read while another thread changes
//                                       it still leads to the root, and no cycle can form.
//
// Each pixel unites itself with the line pixels among its earlier neighbours (the rows above
// within reach, and the pixels to its left in its own row): every pair of neighbours is united
// once, by the later of the two.

#include "lw/kernels/host_device.h"

#include <cstddef>
#include <cstdint>

namespace lw::kernels {

inline constexpr std::uint32_t kNotAStrokePixel = 0xffffffffu;

// Compare-and-swap on a label: atomic on the device, plain on the host (the host runs in
// sequence). Returns the label as it was.
struct LabelCompareAndSwap {
    LW_HOST_DEVICE std::uint32_t operator()(std::uint32_t* label, std::uint32_t expected,
                                            std::uint32_t value) const {
#if defined(__CUDA_ARCH__)
        return atomicCAS(label, expected, value);
#else
        const std::uint32_t old = *label;
        if (old == expected)
            *label = value;
        return old;
#endif
    }
};

// The root of `pixel`'s group, halving the path on the way (each visited label skips to its
// grandparent): a long stroke hooked pixel by pixel is a chain as long as the stroke, and
// without this every find would walk it. A halving store only ever lowers a non-root's label to
// another ancestor, so it cannot undo a concurrent hook (hooks change roots only, by CAS). The
// device runs these as plain loads and stores racing with other threads' (the ECL-CC pattern):
// any value read is an ancestor, which is all the walk needs. (Relaxed atomics instead cost
// method 3's frame with visibility off a quarter on the H100, 0.54 -> 0.69 ms: they bypass the L1.)
LW_HOST_DEVICE inline std::uint32_t strokeRoot(std::uint32_t* labels, std::uint32_t pixel) {
    std::uint32_t parent = labels[pixel];
    if (parent == pixel)
        return pixel;
    std::uint32_t previous = pixel;
    for (;;) {
        const std::uint32_t grandparent = labels[parent];
        if (grandparent >= parent) // parent is a root (labels never point up)
            return parent;
        labels[previous] = grandparent;
        previous = parent;
        parent = grandparent;
    }
}

// The root of `pixel`'s group once every union is done, when no thread writes a label (the
// launches after the unions): a plain walk, without halving, so that only reads meet.
LW_HOST_DEVICE inline std::uint32_t settledStrokeRoot(const std::uint32_t* labels,
                                                      std::uint32_t pixel) {
    std::uint32_t root = pixel;
    for (std::uint32_t parent = labels[root]; parent < root; parent = labels[root])
        root = parent;
    return root;
}

// Joins the groups of line pixels `a` and `b`: the larger root is hooked onto the smaller, by
// compare-and-swap, so only a label that is still a root changes. When another thread hooked
// that root first, the swap fails and returns its new parent, and the join goes on from there.
template <typename CompareAndSwap>
LW_HOST_DEVICE void uniteStrokes(std::uint32_t* labels, std::uint32_t a, std::uint32_t b,
                                 CompareAndSwap compareAndSwap) {
    a = strokeRoot(labels, a);
    b = strokeRoot(labels, b);
    while (a != b) {
        if (a < b) {
            const std::uint32_t t = a;
            a = b;
            b = t;
        }
        const std::uint32_t old = compareAndSwap(labels + a, a, b);
        if (old == a)
            return;
        a = strokeRoot(labels, old);
        b = strokeRoot(labels, b);
    }
}

// Pixel (x, y) of a width x height mask (1 byte a pixel, non-zero: line): united with the line
// pixels among its earlier neighbours within `reach`.
template <typename CompareAndSwap>
LW_HOST_DEVICE void uniteWithEarlierNeighbours(const std::uint8_t* mask, std::uint32_t* labels,
                                               int width, int height, int reach, int x, int y,
                                               CompareAndSwap compareAndSwap) {
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
                uniteStrokes(labels, self, other, compareAndSwap);
        }
    }
}

// Closing a one-pixel gap between two stroke ends. Pruning joins a stroke across a one-pixel gap
// (reach 2); where the gap lies between two stroke ends, the pixel between them is drawn too, so
// a contour that a method draws with one-pixel breaks (method 2's rays near grazing, a line
// crossing a pixel corner) reads as one stroke and not as dashes. Pixel P (off) bridges when:
//
//     . . . . .        - its eight neighbours hold exactly two line pixels A and B, two apart
//     . . . . .          (not neighbours of each other), so P is the only link between them;
//     A P B . .        - P is their midpoint, rounded down where they lie a knight's move apart
//     . . . . .          (A + B - 2P has components 0 or 1), so one pixel bridges a gap, not two;
//     . . . . .        - A and B are stroke ends: each has at most one line neighbour.
//
// Two lines passing each other two pixels apart have no ends there, and a line's side or corner
// brings more than two neighbours into P's ring, so neither is joined.
LW_HOST_DEVICE inline bool isLinePixel(const std::uint8_t* mask, int width, int height, int x,
                                       int y) {
    return x >= 0 && y >= 0 && x < width && y < height &&
           mask[std::size_t(y) * std::size_t(width) + std::size_t(x)] != 0;
}

LW_HOST_DEVICE inline int lineNeighbourCount(const std::uint8_t* mask, int width, int height, int x,
                                             int y) {
    int count = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
            count += (dx != 0 || dy != 0) && isLinePixel(mask, width, height, x + dx, y + dy);
    return count;
}

LW_HOST_DEVICE inline bool bridgesStrokeEnds(const std::uint8_t* mask, int width, int height, int x,
                                             int y) {
    if (x < 0 || y < 0 || x >= width || y >= height || isLinePixel(mask, width, height, x, y))
        return false;
    int found = 0, ax = 0, ay = 0, bx = 0, by = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            if ((dx == 0 && dy == 0) || !isLinePixel(mask, width, height, x + dx, y + dy))
                continue;
            if (++found > 2)
                return false;
            if (found == 1) {
                ax = dx;
                ay = dy;
            } else {
                bx = dx;
                by = dy;
            }
        }
    if (found != 2)
        return false;
    const int apartX = ax > bx ? ax - bx : bx - ax;
    const int apartY = ay > by ? ay - by : by - ay;
    if ((apartX > apartY ? apartX : apartY) != 2)
        return false;
    const int sumX = ax + bx, sumY = ay + by;
    if (sumX < 0 || sumX > 1 || sumY < 0 || sumY > 1)
        return false;
    return lineNeighbourCount(mask, width, height, x + ax, y + ay) <= 1 &&
           lineNeighbourCount(mask, width, height, x + bx, y + by) <= 1;
}

// After the bridges, the 8-connected pieces under half the stroke length go too: the gap keeps a
// contour drawn in dashes alive until its end-to-end breaks are bridged, but it also keeps the
// dots that noise leaves a pixel or two beside a longer stroke (a doubled terrace rim). Half the
// length, measured on the five CT series of docs/BENCHMARKS.md: the whole length (10 px) also
// drops real outline pieces, and the agreement of the methods falls furthest.
LW_HOST_DEVICE inline int minPiecePixels(int minStrokePixels) {
    return minStrokePixels / 2;
}

} // namespace lw::kernels
