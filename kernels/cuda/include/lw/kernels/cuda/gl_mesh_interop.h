#pragma once

// Method 1 on the GPU without a host round trip: the CUDA marching-cubes mesh copied device to
// device into the OpenGL buffers the geometry-shader pass draws (CUDA-GL interop). The buffers
// are registered with CUDA once and again only when GL reallocates their storage (registration
// costs tens of milliseconds; mapping per extraction microseconds). The GL context that owns the
// buffers must be current on the calling thread. Public header: no CUDA or GL types.

#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"

#include <cstddef>

namespace lw::kernels::cuda {

struct GlMeshBuffers {
    unsigned positions = 0; // GL buffer names; positions and normals 3 floats a vertex
    unsigned normals = 0;
    unsigned indices = 0;       // uint32, three a triangle
    std::size_t generation = 0; // changes when GL reallocated the storage
};

class GlMeshInterop {
public:
    GlMeshInterop() = default;
    ~GlMeshInterop();
    GlMeshInterop(const GlMeshInterop&) = delete;
    GlMeshInterop& operator=(const GlMeshInterop&) = delete;

    // Copies `mesh` into the buffers (each large enough: SilhouetteGlRenderer::reserveMesh).
    CudaStatus copy(const DeviceMeshView& mesh, const GlMeshBuffers& buffers);
    // Drops the registration (before the buffers are deleted; needs the GL context current).
    void unregister();
    double lastCopyMs() const { return m_copyMs; }

private:
    // copy()'s work; copy() drops a failure as the runtime's last error (an interop failure is
    // not sticky, but left there the caller's host fallback would report it at its first launch
    // check).
    CudaStatus copyInto(const DeviceMeshView& mesh, const GlMeshBuffers& buffers);

    void* m_resources[3] = {nullptr, nullptr, nullptr}; // cudaGraphicsResource_t
    GlMeshBuffers m_registered;
    double m_copyMs = 0.0;
};

} // namespace lw::kernels::cuda
