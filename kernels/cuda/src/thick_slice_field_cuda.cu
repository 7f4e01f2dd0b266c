#include "dispatch.h"
#include "lw/kernels/cuda/thick_slice_field_cuda.h"
#include "pixel_launch.h"
#include "thick_slice_field_kernels.cuh"
#include "tuning.h"

#include <array>
#include <cstring>

namespace lw::kernels::cuda {

using dispatch::DeviceBuffer;

struct ThickSliceFieldCuda::Impl {
    dispatch::Stream stream;
    DeviceBuffer<unsigned char> source; // the slices as uploaded
    VoxelKind kind = VoxelKind::Int16;
    glm::ivec3 dims{0};
    DeviceBuffer<float> above;
    DeviceBuffer<float> rowNear;
    DeviceBuffer<float> columnNear;
    DeviceBuffer<std::int16_t> distance;
    DeviceBuffer<std::int16_t> refined;
    dispatch::PinnedBuffer<std::int16_t> downloaded;
    DeviceBuffer<unsigned> faceSlots; // faceMaximaKernel's six slots
    dispatch::PinnedBuffer<unsigned> faceSlotsDownloaded;
    std::array<double, 6> faceMaxima{};
    dispatch::StageTimer distanceTimer, refineTimer, downloadTimer;
    ThickSliceFieldTimes times;

