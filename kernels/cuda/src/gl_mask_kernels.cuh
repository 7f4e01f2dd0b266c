#pragma once

// Kernel of GlMaskReader (gl_mask_reader.cu): a GL colour image to a line mask.

#include <cstddef>
#include <cstdint>

namespace lw::kernels::cuda::glmask {

// `rgba`: width x height texels copied from the GL texture, row 0 at the bottom. Mask pixel
// (x, y), row 0 at the top, is 1 where the texel's red differs from the background's.
__global__ void maskFromColour(const uchar4* rgba, int width, int height,
                               std::uint8_t backgroundRed, std::uint8_t* mask) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height)
        return;
    const std::size_t glRow = std::size_t(height - 1 - y);
    const uchar4 texel = rgba[glRow * std::size_t(width) + std::size_t(x)];
    mask[std::size_t(y) * std::size_t(width) + std::size_t(x)] = texel.x != backgroundRed ? 1 : 0;
}

} // namespace lw::kernels::cuda::glmask
