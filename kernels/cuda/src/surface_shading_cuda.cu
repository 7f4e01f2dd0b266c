// Host dispatch of the shaded iso panel on the GPU (kernels in surface_shading_kernels.cuh).

#include "dispatch.h"
#include "host_mesh_upload.h"
#include "lw/kernels/cuda/surface_shading_cuda.h"
#include "pixel_launch.h"
#include "surface_shading_kernels.cuh"
#include "tuning.h"

#include <cstring>
#include <limits>

namespace lw::kernels::cuda {

using dispatch::blocksFor;
using dispatch::DeviceBuffer;

struct SurfaceShadingCuda::Impl {
    dispatch::Stream stream;
    ViewTransform view;
    ScreenProjection projection{};
    DeviceBuffer<unsigned long long> nearest;
    DeviceBuffer<shade::ScreenPoint> screen[kMaxMeshes];
    shade::Slots slots;
    std::uint64_t triangles = 0; // numbered so far this frame
    HostMeshUpload hostMesh;     // keepHostMesh's copy
    // The image and its depth on the device and their page-locked host copies.
    DeviceBuffer<uchar4> rgba;
    DeviceBuffer<float> depth;
    dispatch::PinnedBuffer<uchar4> rgbaHost;
    dispatch::PinnedBuffer<float> depthHost;
    dispatch::StageTimer rasterTimer, shadeTimer;
    bool rasterStarted = false;