    std::size_t voxelCount() const {
        return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
    }
    CudaStatus distanceField(double iso, const ThickSliceFieldSetup& setup);
    CudaStatus refine(const ThickSliceFieldSetup& setup, glm::ivec3 refinedDims);
    CudaStatus bridgeThinWalls(const ThickSliceFieldSetup& setup, glm::ivec3 refinedDims);
    CudaStatus findFaceMaxima(glm::ivec3 refinedDims);
};

namespace {

int refinedCount(int n, int factor) {
    return n > 1 ? (n - 1) * factor + 1 : n;
}

dim3 planeGrid(int width, int height, int slices) {
    const PixelLaunch launch = pixelLaunch(width, height);
    return dim3(launch.grid.x, launch.grid.y, unsigned(slices));
}

} // namespace

CudaStatus ThickSliceFieldCuda::Impl::distanceField(double iso, const ThickSliceFieldSetup& setup) {
    const std::size_t count = voxelCount();
    LW_RETURN_IF_FAILED(above.reserve(count, "thick slices: value buffer"));
    LW_RETURN_IF_FAILED(rowNear.reserve(count, "thick slices: row distances"));
    LW_RETURN_IF_FAILED(columnNear.reserve(count, "thick slices: column distances"));
    LW_RETURN_IF_FAILED(distance.reserve(count, "thick slices: distance field"));
    const cudaStream_t s = stream.get();
    dispatchVoxelKind(kind, [&](auto tag) {
        using T = decltype(tag);
        field::aboveIsoKernel<T>
            <<<dispatch::blocksFor(count, tuning::kFieldVoxelBlock), tuning::kFieldVoxelBlock, 0,
               s>>>(reinterpret_cast<const T*>(source.data()), count, setup.slope, setup.intercept,
                    iso, above.data());
    });
    LW_CUDA_LAUNCHED("thickSlices::aboveIso");
    const field::SliceGrid grid{dims.x, dims.y, dims.z};
    const int reachI = sliceDistanceReach(setup.limitMm, setup.spacingI, dims.x);
    const int reachJ = sliceDistanceReach(setup.limitMm, setup.spacingJ, dims.y);
    const float scaleI = float(setup.spacingI * setup.spacingI);
    const float scaleJ = float(setup.spacingJ * setup.spacingJ);
    const dim3 blocks = planeGrid(dims.x, dims.y, dims.z);
    const dim3 threads(tuning::kPixelBlockX, tuning::kPixelBlockY);
    field::nearestKernel<<<blocks, threads, 0, s>>>(above.data(), grid, reachI, reachJ, scaleI,
                                                    scaleJ, rowNear.data(), columnNear.data());
    LW_CUDA_LAUNCHED("thickSlices::nearest");
    field::distanceKernel<<<blocks, threads, 0, s>>>(
        above.data(), rowNear.data(), columnNear.data(), grid, reachI, reachJ, scaleI, scaleJ,
        setup.limitMm, setup.stepsPerMm, distance.data());
    LW_CUDA_LAUNCHED("thickSlices::distance");
    return CudaStatus::success();
}

CudaStatus ThickSliceFieldCuda::Impl::refine(const ThickSliceFieldSetup& setup,
                                             glm::ivec3 refinedDims) {
    const std::size_t count =
        std::size_t(refinedDims.x) * std::size_t(refinedDims.y) * std::size_t(refinedDims.z);
    LW_RETURN_IF_FAILED(refined.reserve(count, "thick slices: refined field"));
    const field::RefineGrid grid{
        dims.x,          dims.y,          dims.z,
        refinedDims.x,   refinedDims.y,   setup.factors.x,
        setup.factors.y, setup.factors.z, setup.monotoneAlongSlices && dims.z > 2};
    field::refineKernel<<<planeGrid(refinedDims.x, refinedDims.y, refinedDims.z),
                          dim3(tuning::kPixelBlockX, tuning::kPixelBlockY), 0, stream.get()>>>(
        distance.data(), grid, refined.data());
    LW_CUDA_LAUNCHED("thickSlices::refine");
    return CudaStatus::success();
}

// The refined slices between each two raised to the thin walls slid between them
// (volume/slice_bridging.h), on the refined grid as the host does it.
CudaStatus ThickSliceFieldCuda::Impl::bridgeThinWalls(const ThickSliceFieldSetup& setup,
                                                      glm::ivec3 refinedDims) {
    if (setup.factors.z < 2 || !(setup.thinWallMm > 0.0) || refinedDims.x < 3 ||
        refinedDims.y < 3 || dims.z < 2)
        return CudaStatus::success();
    const ThinShellSlices pair = thinShellSlices(
        refinedDims.x, refinedDims.y, setup.spacingI / setup.factors.x,
        setup.spacingJ / setup.factors.y, setup.stepsPerMm, setup.limitMm, setup.thinWallMm);
    field::bridgeKernel<<<planeGrid(refinedDims.x, refinedDims.y, dims.z - 1),
                          dim3(tuning::kPixelBlockX, tuning::kPixelBlockY), 0, stream.get()>>>(
        refined.data(), pair, setup.factors.z);
    LW_CUDA_LAUNCHED("thickSlices::bridge");
    return CudaStatus::success();
}

// Queues the faces' maxima and their download on the stream (read after it is synchronised).
CudaStatus ThickSliceFieldCuda::Impl::findFaceMaxima(glm::ivec3 refinedDims) {
    const cudaStream_t s = stream.get();
    LW_RETURN_IF_FAILED(faceSlots.reserve(6, "thick slices: face maxima"));
    LW_RETURN_IF_FAILED(faceSlotsDownloaded.reserve(6, "thick slices: face maxima"));
    LW_CUDA_TRY(cudaMemsetAsync(faceSlots.data(), 0, 6 * sizeof(unsigned), s),
                "thick slices: face maxima reset");
    field::faceMaximaKernel<<<dim3(tuning::kFaceMaximaBlocks, 6), tuning::kFaceMaximaBlock, 0, s>>>(
        refined.data(), refinedDims.x, refinedDims.y, refinedDims.z, faceSlots.data());
    LW_CUDA_LAUNCHED("thickSlices::faceMaxima");
    LW_CUDA_TRY(cudaMemcpyAsync(faceSlotsDownloaded.data(), faceSlots.data(), 6 * sizeof(unsigned),
                                cudaMemcpyDeviceToHost, s),
                "thick slices: face maxima download");
    return CudaStatus::success();
}

ThickSliceFieldCuda::ThickSliceFieldCuda() : m_impl(std::make_unique<Impl>()) {}
ThickSliceFieldCuda::~ThickSliceFieldCuda() = default;

CudaStatus ThickSliceFieldCuda::setVolume(const VolumeView& hostVolume) {
    Impl& d = *m_impl;
    if (hostVolume.dims.x < 1 || hostVolume.dims.y < 1 || hostVolume.dims.z < 1)
        return CudaStatus::failure(CudaStatus::Code::Failed, "thick slices", "an empty volume");
    LW_RETURN_IF_FAILED(d.stream.create());
    LW_RETURN_IF_FAILED(d.source.reserve(hostVolume.byteCount(), "thick slices: the slices"));
    // On the field's own stream: a plain cudaMemcpy from pageable memory may return before its
    // DMA lands, and the stream (non-blocking) is not ordered after the legacy default stream, so
    // the first kernels could read the slices half-written.
    LW_CUDA_TRY(cudaMemcpyAsync(d.source.data(), hostVolume.voxels, hostVolume.byteCount(),
                                cudaMemcpyHostToDevice, d.stream.get()),
                "thick slices: slices upload");
    d.kind = hostVolume.kind;
    d.dims = hostVolume.dims;
    return CudaStatus::success();
}

CudaStatus ThickSliceFieldCuda::make(double iso, const ThickSliceFieldSetup& setup,
                                     std::int16_t* lockedTarget) {
    Impl& d = *m_impl;
    if (!d.source.data())
        return CudaStatus::failure(CudaStatus::Code::Failed, "thick slices", "no volume set");
    if (setup.factors.x < 1 || setup.factors.y < 1 || setup.factors.z < 1)
        return CudaStatus::failure(CudaStatus::Code::Failed, "thick slices",
                                   "factors must be at least 1");
    const glm::ivec3 refinedDims(refinedCount(d.dims.x, setup.factors.x),
                                 refinedCount(d.dims.y, setup.factors.y),
                                 refinedCount(d.dims.z, setup.factors.z));
    const cudaStream_t s = d.stream.get();
    LW_RETURN_IF_FAILED(d.distanceTimer.start(s));
    LW_RETURN_IF_FAILED(d.distanceField(iso, setup));
    LW_RETURN_IF_FAILED(d.distanceTimer.stop(s));
    LW_RETURN_IF_FAILED(d.refineTimer.start(s));
    LW_RETURN_IF_FAILED(d.refine(setup, refinedDims));
    LW_RETURN_IF_FAILED(d.bridgeThinWalls(setup, refinedDims));
    LW_RETURN_IF_FAILED(d.findFaceMaxima(refinedDims));
    LW_RETURN_IF_FAILED(d.refineTimer.stop(s));
    LW_RETURN_IF_FAILED(d.downloadTimer.start(s));
    const std::size_t count =
        std::size_t(refinedDims.x) * std::size_t(refinedDims.y) * std::size_t(refinedDims.z);
    std::int16_t* target = lockedTarget;
    if (!target) {
        LW_RETURN_IF_FAILED(d.downloaded.reserve(count, "thick slices: page-locked field"));
        target = d.downloaded.data();
    }
    LW_CUDA_TRY(cudaMemcpyAsync(target, d.refined.data(), count * sizeof(std::int16_t),
                                cudaMemcpyDeviceToHost, s),
                "thick slices: field download");
    LW_RETURN_IF_FAILED(d.downloadTimer.stop(s));
    LW_CUDA_TRY(cudaStreamSynchronize(s), "thick slices: cudaStreamSynchronize");
    d.times = {d.distanceTimer.ms(), d.refineTimer.ms(), d.downloadTimer.ms()};
    for (std::size_t face = 0; face < d.faceMaxima.size(); ++face)
        d.faceMaxima[face] = double(int(d.faceSlotsDownloaded.data()[face]) - 32768);
    return CudaStatus::success();
}

const std::int16_t* ThickSliceFieldCuda::field() const {
    return m_impl->downloaded.data();
}

const std::array<double, 6>& ThickSliceFieldCuda::faceMaxima() const {
    return m_impl->faceMaxima;
}

const std::int16_t* ThickSliceFieldCuda::deviceField() const {
    return m_impl->refined.data();
}

const ThickSliceFieldTimes& ThickSliceFieldCuda::times() const {
    return m_impl->times;
}

std::size_t ThickSliceFieldCuda::deviceBytes() const {
    const Impl& d = *m_impl;
    return d.source.bytes() + d.above.bytes() + d.rowNear.bytes() + d.columnNear.bytes() +
           d.distance.bytes() + d.refined.bytes();
}

void ThickSliceFieldCuda::release() {
    Impl& d = *m_impl;
    d.source.release();
    d.above.release();
    d.rowNear.release();
    d.columnNear.release();
    d.distance.release();
    d.refined.release();
    d.faceSlots.release();
    d.dims = glm::ivec3(0);
}

} // namespace lw::kernels::cuda
