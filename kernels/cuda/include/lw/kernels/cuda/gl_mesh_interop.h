#pragma once

// Method 1 on the GPU without a host round trip: the CUDA marching-cubes mesh copied device to
// device into the OpenGL buffers the geometry-shader pass draws (CUDA-GL interop). The buffers
// are registered with CUDA once and again only when GL reallocates their storage (registration
// costs tens of milliseconds; mapping per frame microseconds). The GL context that owns the
// buffers must be current on the calling thread. Public header: no CUDA or GL types.

#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"

#include <cstddef>
#include <glm/glm.hpp>

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
    // Per frame: the triangles of `mesh` that can hold a silhouette segment for `viewer` (the eye
    // with w = 1, or the unit direction toward the viewer with w = 0) into the GL element buffer
    // `candidates` (three indices a triangle; `generation` changes when GL reallocated it); their
    // count. A triangle is left out only when all three d = N . (eye - B) lie clearly on one side
    // of 0 (beyond a rounding margin), so the geometry shader, which tests the sign again, emits
    // exactly what it emits for the whole mesh.
    CudaStatus writeLineCandidates(const DeviceMeshView& mesh, glm::vec4 viewer,
                                   unsigned candidates, std::size_t generation,
                                   std::size_t& triangles);
    // Drops the registration (before the buffers are deleted; needs the GL context current).
    void unregister();
    double lastCopyMs() const { return m_copyMs; }

private:
    // The two calls' work; the public ones drop a failure as the runtime's last error (an
    // interop failure is not sticky, but left there the caller's host fallback would report it
    // at its first launch check).
    CudaStatus copyInto(const DeviceMeshView& mesh, const GlMeshBuffers& buffers);
    CudaStatus candidatesInto(const DeviceMeshView& mesh, glm::vec4 viewer, unsigned candidates,
                              std::size_t generation, std::size_t& triangles);

    void* m_resources[3] = {nullptr, nullptr, nullptr}; // cudaGraphicsResource_t
    void* m_candidateResource = nullptr;
    unsigned m_candidateName = 0;
    std::size_t m_candidateGeneration = 0;
    unsigned long long* m_counter = nullptr; // device
    GlMeshBuffers m_registered;
    double m_copyMs = 0.0;
};

} // namespace lw::kernels::cuda