    std::size_t pixels() const {
        return std::size_t(view.width > 0 ? view.width : 0) *
               std::size_t(view.height > 0 ? view.height : 0);
    }
};

SurfaceShadingCuda::SurfaceShadingCuda() : m_impl(std::make_unique<Impl>()) {}
SurfaceShadingCuda::~SurfaceShadingCuda() = default;

void SurfaceShadingCuda::release() {
    m_impl = std::make_unique<Impl>();
}

std::size_t SurfaceShadingCuda::deviceBytes() const {
    const Impl& s = *m_impl;
    std::size_t bytes = s.nearest.bytes() + s.hostMesh.bytes() + s.rgba.bytes() + s.depth.bytes();
    for (const auto& screen : s.screen)
        bytes += screen.bytes();
    return bytes;
}

CudaStatus SurfaceShadingCuda::begin(const ViewTransform& view) {
    Impl& s = *m_impl;
    LW_RETURN_IF_FAILED(s.stream.create());
    s.view = view;
    s.projection = view.projection();
    s.slots = shade::Slots();
    s.triangles = 0;
    const std::size_t pixels = s.pixels();
    LW_RETURN_IF_FAILED(s.nearest.reserve(pixels, "cudaMalloc(nearest)"));
    cudaStream_t st = s.stream.get();
    LW_RETURN_IF_FAILED(s.rasterTimer.start(st));
    s.rasterStarted = true;
    LW_CUDA_TRY(cudaMemsetAsync(s.nearest.data(), 0, pixels * sizeof(unsigned long long), st),
                "cudaMemset(nearest)");
    return CudaStatus::success();
}

CudaStatus SurfaceShadingCuda::draw(const DeviceMeshView& mesh) {
    Impl& s = *m_impl;
    if (mesh.triangleCount == 0)
        return CudaStatus::success();
    if (s.slots.count >= kMaxMeshes)
        return CudaStatus::failure(CudaStatus::Code::TooLarge, "shade::drawNearest",
                                   "more meshes than a frame numbers");
    if (s.triangles + mesh.triangleCount >= std::numeric_limits<std::uint32_t>::max())
        return CudaStatus::failure(CudaStatus::Code::TooLarge, "shade::drawNearest",
                                   "more triangles than 32-bit numbers hold");
    const int slot = s.slots.count;
    cudaStream_t st = s.stream.get();
    LW_RETURN_IF_FAILED(s.screen[slot].reserve(mesh.vertexCount, "cudaMalloc(shadeVertices)"));
    shade::projectVertices<<<blocksFor(mesh.vertexCount, tuning::kVertexBlock),
                             tuning::kVertexBlock, 0, st>>>(
        mesh.positions, std::uint32_t(mesh.vertexCount), s.projection, s.screen[slot].data());
    LW_CUDA_LAUNCHED("shade::projectVertices");
    shade::MeshSlot& slotted = s.slots.mesh[slot];
    slotted = {mesh.positions, mesh.normals, mesh.indices, s.screen[slot].data(),
               std::uint32_t(s.triangles)};
    shade::drawNearest<<<blocksFor(mesh.triangleCount, tuning::kTriangleBlock),
                         tuning::kTriangleBlock, 0, st>>>(
        slotted, std::uint32_t(mesh.triangleCount), s.view.width, s.view.height, s.nearest.data());
    LW_CUDA_LAUNCHED("shade::drawNearest");
    s.triangles += mesh.triangleCount;
    ++s.slots.count;
    return CudaStatus::success();
}

CudaStatus SurfaceShadingCuda::keepHostMesh(const TriangleMesh& mesh) {
    Impl& s = *m_impl;
    LW_RETURN_IF_FAILED(s.stream.create());
    return s.hostMesh.upload(mesh, s.stream.get());
}

CudaStatus SurfaceShadingCuda::drawKeptHostMesh() {
    return draw(m_impl->hostMesh.view());
}

CudaStatus SurfaceShadingCuda::shade(const SurfaceLighting& lighting, std::uint8_t* hostRgba,
                                     float* hostDepth, SurfaceShadingTimes& times) {
    Impl& s = *m_impl;
    const std::size_t pixels = s.pixels();
    if (pixels == 0 || !s.rasterStarted)
        return CudaStatus::success();
    cudaStream_t st = s.stream.get();
    LW_RETURN_IF_FAILED(s.rasterTimer.stop(st));
    LW_RETURN_IF_FAILED(s.shadeTimer.start(st));
    LW_RETURN_IF_FAILED(s.rgba.reserve(pixels, "cudaMalloc(shadedImage)"));
    LW_RETURN_IF_FAILED(s.depth.reserve(pixels, "cudaMalloc(shadedDepth)"));
    LW_RETURN_IF_FAILED(s.rgbaHost.reserve(pixels, "cudaMallocHost(shadedImage)"));
    if (hostDepth)
        LW_RETURN_IF_FAILED(s.depthHost.reserve(pixels, "cudaMallocHost(shadedDepth)"));
    const shade::ShadeView view{s.projection, s.view.orthographic, s.view.eye, s.view.toViewer};
    const PixelLaunch launch = pixelLaunch(s.view.width, s.view.height);
    shade::shadePixels<<<launch.grid, launch.block, 0, st>>>(
        s.nearest.data(), s.slots, view, lighting, s.rgba.data(), s.depth.data());
    LW_CUDA_LAUNCHED("shade::shadePixels");
    LW_CUDA_TRY(cudaMemcpyAsync(s.rgbaHost.data(), s.rgba.data(), pixels * sizeof(uchar4),
                                cudaMemcpyDeviceToHost, st),
                "cudaMemcpy(shadedImage)");
    if (hostDepth)
        LW_CUDA_TRY(cudaMemcpyAsync(s.depthHost.data(), s.depth.data(), pixels * sizeof(float),
                                    cudaMemcpyDeviceToHost, st),
                    "cudaMemcpy(shadedDepth)");
    LW_RETURN_IF_FAILED(s.shadeTimer.stop(st));
    LW_CUDA_TRY(cudaStreamSynchronize(st), "shade::shadePixels");
    s.rasterStarted = false;
    times.rasterMs += s.rasterTimer.ms();
    times.shadeMs += s.shadeTimer.ms();
    std::memcpy(hostRgba, s.rgbaHost.data(), pixels * sizeof(uchar4));
    if (hostDepth)
        std::memcpy(hostDepth, s.depthHost.data(), pixels * sizeof(float));
    return CudaStatus::success();
}

} // namespace lw::kernels::cuda
