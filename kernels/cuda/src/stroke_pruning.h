#pragma once

// Stroke pruning on the device (kernels in stroke_kernels.cuh): the short groups of line pixels
// of a device mask cleared in place, before the mask goes to the host or into a GL texture, so
// that the host's search (PixelMask::removeComponentsSmallerThan, single-threaded) is not on
// the frame's path. The result equals PixelMask::pruneStrokes bit for bit: both find the same
// groups, the same bridges and the same pieces.
// Internal: CUDA types allowed.

#include "dispatch.h"

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace lw::kernels::cuda {

class StrokePruning {
public:
    // `mask`: width * height bytes on the device, non-zero = line. Groups of fewer than
    // `minPixels` pixels (joined across gaps of `gapPixels`) are cleared, and with gapPixels >= 1
    // the one-pixel gaps between stroke ends drawn and then the 8-connected pieces under
    // minPiecePixels(minPixels) cleared (PixelMask::pruneStrokes); minPixels <= 1: nothing.
    // Queued on `stream`; nothing is synchronised.
    CudaStatus run(std::uint8_t* mask, int width, int height, int minPixels, int gapPixels,
                   cudaStream_t stream);
    std::size_t deviceBytes() const { return m_labels.bytes() + m_sizes.bytes(); }

private:
    // The groups within `reach` of fewer than `minPixels` pixels cleared: labels, unions, sizes,
    // clearing (four launches; m_sizes must hold the mask's pixels).
    CudaStatus clearShortGroups(std::uint8_t* mask, int width, int height, int reach, int minPixels,
                                cudaStream_t stream);
    dispatch::DeviceBuffer<std::uint32_t> m_labels, m_sizes;
};

// A device mask's way to the host memory a frame hands out (PixelMask, pageable): through
// page-locked memory kept between frames. A copy into pageable memory is staged by the driver in
// chunks and synchronised (some 0.5 ms a megabyte on the H100 machine, against 0.05 ms for a
// direct transfer plus a host memcpy; method 3's 0.6 ms view was a third that copy).
class MaskDownload {
public:
    // Queues the copy of `pixels` bytes of `deviceMask` on `stream`.
    CudaStatus queue(const std::uint8_t* deviceMask, std::size_t pixels, cudaStream_t stream) {
        m_pixels = pixels;
        if (pixels == 0)
            return CudaStatus::success();
        LW_RETURN_IF_FAILED(m_staging.reserve(pixels, "cudaMallocHost(mask)"));
        LW_CUDA_TRY(
            cudaMemcpyAsync(m_staging.data(), deviceMask, pixels, cudaMemcpyDeviceToHost, stream),
            "cudaMemcpy(mask)");
        return CudaStatus::success();
    }
    // Once the stream has been synchronised: the queued mask into `hostMask`.
    void deliver(std::uint8_t* hostMask) const {
        if (m_pixels > 0)
            std::memcpy(hostMask, m_staging.data(), m_pixels);
    }

private:
    dispatch::PinnedBuffer<std::uint8_t> m_staging;
    std::size_t m_pixels = 0;
};

// A pruned device mask into a GL texture's array (GL_R8, mapped by the caller), queued on
// `stream`.
CudaStatus copyMaskToSurface(const std::uint8_t* mask, int width, int height,
                             cudaSurfaceObject_t target, cudaStream_t stream);

} // namespace lw::kernels::cuda
