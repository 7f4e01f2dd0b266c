#pragma once

// Stroke pruning on the device (kernels in stroke_kernels.cuh): the short groups of line pixels
// of a device mask cleared in place, before the mask goes to the host or into a GL texture, so
// that the host's flood fill (PixelMask::removeComponentsSmallerThan, single-threaded) is not on
// the frame's path. The result equals PixelMask::pruneStrokes bit for bit: both find the same
// groups and the same bridges.
// Internal: CUDA types allowed.

#include "dispatch.h"

#include <cstddef>
#include <cstdint>

namespace lw::kernels::cuda {

class StrokePruning {
public:
    // `mask`: width * height bytes on the device, non-zero = line. Groups of fewer than
    // `minPixels` pixels (joined across gaps of `gapPixels`) are cleared, and with gapPixels >= 1
    // the one-pixel gaps between stroke ends drawn (PixelMask::pruneStrokes); minPixels <= 1:
    // nothing.
    // Queued on `stream`; nothing is synchronised.
    CudaStatus run(std::uint8_t* mask, int width, int height, int minPixels, int gapPixels,
                   cudaStream_t stream);
    std::size_t deviceBytes() const { return m_labels.bytes() + m_sizes.bytes(); }

private:
    dispatch::DeviceBuffer<std::uint32_t> m_labels, m_sizes;
};

// A pruned device mask into a GL texture's array (GL_R8, mapped by the caller), queued on
// `stream`.
CudaStatus copyMaskToSurface(const std::uint8_t* mask, int width, int height,
                             cudaSurfaceObject_t target, cudaStream_t stream);

} // namespace lw::kernels::cuda
