// CUDA-GL interop for method 3's GL texture (see gl_texture_interop.h).

#include "dispatch.h"
#include "lw/kernels/cuda/gl_texture_interop.h"

#include <GL/gl.h>
#include <cuda_gl_interop.h>

namespace lw::kernels::cuda {

GlTextureInterop::~GlTextureInterop() {
    detach();
}

CudaStatus GlTextureInterop::attach(unsigned texture, int width, int height) {
    if (m_resource && texture == m_texture && width == m_width && height == m_height)
        return CudaStatus::success();
    detach();
    if (texture == 0 || width <= 0 || height <= 0)
        return CudaStatus::failure(CudaStatus::Code::Failed, "cudaGraphicsGLRegisterImage",
                                   "no texture or an empty one");
    cudaGraphicsResource_t resource = nullptr;
    // Surface load/store: the compose kernel writes texels through a surface object.
    const cudaError_t error = cudaGraphicsGLRegisterImage(
        &resource, GLuint(texture), GL_TEXTURE_2D, cudaGraphicsRegisterFlagsSurfaceLoadStore);
    if (error != cudaSuccess) {
        // Not sticky, but left as the runtime's last error: the caller's host path would find it
        // at its next launch check (seen on the GPU without a GL context current).
        cudaGetLastError();
        return dispatch::statusOf(error, "cudaGraphicsGLRegisterImage");
    }
    m_resource = resource;
    m_texture = texture;
    m_width = width;
    m_height = height;
    return CudaStatus::success();
}

void GlTextureInterop::detach() {
    if (m_resource)
        cudaGraphicsUnregisterResource(static_cast<cudaGraphicsResource_t>(m_resource));
    m_resource = nullptr;
    m_texture = 0;
    m_width = m_height = 0;
}

} // namespace lw::kernels::cuda
