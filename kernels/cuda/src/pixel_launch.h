#pragma once

// The 2D launch over a width x height image, one thread a pixel: tuning's pixel blocks
// (32 x 8, a warp along a row), as many as cover the image. Method 3's resolve and compose, the
// stroke pruning's unions and bridges.
// Internal: CUDA types allowed.

#include "dispatch.h"
#include "tuning.h"

#include <cstddef>

namespace lw::kernels::cuda {

struct PixelLaunch {
    dim3 grid, block;
};

inline PixelLaunch pixelLaunch(int width, int height) {
    return {dim3(dispatch::blocksFor(std::size_t(width), tuning::kPixelBlockX),
                 dispatch::blocksFor(std::size_t(height), tuning::kPixelBlockY)),
            dim3(tuning::kPixelBlockX, tuning::kPixelBlockY)};
}

} // namespace lw::kernels::cuda
