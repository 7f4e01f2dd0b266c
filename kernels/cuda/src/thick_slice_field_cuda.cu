#include "dispatch.h"
#include "lw/kernels/cuda/thick_slice_field_cuda.h"
#include "pixel_launch.h"
#include "thick_slice_field_kernels.cuh"
#include "tuning.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace lw::kernels::cuda {

using dispatch::DeviceBuffer;

struct ThickSliceFieldCuda::Impl {
    dispatch::Stream stream;
    DeviceBuffer<unsigned char> source; // the slices as uploaded
    VoxelKind kind = VoxelKind::Int16;
    glm::ivec3 dims{0};
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
    CudaStatus refineAlongSlices(const ThickSliceFieldSetup& setup, glm::ivec3 refinedDims);
    CudaStatus resetFaceSlots();
    CudaStatus findFaceMaxima(glm::ivec3 refinedDims);
    CudaStatus downloadFaceSlots();
};

namespace {

// Shared memory a block may use without opting in to more.
constexpr std::size_t kSharedBytes = 48 * 1024;

// Shared memory a block may use where the kernel opts in (the current device's limit).
std::size_t sharedBytesOptIn() {
    int device = 0, bytes = 0;
    if (cudaGetDevice(&device) != cudaSuccess ||
        cudaDeviceGetAttribute(&bytes, cudaDevAttrMaxSharedMemoryPerBlockOptin, device) !=
            cudaSuccess)
        return kSharedBytes;
    return std::size_t(bytes);
}

int refinedCount(int n, int factor) {
    return n > 1 ? (n - 1) * factor + 1 : n;
}

// Refined along the slices alone (the thick slices' usual plan): refineAlongSlicesKernel's case.
bool refinesAlongSlicesOnly(const ThickSliceFieldSetup& setup, glm::ivec3 dims) {
    return setup.factors.x == 1 && setup.factors.y == 1 && setup.factors.z >= 2 && dims.z >= 2;
}

dim3 planeGrid(int width, int height, int slices) {
    const PixelLaunch launch = pixelLaunch(width, height);
    return dim3(launch.grid.x, launch.grid.y, unsigned(slices));
}

} // namespace

