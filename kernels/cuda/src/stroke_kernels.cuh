#pragma once

// Stroke pruning's kernels (dispatch in stroke_pruning.cu): the union-find rules are
// kernels/common's stroke_components.h. Four launches over the pixels: labels, unions, the
// groups' sizes, the short groups cleared; with a gap, two more: the stroke ends' bridges found,
// then drawn; then the first four again at reach 1 for the short pieces (stroke_pruning.cu).

#include "lw/kernels/stroke_components.h"

#include <cstddef>
#include <cstdint>

namespace lw::kernels::cuda::sk {

__global__ void initLabels(const std::uint8_t* mask, std::uint32_t pixels, std::uint32_t* labels,
                           std::uint32_t* sizes) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= pixels)
        return;
    labels[i] = mask[i] ? i : kNotAStrokePixel;
    sizes[i] = 0;
}

__global__ void uniteNeighbours(const std::uint8_t* mask, int width, int height, int reach,
                                std::uint32_t* labels) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    uniteWithEarlierNeighbours(mask, labels, width, height, reach, x, y, LabelCompareAndSwap{});
}

// Each line pixel counts itself at its group's root (all unions are done: the launch before
// finished). From here on the labels are only read (settledStrokeRoot): the unions' halving left
// the paths short, and plain loads that no store races with may be cached.
__global__ void countGroups(const std::uint8_t* mask, std::uint32_t pixels,
                            const std::uint32_t* labels, std::uint32_t* sizes) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= pixels || !mask[i])
        return;
    atomicAdd(sizes + settledStrokeRoot(labels, i), 1u);
}

__global__ void clearShortGroups(std::uint8_t* mask, std::uint32_t pixels,
                                 const std::uint32_t* labels, const std::uint32_t* sizes,
                                 std::uint32_t minPixels) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= pixels || !mask[i])
        return;
    if (sizes[settledStrokeRoot(labels, i)] < minPixels)
        mask[i] = 0;
}

// The stroke ends' bridges (bridgesStrokeEnds), found on the pruned mask into `bridges` (one word
// a pixel: the group sizes' buffer, free once the short groups are cleared) and then drawn, so no
// thread reads a pixel another has drawn in the same pass (the host finds all before it draws).
__global__ void findBridges(const std::uint8_t* mask, int width, int height,
                            std::uint32_t* bridges) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height)
        return;
    bridges[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
        bridgesStrokeEnds(mask, width, height, x, y) ? 1u : 0u;
}

__global__ void drawBridges(std::uint8_t* mask, std::uint32_t pixels,
                            const std::uint32_t* bridges) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i < pixels && bridges[i])
        mask[i] = 1;
}

// A mask already pruned into a GL texture's array (GL_R8: one byte a texel, row y = mask row y).
__global__ void copyToSurface(const std::uint8_t* mask, int width, int height,
                              cudaSurfaceObject_t target) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height)
        return;
    surf2Dwrite(mask[std::size_t(y) * std::size_t(width) + std::size_t(x)], target,
                x * int(sizeof(std::uint8_t)), y);
}

} // namespace lw::kernels::cuda::sk
