// Host dispatch of stroke pruning on the device (kernels in stroke_kernels.cuh).

#include "lw/kernels/cuda/stroke_pruning_cuda.h"
#include "pixel_launch.h"
#include "stroke_kernels.cuh"
#include "stroke_pruning.h"
#include "tuning.h"

#include <algorithm>
#include <cstring>
#include <memory>

namespace lw::kernels::cuda {

using dispatch::blocksFor;

CudaStatus StrokePruning::run(std::uint8_t* mask, int width, int height, int minPixels,
                              int gapPixels, cudaStream_t stream) {
    if (minPixels <= 1 || width <= 0 || height <= 0)
        return CudaStatus::success();
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    if (pixels >= std::size_t(kNotAStrokePixel))
        return CudaStatus::failure(CudaStatus::Code::Failed, "sk::initLabels",
                                   "the mask has more pixels than a 32-bit label can name");
    LW_RETURN_IF_FAILED(m_labels.reserve(pixels, "cudaMalloc(strokeLabels)"));
    LW_RETURN_IF_FAILED(m_sizes.reserve(pixels, "cudaMalloc(strokeSizes)"));
    LW_RETURN_IF_FAILED(
        clearShortGroups(mask, width, height, 1 + std::max(0, gapPixels), minPixels, stream));
    if (gapPixels < 1)
        return CudaStatus::success();
    const PixelLaunch launch = pixelLaunch(width, height);
    sk::findBridges<<<launch.grid, launch.block, 0, stream>>>(mask, width, height, m_sizes.data());
    LW_CUDA_LAUNCHED("sk::findBridges");
    sk::drawBridges<<<blocksFor(pixels, tuning::kStrokePixelBlock), tuning::kStrokePixelBlock, 0,
                      stream>>>(mask, std::uint32_t(pixels), m_sizes.data());
    LW_CUDA_LAUNCHED("sk::drawBridges");
    // The pieces the bridges did not join into a stroke long enough (PixelMask::pruneStrokes).
    return clearShortGroups(mask, width, height, 1, minPiecePixels(minPixels), stream);
}

CudaStatus StrokePruning::clearShortGroups(std::uint8_t* mask, int width, int height, int reach,
                                           int minPixels, cudaStream_t stream) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    const unsigned blocks = blocksFor(pixels, tuning::kStrokePixelBlock);
    const auto count = std::uint32_t(pixels);
    sk::initLabels<<<blocks, tuning::kStrokePixelBlock, 0, stream>>>(mask, count, m_labels.data(),
                                                                     m_sizes.data());
    LW_CUDA_LAUNCHED("sk::initLabels");
    const PixelLaunch launch = pixelLaunch(width, height);
    sk::uniteNeighbours<<<launch.grid, launch.block, 0, stream>>>(mask, width, height, reach,
                                                                  m_labels.data());
    LW_CUDA_LAUNCHED("sk::uniteNeighbours");
    sk::countGroups<<<blocks, tuning::kStrokePixelBlock, 0, stream>>>(mask, count, m_labels.data(),
                                                                      m_sizes.data());
    LW_CUDA_LAUNCHED("sk::countGroups");
    sk::clearShortGroups<<<blocks, tuning::kStrokePixelBlock, 0, stream>>>(
        mask, count, m_labels.data(), m_sizes.data(), std::uint32_t(minPixels));
    LW_CUDA_LAUNCHED("sk::clearShortGroups");
    return CudaStatus::success();
}

CudaStatus copyMaskToSurface(const std::uint8_t* mask, int width, int height,
                             cudaSurfaceObject_t target, cudaStream_t stream) {
    const PixelLaunch launch = pixelLaunch(width, height);
    sk::copyToSurface<<<launch.grid, launch.block, 0, stream>>>(mask, width, height, target);
    LW_CUDA_LAUNCHED("sk::copyToSurface");
    return CudaStatus::success();
}

struct HostMaskPruner::Impl {
    dispatch::Stream stream;
    // The mask goes up and down through page-locked memory (MaskDownload's note).
    dispatch::PinnedBuffer<std::uint8_t> staging;
    dispatch::DeviceBuffer<std::uint8_t> mask;
    StrokePruning pruning;
};

HostMaskPruner::HostMaskPruner() : m_impl(std::make_unique<Impl>()) {}
HostMaskPruner::~HostMaskPruner() = default;

CudaStatus HostMaskPruner::prune(std::uint8_t* mask, int width, int height, int minPixels,
                                 int gapPixels) {
    if (width <= 0 || height <= 0 || minPixels <= 1)
        return CudaStatus::success();
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    LW_RETURN_IF_FAILED(m_impl->stream.create());
    LW_RETURN_IF_FAILED(m_impl->mask.reserve(pixels, "cudaMalloc(mask)"));
    LW_RETURN_IF_FAILED(m_impl->staging.reserve(pixels, "cudaMallocHost(mask)"));
    cudaStream_t st = m_impl->stream.get();
    std::uint8_t* deviceMask = m_impl->mask.data();
    std::uint8_t* staging = m_impl->staging.data();
    std::memcpy(staging, mask, pixels);
    LW_CUDA_TRY(cudaMemcpyAsync(deviceMask, staging, pixels, cudaMemcpyHostToDevice, st),
                "cudaMemcpy(mask)");
    LW_RETURN_IF_FAILED(m_impl->pruning.run(deviceMask, width, height, minPixels, gapPixels, st));
    LW_CUDA_TRY(cudaMemcpyAsync(staging, deviceMask, pixels, cudaMemcpyDeviceToHost, st),
                "cudaMemcpy(mask)");
    LW_CUDA_TRY(cudaStreamSynchronize(st), "HostMaskPruner::prune");
    std::memcpy(mask, staging, pixels);
    return CudaStatus::success();
}

CudaStatus pruneStrokesOnDevice(std::uint8_t* mask, int width, int height, int minPixels,
                                int gapPixels) {
    HostMaskPruner pruner;
    return pruner.prune(mask, width, height, minPixels, gapPixels);
}

} // namespace lw::kernels::cuda
