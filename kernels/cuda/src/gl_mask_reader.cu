// Host dispatch of GlMaskReader (gl_mask_reader.h; kernel in gl_mask_kernels.cuh).

#include "dispatch.h"
#include "gl_mask_kernels.cuh"
#include "lw/kernels/cuda/gl_mask_reader.h"
#include "lw/kernels/cuda/gl_texture_interop.h"
#include "pixel_launch.h"
#include "stroke_pruning.h"

#include <GL/gl.h>
#include <cuda_gl_interop.h>

namespace lw::kernels::cuda {

struct GlMaskReader::Impl {
    GlTextureInterop texture; // the colour texture, registered read-only
    dispatch::Stream stream;
    dispatch::DeviceBuffer<uchar4> colour;
    dispatch::DeviceBuffer<std::uint8_t> mask;
    StrokePruning pruning;
    MaskDownload download;

    // The texture's texels into `colour` (mapped on the stream: GL's drawing into it completes
    // first; unmapped whatever happened, as GL may not draw into a texture CUDA still holds).
    CudaStatus copyColour(cudaStream_t st) {
        auto resource = static_cast<cudaGraphicsResource_t>(texture.resource());
        const int width = texture.width(), height = texture.height();
        CudaStatus status = dispatch::statusOf(cudaGraphicsMapResources(1, &resource, st),
                                               "cudaGraphicsMapResources(colour texture)");
        if (!status.ok())
            return status;
        cudaArray_t array = nullptr;
        status = dispatch::statusOf(cudaGraphicsSubResourceGetMappedArray(&array, resource, 0, 0),
                                    "cudaGraphicsSubResourceGetMappedArray(colour texture)");
        const std::size_t rowBytes = std::size_t(width) * sizeof(uchar4);
        if (status.ok())
            status = dispatch::statusOf(cudaMemcpy2DFromArrayAsync(colour.data(), rowBytes, array,
                                                                   0, 0, rowBytes, height,
                                                                   cudaMemcpyDeviceToDevice, st),
                                        "cudaMemcpy2DFromArray(colour texture)");
        const CudaStatus unmapped =
            dispatch::statusOf(cudaGraphicsUnmapResources(1, &resource, st),
                               "cudaGraphicsUnmapResources(colour texture)");
        return status.ok() ? unmapped : status;
    }
};

GlMaskReader::GlMaskReader() : m_impl(std::make_unique<Impl>()) {}

GlMaskReader::~GlMaskReader() = default;

bool GlMaskReader::attached() const {
    return m_impl->texture.attached();
}

CudaStatus GlMaskReader::attach(unsigned texture, int width, int height) {
    return m_impl->texture.attach(texture, width, height, GlTextureAccess::ReadOnly);
}

void GlMaskReader::detach() {
    m_impl->texture.detach();
}

CudaStatus GlMaskReader::read(std::uint8_t backgroundRed, int minPixels, int gapPixels,
                              std::uint8_t* mask) {
    Impl& s = *m_impl;
    if (!s.texture.attached())
        return CudaStatus::failure(CudaStatus::Code::Failed, "GlMaskReader::read",
                                   "no texture attached");
    const int width = s.texture.width(), height = s.texture.height();
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    LW_RETURN_IF_FAILED(s.stream.create());
    LW_RETURN_IF_FAILED(s.colour.reserve(pixels, "cudaMalloc(colour)"));
    LW_RETURN_IF_FAILED(s.mask.reserve(pixels, "cudaMalloc(mask)"));
    cudaStream_t st = s.stream.get();
    const CudaStatus copied = s.copyColour(st);
    if (!copied.ok()) {
        cudaGetLastError();
        return copied;
    }
    const PixelLaunch launch = pixelLaunch(width, height);
    glmask::maskFromColour<<<launch.grid, launch.block, 0, st>>>(s.colour.data(), width, height,
                                                                 backgroundRed, s.mask.data());
    LW_CUDA_LAUNCHED("glmask::maskFromColour");
    LW_RETURN_IF_FAILED(s.pruning.run(s.mask.data(), width, height, minPixels, gapPixels, st));
    LW_RETURN_IF_FAILED(s.download.queue(s.mask.data(), pixels, st));
    LW_CUDA_TRY(cudaStreamSynchronize(st), "GlMaskReader::read");
    s.download.deliver(mask);
    return CudaStatus::success();
}

} // namespace lw::kernels::cuda
