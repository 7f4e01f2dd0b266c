#pragma once

// Stroke pruning on the GPU for a mask in host memory: uploaded, pruned by the kernels methods
// 2 and 3 run on their device masks, downloaded. The tests hold it against the host's
// PixelMask::removeComponentsSmallerThan. Public header: no CUDA types.

#include "lw/kernels/cuda/cuda_status.h"

#include <cstdint>

namespace lw::kernels::cuda {

// `mask`: width * height bytes, non-zero = line; pruned in place (see StrokePruning::run).
CudaStatus pruneStrokesOnDevice(std::uint8_t* mask, int width, int height, int minPixels,
                                int gapPixels);

} // namespace lw::kernels::cuda
