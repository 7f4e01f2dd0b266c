// CUDA-GL interop for method 1 (see gl_mesh_interop.h).

#include "dispatch.h"
#include "lw/kernels/cuda/gl_mesh_interop.h"

#include <GL/gl.h>
#include <cuda_gl_interop.h>

namespace lw::kernels::cuda {

GlMeshInterop::~GlMeshInterop() {
    unregister();
}

CudaStatus GlMeshInterop::copy(const DeviceMeshView& mesh, const GlMeshBuffers& buffers) {
    const CudaStatus status = copyInto(mesh, buffers);
    if (!status.ok())
        cudaGetLastError();
    return status;
}

void GlMeshInterop::unregister() {
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
