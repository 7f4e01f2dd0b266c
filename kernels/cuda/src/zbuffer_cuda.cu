// Host dispatch of method 3 on the GPU (kernels in zbuffer_kernels.cuh).

#include "dispatch.h"
#include "host_mesh_upload.h"
#include "lw/kernels/cuda/gl_texture_interop.h"
#include "lw/kernels/cuda/zbuffer_cuda.h"
#include "pixel_launch.h"
#include "stroke_pruning.h"
#include "tuning.h"
#include "zbuffer_kernels.cuh"

namespace lw::kernels::cuda {

using dispatch::blocksFor;
using dispatch::DeviceBuffer;

struct ZBufferCuda::Impl {
    dispatch::Stream stream;
    ViewTransform view;
    ScreenProjection projection{};
    DeviceBuffer<zb::ScreenVertex> screen;
    DeviceBuffer<std::uint32_t> surface, lines;
    DeviceBuffer<std::uint8_t> mask;
    MaskDownload download;
    DeviceBuffer<unsigned long long> segmentCount;
    StrokePruning pruning;
    HostMeshUpload hostMesh;        // drawHost's copy of a host mesh
    dispatch::StageTimer timers[3]; // project, silhouette (+ coverage), resolve
    // A draw's times are read once it has finished: at the next draw, waitForDraws or the
    // resolve, so that a frame's draws and its colour pass queue without a host wait between.
    bool drawUnread = false;
    double unreadProjectMs = 0.0, unreadDrawMs = 0.0;
    std::size_t pixels() const {
        return std::size_t(view.width > 0 ? view.width : 0) *
               std::size_t(view.height > 0 ? view.height : 0);
    }
};

ZBufferCuda::ZBufferCuda() : m_impl(std::make_unique<Impl>()) {}

void ZBufferCuda::release() {
    m_impl = std::make_unique<Impl>();
}

std::size_t ZBufferCuda::deviceBytes() const {
    const Impl& s = *m_impl;
    return s.screen.bytes() + s.surface.bytes() + s.lines.bytes() + s.mask.bytes() +
           s.segmentCount.bytes() + s.hostMesh.bytes() + s.pruning.deviceBytes();
}
ZBufferCuda::~ZBufferCuda() = default;

CudaStatus ZBufferCuda::begin(const ViewTransform& view) {
    Impl& s = *m_impl;
    LW_RETURN_IF_FAILED(s.stream.create());
    s.view = view;
    s.projection = view.projection();
    const std::size_t pixels = s.pixels();
    LW_RETURN_IF_FAILED(s.surface.reserve(pixels, "cudaMalloc(zbuffer1)"));
    LW_RETURN_IF_FAILED(s.lines.reserve(pixels, "cudaMalloc(zbuffer2)"));
    LW_RETURN_IF_FAILED(s.mask.reserve(pixels, "cudaMalloc(mask)"));
    LW_RETURN_IF_FAILED(s.segmentCount.reserve(1, "cudaMalloc(segmentCount)"));
    cudaStream_t st = s.stream.get();
    LW_CUDA_TRY(cudaMemsetAsync(s.surface.data(), 0, pixels * sizeof(std::uint32_t), st),
                "cudaMemset(zbuffer1)");
    LW_CUDA_TRY(cudaMemsetAsync(s.lines.data(), 0, pixels * sizeof(std::uint32_t), st),
                "cudaMemset(zbuffer2)");
    LW_CUDA_TRY(cudaMemsetAsync(s.segmentCount.data(), 0, sizeof(unsigned long long), st),
                "cudaMemset(segmentCount)");
    return CudaStatus::success();
}

namespace {

// The last draw's stage times into the unread sums (waits for that draw to finish: its timers are
// recorded again by the next one).
CudaStatus readDrawTimes(ZBufferCuda::Impl& s) {
    if (!s.drawUnread)
        return CudaStatus::success();
    LW_RETURN_IF_FAILED(s.timers[1].waitForStop());
    s.unreadProjectMs += s.timers[0].ms();
    s.unreadDrawMs += s.timers[1].ms();
    s.drawUnread = false;
    return CudaStatus::success();
}

void moveDrawTimes(ZBufferCuda::Impl& s, ZBufferCudaFrame& frame) {
    frame.projectMs += std::exchange(s.unreadProjectMs, 0.0);
    frame.drawMs += std::exchange(s.unreadDrawMs, 0.0);
}

} // namespace

CudaStatus ZBufferCuda::waitForDraws(ZBufferCudaFrame& frame) {
    Impl& s = *m_impl;
    LW_RETURN_IF_FAILED(readDrawTimes(s));
    moveDrawTimes(s, frame);
    return CudaStatus::success();
}

CudaStatus ZBufferCuda::draw(const DeviceMeshView& mesh, const ZBufferCudaSettings& settings,
                             ZBufferCudaFrame& frame) {
    Impl& s = *m_impl;
    if (mesh.triangleCount == 0)
        return CudaStatus::success();
    LW_RETURN_IF_FAILED(readDrawTimes(s));
    moveDrawTimes(s, frame);
    cudaStream_t st = s.stream.get();
    LW_RETURN_IF_FAILED(s.screen.reserve(mesh.vertexCount, "cudaMalloc(screenVertices)"));
    const glm::vec3 eyeOrDirection = glm::vec3(s.view.orthographic ? s.view.toViewer : s.view.eye);

    LW_RETURN_IF_FAILED(s.timers[0].start(st));
    zb::projectVertices<<<blocksFor(mesh.vertexCount, tuning::kVertexBlock), tuning::kVertexBlock,
                          0, st>>>(mesh.positions, mesh.normals, std::uint32_t(mesh.vertexCount),
                                   s.projection, eyeOrDirection, s.view.orthographic,
                                   s.screen.data());
    LW_CUDA_LAUNCHED("zb::projectVertices");
    LW_RETURN_IF_FAILED(s.timers[0].stop(st));

    const unsigned triangleBlocks = blocksFor(mesh.triangleCount, tuning::kTriangleBlock);
    LW_RETURN_IF_FAILED(s.timers[1].start(st));
    const auto drawTriangles =
        settings.visibility ? zb::drawTriangles<true> : zb::drawTriangles<false>;
    drawTriangles<<<triangleBlocks, tuning::kTriangleBlock, 0, st>>>(
        mesh.positions, mesh.indices, std::uint32_t(mesh.triangleCount), s.screen.data(),
        s.projection, settings.cullBackFaces, s.lines.data(), s.surface.data(),
        s.segmentCount.data());
    LW_CUDA_LAUNCHED("zb::drawTriangles");
    LW_RETURN_IF_FAILED(s.timers[1].stop(st));
    s.drawUnread = true;
    return CudaStatus::success();
}

CudaStatus ZBufferCuda::drawHost(const TriangleMesh& mesh, const ZBufferCudaSettings& settings,
                                 ZBufferCudaFrame& frame) {
    LW_RETURN_IF_FAILED(keepHostMesh(mesh));
    return drawKeptHostMesh(settings, frame);
}

CudaStatus ZBufferCuda::keepHostMesh(const TriangleMesh& mesh) {
    Impl& s = *m_impl;
    LW_RETURN_IF_FAILED(s.stream.create());
    return s.hostMesh.upload(mesh, s.stream.get());
}

CudaStatus ZBufferCuda::drawKeptHostMesh(const ZBufferCudaSettings& settings,
                                         ZBufferCudaFrame& frame) {
    return draw(m_impl->hostMesh.view(), settings, frame);
}

CudaStatus ZBufferCuda::finishResolve(ZBufferCudaFrame& frame) {
    Impl& s = *m_impl;
    cudaStream_t st = s.stream.get();
    LW_RETURN_IF_FAILED(s.timers[2].stop(st));
    unsigned long long segments = 0;
    LW_CUDA_TRY(cudaMemcpyAsync(&segments, s.segmentCount.data(), sizeof segments,
                                cudaMemcpyDeviceToHost, st),
                "cudaMemcpy(segmentCount)");
    LW_CUDA_TRY(cudaStreamSynchronize(st), "zb::resolve");
    LW_RETURN_IF_FAILED(readDrawTimes(s));
    moveDrawTimes(s, frame);
    frame.resolveMs += s.timers[2].ms();
    frame.segments = std::size_t(segments);
    return CudaStatus::success();
}

CudaStatus ZBufferCuda::resolve(const ZBufferCudaSettings& settings, std::uint8_t* hostMask,
                                ZBufferCudaFrame& frame) {
    Impl& s = *m_impl;
    cudaStream_t st = s.stream.get();
    const int width = s.view.width, height = s.view.height;
    const std::size_t pixels = s.pixels();
    LW_RETURN_IF_FAILED(s.timers[2].start(st));
    if (pixels > 0) {
        const PixelLaunch launch = pixelLaunch(width, height);
        zb::resolve<<<launch.grid, launch.block, 0, st>>>(s.surface.data(), s.lines.data(), width,
                                                          height, settings.epsilon,
                                                          settings.visibility, s.mask.data());
        LW_CUDA_LAUNCHED("zb::resolve");
        LW_RETURN_IF_FAILED(s.pruning.run(s.mask.data(), width, height, settings.minStrokePixels,
                                          settings.strokeGapPixels, st));
    }
    LW_RETURN_IF_FAILED(s.download.queue(s.mask.data(), pixels, st));
    LW_RETURN_IF_FAILED(finishResolve(frame)); // synchronises the stream
    s.download.deliver(hostMask);
    return CudaStatus::success();
}

namespace {

// The colour pass into the texture's surface object: straight, or, when strokes are pruned, into
// the device mask first and copied once pruned.
CudaStatus composeKernels(ZBufferCuda::Impl& s, const ZBufferCudaSettings& settings,
                          cudaSurfaceObject_t texels) {
    cudaStream_t st = s.stream.get();
    const int width = s.view.width, height = s.view.height;
    const PixelLaunch launch = pixelLaunch(width, height);
    if (settings.minStrokePixels <= 1) {
        zb::resolveToSurface<<<launch.grid, launch.block, 0, st>>>(s.surface.data(), s.lines.data(),
                                                                   width, height, settings.epsilon,
                                                                   settings.visibility, texels);
        return dispatch::checkLaunch("zb::resolveToSurface");
    }
    zb::resolve<<<launch.grid, launch.block, 0, st>>>(s.surface.data(), s.lines.data(), width,
                                                      height, settings.epsilon, settings.visibility,
                                                      s.mask.data());
    LW_CUDA_LAUNCHED("zb::resolve");
    LW_RETURN_IF_FAILED(s.pruning.run(s.mask.data(), width, height, settings.minStrokePixels,
                                      settings.strokeGapPixels, st));
    return copyMaskToSurface(s.mask.data(), width, height, texels, st);
}

// The compose kernel into the mapped texture's array through a surface object, which may go only
// once the kernel is done.
CudaStatus composeIntoTexture(ZBufferCuda::Impl& s, const ZBufferCudaSettings& settings,
                              cudaGraphicsResource_t resource) {
    cudaStream_t st = s.stream.get();
    cudaArray_t array = nullptr;
    LW_CUDA_TRY(cudaGraphicsSubResourceGetMappedArray(&array, resource, 0, 0),
                "cudaGraphicsSubResourceGetMappedArray(mask texture)");
    cudaResourceDesc description{};
    description.resType = cudaResourceTypeArray;
    description.res.array.array = array;
    cudaSurfaceObject_t texels = 0;
    LW_CUDA_TRY(cudaCreateSurfaceObject(&texels, &description),
                "cudaCreateSurfaceObject(mask texture)");
    CudaStatus status = composeKernels(s, settings, texels);
    if (status.ok())
        status = dispatch::statusOf(cudaStreamSynchronize(st), "zb::resolveToSurface");
    const CudaStatus destroyed = dispatch::statusOf(cudaDestroySurfaceObject(texels),
                                                    "cudaDestroySurfaceObject(mask texture)");
    LW_RETURN_IF_FAILED(status);
    return destroyed;
}

} // namespace

CudaStatus ZBufferCuda::resolveInto(const ZBufferCudaSettings& settings,
                                    const GlTextureInterop& target, ZBufferCudaFrame& frame) {
    Impl& s = *m_impl;
    if (!target.attached() || target.width() != s.view.width || target.height() != s.view.height ||
        s.pixels() == 0)
        return CudaStatus::failure(CudaStatus::Code::Failed, "zb::resolveToSurface",
                                   "the GL texture is not attached at the frame's size");
    cudaStream_t st = s.stream.get();
    auto resource = static_cast<cudaGraphicsResource_t>(target.resource());
    LW_RETURN_IF_FAILED(s.timers[2].start(st));
    // Mapped on the frame's stream: GL's earlier use of the texture completes before the kernel.
    CudaStatus status = dispatch::statusOf(cudaGraphicsMapResources(1, &resource, st),
                                           "cudaGraphicsMapResources(mask texture)");
    if (status.ok()) {
        status = composeIntoTexture(s, settings, resource);
        // Unmapped whatever happened: GL may not use a texture CUDA still holds.
        const CudaStatus unmapped = dispatch::statusOf(cudaGraphicsUnmapResources(1, &resource, st),
                                                       "cudaGraphicsUnmapResources(mask texture)");
        if (status.ok())
            status = unmapped;
    }
    if (!status.ok()) {
        // An interop failure is not sticky: drop it as the last error, so that the host path the
        // caller takes next does not report it at its first launch check.
        cudaGetLastError();
        return status;
    }
    return finishResolve(frame);
}

} // namespace lw::kernels::cuda
