#pragma once

// Method 1's line mask without the host's read-back: the colour texture of its GL framebuffer
// (GL_RGBA8, row 0 at the bottom as GL draws) registered with CUDA, turned on the device into
// the mask (1 where red differs from the background's red, row 0 at the top as in PixelMask),
// its short strokes pruned there (StrokePruning), and only the result downloaded. It replaces
// glReadPixels with the host's flip and threshold (0.5 ms a 1024^2 frame on the H100 machine)
// and the pruner's upload (HostMaskPruner, the path when this one is unavailable).
//
// Registration costs tens of milliseconds, so it is done once per texture and size (a texture
// whose storage is re-specified must be registered again: attach() does it when the name or
// the size changed). The GL context that owns the texture must be current on the calling thread
// for attach, read and detach, and the registration must go before the texture is deleted (the
// destructor does it). Public header: no CUDA or GL types.

#include "lw/kernels/cuda/cuda_status.h"

#include <cstdint>
#include <memory>

namespace lw::kernels::cuda {

class GlMaskReader {
public:
    GlMaskReader();
    ~GlMaskReader();
    GlMaskReader(const GlMaskReader&) = delete;
    GlMaskReader& operator=(const GlMaskReader&) = delete;

    // Registers GL texture `texture` (width x height, GL_RGBA8) for reading; nothing to do when
    // it is registered already at that size.
    CudaStatus attach(unsigned texture, int width, int height);
    void detach();
    bool attached() const;

    // The attached texture as a mask into `mask` (width * height bytes, host memory), strokes
    // under `minPixels` dropped as StrokePruning::run drops them (minPixels <= 1: none). Returns
    // when `mask` is filled; on failure `mask` is left as it was.
    CudaStatus read(std::uint8_t backgroundRed, int minPixels, int gapPixels, std::uint8_t* mask);

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::kernels::cuda
