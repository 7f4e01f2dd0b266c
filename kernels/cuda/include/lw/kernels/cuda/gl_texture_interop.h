#pragma once

// Method 3 in the GUI without a host round trip: a GL texture registered with CUDA, so that the
// compose kernel (ZBufferCuda::resolveInto) writes the silhouette mask straight into the texture
// the panel draws. The texture is GL_TEXTURE_2D with GL_R8 storage of the frame's size; texel
// (x, y) is mask pixel (x, y), row 0 at the top as in PixelMask, value 0 or 1.
//
// Registration costs tens of milliseconds, so it is done once per texture; mapping (per frame,
// on the renderer's stream) microseconds. The GL context that owns the texture must be current
// on the calling thread for attach, every resolveInto and detach, and the registration must go
// before the texture is deleted (the destructor does it). Public header: no CUDA or GL types.

#include "lw/kernels/cuda/cuda_status.h"

namespace lw::kernels::cuda {

class GlTextureInterop {
public:
    GlTextureInterop() = default;
    ~GlTextureInterop();
    GlTextureInterop(const GlTextureInterop&) = delete;
    GlTextureInterop& operator=(const GlTextureInterop&) = delete;

    // Registers GL texture `texture` (width x height) for writes through a surface object;
    // nothing to do when it is registered already.
    CudaStatus attach(unsigned texture, int width, int height);
    // Drops the registration (needs the owning GL context current).
    void detach();

    bool attached() const { return m_resource != nullptr; }
    unsigned texture() const { return m_texture; }
    int width() const { return m_width; }
    int height() const { return m_height; }
    // The registered resource (cudaGraphicsResource_t), for the kernels' dispatch.
    void* resource() const { return m_resource; }

private:
    void* m_resource = nullptr;
    unsigned m_texture = 0;
    int m_width = 0, m_height = 0;
};

} // namespace lw::kernels::cuda