// The slices' distances in one kernel, a 32 x 32 tile a block, where the tile's shared memory fits
// the block (sliceDistanceTileKernel); else the nearest crossings (nearTermsKernel) and the
// minima (distanceKernel) through global memory.
CudaStatus ThickSliceFieldCuda::Impl::distanceField(double iso, const ThickSliceFieldSetup& setup) {
    const std::size_t count = voxelCount();
    LW_RETURN_IF_FAILED(distance.reserve(count, "thick slices: distance field"));
    const cudaStream_t s = stream.get();
    const field::SliceGrid grid{dims.x, dims.y, dims.z};
    const field::AboveIso above{setup.slope, setup.intercept, iso};
    const int reachI = sliceDistanceReach(setup.limitMm, setup.spacingI, dims.x);
    const int reachJ = sliceDistanceReach(setup.limitMm, setup.spacingJ, dims.y);
    const float scaleI = float(setup.spacingI * setup.spacingI);
    const float scaleJ = float(setup.spacingJ * setup.spacingJ);
    const field::DistanceTile tile{reachI, reachJ};
    const std::size_t tileBytes = std::size_t(tile.floats()) * sizeof(float);
    if (std::max(reachI, reachJ) <= tuning::kDistanceTileMaxReach &&
        tileBytes <= sharedBytesOptIn()) {
        const float reaching = squaredReachingLimit(setup.limitMm);
        const field::DistanceSetup distanceSetup{
            scaleI,
            scaleJ,
            reaching,
            setup.limitMm,
            setup.stepsPerMm,
            storedSliceDistance(reaching, true, setup.limitMm, setup.stepsPerMm),
            storedSliceDistance(reaching, false, setup.limitMm, setup.stepsPerMm)};
        const dim3 blocks(unsigned(dispatch::blocksFor(std::size_t(dims.x), 32)),
                          unsigned(dispatch::blocksFor(std::size_t(dims.y), 32)), unsigned(dims.z));
        CudaStatus status = CudaStatus::success();
        dispatchVoxelKind(kind, [&](auto tag) {
            using T = decltype(tag);
            const auto kernel = field::sliceDistanceTileKernel<T>;
            if (tileBytes > kSharedBytes) {
                const cudaError_t error = cudaFuncSetAttribute(
                    kernel, cudaFuncAttributeMaxDynamicSharedMemorySize, int(tileBytes));
                if (error != cudaSuccess) {
                    status = dispatch::statusOf(error, "thick slices: the tile's shared memory");
                    return;
                }
            }
            kernel<<<blocks, dim3(tuning::kPixelBlockX, tuning::kPixelBlockY), tileBytes, s>>>(
                reinterpret_cast<const T*>(source.data()), above, grid, tile, distanceSetup,
                distance.data());
        });
        LW_RETURN_IF_FAILED(status);
        LW_CUDA_LAUNCHED("thickSlices::sliceDistanceTile");
        return CudaStatus::success();
    }
    LW_RETURN_IF_FAILED(rowNear.reserve(count, "thick slices: row distances"));
    LW_RETURN_IF_FAILED(columnNear.reserve(count, "thick slices: column distances"));
    // Runs of 32 edges either side of a warp's columns that cover the reach (and its two pixels
    // more: the windows the CPU's crossings can lie in).
    const int chunks = (reachI + 2 + 31) / 32;
    const std::size_t warpBytes = std::size_t(field::nearTermsSharedFloats(chunks)) * sizeof(float);
    const int warps = int(std::min<std::size_t>(tuning::kNearWarps, kSharedBytes / warpBytes));
    if (warps < 1)
        return CudaStatus::failure(CudaStatus::Code::Failed, "thick slices",
                                   "the distance limit reaches too many pixels along a row");
    const dim3 nearBlocks(unsigned(dispatch::blocksFor(std::size_t(dims.x), 32)),
                          unsigned(dispatch::blocksFor(
                              std::size_t(dims.y), std::size_t(warps) * tuning::kNearRowsPerWarp)),
                          unsigned(dims.z));
    dispatchVoxelKind(kind, [&](auto tag) {
        using T = decltype(tag);
        const T* voxels = reinterpret_cast<const T*>(source.data());
        field::nearTermsKernel<tuning::kNearRowsPerWarp, T>
            <<<nearBlocks, dim3(32, unsigned(warps)), std::size_t(warps) * warpBytes, s>>>(
                voxels, above, grid, chunks, reachJ, scaleI, scaleJ, rowNear.data(),
                columnNear.data());
        field::distanceKernel<T>
            <<<planeGrid(dims.x, dims.y, dims.z), dim3(tuning::kPixelBlockX, tuning::kPixelBlockY),
               0, s>>>(voxels, above, rowNear.data(), columnNear.data(), grid, reachI, reachJ,
                       scaleI, scaleJ, setup.limitMm, setup.stepsPerMm, distance.data());
    });
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

// Refinement, thin walls and the faces' maxima in one kernel (refinesAlongSlicesOnly): the
// bridge's two slices are the distance slices, which the refinement copies unchanged.
CudaStatus ThickSliceFieldCuda::Impl::refineAlongSlices(const ThickSliceFieldSetup& setup,
                                                        glm::ivec3 refinedDims) {
    const std::size_t count =
        std::size_t(refinedDims.x) * std::size_t(refinedDims.y) * std::size_t(refinedDims.z);
    LW_RETURN_IF_FAILED(refined.reserve(count, "thick slices: refined field"));
    const field::RefineGrid grid{dims.x, dims.y,          dims.z,
                                 dims.x, dims.y,          1,
                                 1,      setup.factors.z, setup.monotoneAlongSlices && dims.z > 2};
    const bool bridge = setup.thinWallMm > 0.0 && dims.x >= 3 && dims.y >= 3;
    const ThinShellSlices pair =
        thinShellSlices(dims.x, dims.y, setup.spacingI, setup.spacingJ, setup.stepsPerMm,
                        setup.limitMm, bridge ? setup.thinWallMm : 0.0);
    field::refineAlongSlicesKernel<<<planeGrid(dims.x, dims.y, dims.z - 1),
                                     dim3(tuning::kPixelBlockX, tuning::kPixelBlockY), 0,
                                     stream.get()>>>(distance.data(), grid, pair, bridge,
                                                     refined.data(), faceSlots.data());
    LW_CUDA_LAUNCHED("thickSlices::refineAlongSlices");
    return CudaStatus::success();
}

CudaStatus ThickSliceFieldCuda::Impl::resetFaceSlots() {
    LW_RETURN_IF_FAILED(faceSlots.reserve(6, "thick slices: face maxima"));
    LW_RETURN_IF_FAILED(faceSlotsDownloaded.reserve(6, "thick slices: face maxima"));
    LW_CUDA_TRY(cudaMemsetAsync(faceSlots.data(), 0, 6 * sizeof(unsigned), stream.get()),
                "thick slices: face maxima reset");
    return CudaStatus::success();
}

CudaStatus ThickSliceFieldCuda::Impl::findFaceMaxima(glm::ivec3 refinedDims) {
    field::faceMaximaKernel<<<dim3(tuning::kFaceMaximaBlocks, 6), tuning::kFaceMaximaBlock, 0,
                              stream.get()>>>(refined.data(), refinedDims.x, refinedDims.y,
                                              refinedDims.z, faceSlots.data());
    LW_CUDA_LAUNCHED("thickSlices::faceMaxima");
    return CudaStatus::success();
}

// Queues the faces' maxima's download (read after the stream is synchronised).
CudaStatus ThickSliceFieldCuda::Impl::downloadFaceSlots() {
    LW_CUDA_TRY(cudaMemcpyAsync(faceSlotsDownloaded.data(), faceSlots.data(), 6 * sizeof(unsigned),
                                cudaMemcpyDeviceToHost, stream.get()),
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
    LW_RETURN_IF_FAILED(d.resetFaceSlots());
    if (refinesAlongSlicesOnly(setup, d.dims)) {
        LW_RETURN_IF_FAILED(d.refineAlongSlices(setup, refinedDims));
    } else {
        LW_RETURN_IF_FAILED(d.refine(setup, refinedDims));
        LW_RETURN_IF_FAILED(d.bridgeThinWalls(setup, refinedDims));
        LW_RETURN_IF_FAILED(d.findFaceMaxima(refinedDims));
    }
    LW_RETURN_IF_FAILED(d.downloadFaceSlots());
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
    return d.source.bytes() + d.rowNear.bytes() + d.columnNear.bytes() + d.distance.bytes() +
           d.refined.bytes();
}

void ThickSliceFieldCuda::release() {
    Impl& d = *m_impl;
    d.source.release();
    d.rowNear.release();
    d.columnNear.release();
    d.distance.release();
    d.refined.release();
    d.faceSlots.release();
    d.dims = glm::ivec3(0);
}

} // namespace lw::kernels::cuda
