// CUDA-GL interop for method 1 (see gl_mesh_interop.h).

#include "dispatch.h"
#include "lw/kernels/cuda/gl_mesh_interop.h"
#include "lw/kernels/silhouette_segment.h"

#include <GL/gl.h>
#include <cuda_gl_interop.h>

namespace lw::kernels::cuda {

namespace {

// One thread per triangle: kept unless all three d lie beyond the margin on one side
// (mayHoldContour).
__global__ void lineCandidates(const glm::vec3* positions, const glm::vec3* normals,
                               const std::uint32_t* indices, std::uint32_t triangleCount,
                               glm::vec4 viewer, std::uint32_t* out, unsigned long long* counter) {
    const std::uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
    if (t >= triangleCount)
        return;
    const std::uint32_t v[3] = {indices[3 * std::size_t(t)], indices[3 * std::size_t(t) + 1],
                                indices[3 * std::size_t(t) + 2]};
    const glm::vec3 p[3] = {positions[v[0]], positions[v[1]], positions[v[2]]};
    const glm::vec3 n[3] = {normals[v[0]], normals[v[1]], normals[v[2]]};
    if (!mayHoldContour(p, n, viewer))
        return;
    const unsigned long long slot = atomicAdd(counter, 1ull);
    out[3 * slot] = v[0];
    out[3 * slot + 1] = v[1];
    out[3 * slot + 2] = v[2];
}

} // namespace

GlMeshInterop::~GlMeshInterop() {
    unregister();
    if (m_counter)
        cudaFree(m_counter);
}

CudaStatus GlMeshInterop::writeLineCandidates(const DeviceMeshView& mesh, glm::vec4 viewer,
                                              unsigned candidates, std::size_t generation,
                                              std::size_t& triangles) {
    const CudaStatus status = candidatesInto(mesh, viewer, candidates, generation, triangles);
    if (!status.ok())
        cudaGetLastError();
    return status;
}

CudaStatus GlMeshInterop::copy(const DeviceMeshView& mesh, const GlMeshBuffers& buffers) {
    const CudaStatus status = copyInto(mesh, buffers);
    if (!status.ok())
        cudaGetLastError();
    return status;
}

CudaStatus GlMeshInterop::candidatesInto(const DeviceMeshView& mesh, glm::vec4 viewer,
                                         unsigned candidates, std::size_t generation,
                                         std::size_t& triangles) {
    triangles = 0;
    if (!m_counter)
        LW_CUDA_TRY(cudaMalloc(&m_counter, sizeof(unsigned long long)), "cudaMalloc(counter)");
    if (!m_candidateResource || candidates != m_candidateName ||
        generation != m_candidateGeneration) {
        if (m_candidateResource)
            cudaGraphicsUnregisterResource(
                static_cast<cudaGraphicsResource_t>(m_candidateResource));
        m_candidateResource = nullptr;
        cudaGraphicsResource_t resource = nullptr;
        LW_CUDA_TRY(cudaGraphicsGLRegisterBuffer(&resource, GLuint(candidates),
                                                 cudaGraphicsRegisterFlagsWriteDiscard),
                    "cudaGraphicsGLRegisterBuffer(candidates)");
        m_candidateResource = resource;
        m_candidateName = candidates;
        m_candidateGeneration = generation;
    }
    cudaGraphicsResource_t resource = static_cast<cudaGraphicsResource_t>(m_candidateResource);
    LW_CUDA_TRY(cudaGraphicsMapResources(1, &resource, nullptr), "cudaGraphicsMapResources");
    void* target = nullptr;
    std::size_t size = 0;
    CudaStatus status =
        dispatch::statusOf(cudaGraphicsResourceGetMappedPointer(&target, &size, resource),
                           "cudaGraphicsResourceGetMappedPointer(candidates)");
    if (status.ok() && size < mesh.triangleCount * 3 * sizeof(std::uint32_t))
        status = CudaStatus::failure(CudaStatus::Code::Failed, "GL line candidates",
                                     "the candidate buffer is smaller than the mesh");
    if (status.ok())
        status = dispatch::statusOf(cudaMemsetAsync(m_counter, 0, sizeof(unsigned long long)),
                                    "cudaMemset(counter)");
    if (status.ok() && mesh.triangleCount > 0) {
        lineCandidates<<<dispatch::blocksFor(mesh.triangleCount, 256), 256>>>(
            mesh.positions, mesh.normals, mesh.indices, std::uint32_t(mesh.triangleCount), viewer,
            static_cast<std::uint32_t*>(target), m_counter);
        status = dispatch::checkLaunch("lineCandidates");
    }
    unsigned long long count = 0;
    if (status.ok())
        status = dispatch::statusOf(
            cudaMemcpy(&count, m_counter, sizeof count, cudaMemcpyDeviceToHost), "lineCandidates");
    const CudaStatus unmapped = dispatch::statusOf(
        cudaGraphicsUnmapResources(1, &resource, nullptr), "cudaGraphicsUnmapResources");
    LW_RETURN_IF_FAILED(status);
    LW_RETURN_IF_FAILED(unmapped);
    triangles = std::size_t(count);
    return CudaStatus::success();
}

void GlMeshInterop::unregister() {
    if (m_candidateResource)
        cudaGraphicsUnregisterResource(static_cast<cudaGraphicsResource_t>(m_candidateResource));
    m_candidateResource = nullptr;
    m_candidateName = 0;
    for (void*& resource : m_resources) {
        if (resource)
            cudaGraphicsUnregisterResource(static_cast<cudaGraphicsResource_t>(resource));
        resource = nullptr;
    }
    m_registered = GlMeshBuffers();
}

CudaStatus GlMeshInterop::copyInto(const DeviceMeshView& mesh, const GlMeshBuffers& buffers) {
    const bool stale = !m_resources[0] || buffers.positions != m_registered.positions ||
                       buffers.normals != m_registered.normals ||
                       buffers.indices != m_registered.indices ||
                       buffers.generation != m_registered.generation;
    if (stale) {
        unregister();
        const unsigned names[3] = {buffers.positions, buffers.normals, buffers.indices};
        for (int i = 0; i < 3; ++i) {
            cudaGraphicsResource_t resource = nullptr;
            LW_CUDA_TRY(cudaGraphicsGLRegisterBuffer(&resource, GLuint(names[i]),
                                                     cudaGraphicsRegisterFlagsWriteDiscard),
                        "cudaGraphicsGLRegisterBuffer");
            m_resources[i] = resource;
        }
        m_registered = buffers;
    }
    cudaGraphicsResource_t resources[3];
    for (int i = 0; i < 3; ++i)
        resources[i] = static_cast<cudaGraphicsResource_t>(m_resources[i]);
    dispatch::StageTimer timer;
    LW_RETURN_IF_FAILED(timer.start(nullptr));
    LW_CUDA_TRY(cudaGraphicsMapResources(3, resources, nullptr), "cudaGraphicsMapResources");
    const std::size_t bytes[3] = {mesh.vertexCount * sizeof(glm::vec3),
                                  mesh.vertexCount * sizeof(glm::vec3),
                                  mesh.triangleCount * 3 * sizeof(std::uint32_t)};
    const void* sources[3] = {mesh.positions, mesh.normals, mesh.indices};
    CudaStatus status;
    for (int i = 0; i < 3 && status.ok(); ++i) {
        void* target = nullptr;
        std::size_t size = 0;
        status =
            dispatch::statusOf(cudaGraphicsResourceGetMappedPointer(&target, &size, resources[i]),
                               "cudaGraphicsResourceGetMappedPointer");
        if (status.ok() && size < bytes[i])
            status = CudaStatus::failure(CudaStatus::Code::Failed, "GL mesh interop",
                                         "a GL buffer is smaller than the mesh (reserve it first)");
        if (status.ok() && bytes[i] > 0)
            status = dispatch::statusOf(
                cudaMemcpyAsync(target, sources[i], bytes[i], cudaMemcpyDeviceToDevice, nullptr),
                "cudaMemcpy(mesh -> GL)");
    }
    // Unmapped whatever happened: GL may not use a buffer CUDA still holds.
    const CudaStatus unmapped = dispatch::statusOf(
        cudaGraphicsUnmapResources(3, resources, nullptr), "cudaGraphicsUnmapResources");
    LW_RETURN_IF_FAILED(status);
    LW_RETURN_IF_FAILED(unmapped);
    LW_RETURN_IF_FAILED(timer.stop(nullptr));
    LW_CUDA_TRY(cudaStreamSynchronize(nullptr), "cudaMemcpy(mesh -> GL)");
    m_copyMs = timer.ms();
    return CudaStatus::success();
}

} // namespace lw::kernels::cuda
