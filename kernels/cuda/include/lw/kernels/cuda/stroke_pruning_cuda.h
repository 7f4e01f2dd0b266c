#pragma once

// Stroke pruning on the GPU for a mask in host memory: uploaded, pruned by the kernels methods
// 2 and 3 run on their device masks, downloaded. Method 1 on the CUDA back-end reads its mask
// back from GL and prunes it here instead of in the host's single-threaded search. The tests
// hold it against the host's PixelMask::pruneStrokes. Public header: no CUDA
// types.

#include "lw/kernels/cuda/cuda_status.h"

#include <cstdint>
#include <memory>

namespace lw::kernels::cuda {

// Keeps its stream and device buffers from one frame to the next (a fresh cudaMalloc of the mask
// and the labels each frame would cost more than the pruning).
class HostMaskPruner {
public:
    HostMaskPruner();
    ~HostMaskPruner();
    HostMaskPruner(const HostMaskPruner&) = delete;
    HostMaskPruner& operator=(const HostMaskPruner&) = delete;

    // `mask`: width * height bytes, non-zero = line; pruned in place (see StrokePruning::run).
    // Returns when the pruned mask is back in `mask`; on failure `mask` is left as it was.
    CudaStatus prune(std::uint8_t* mask, int width, int height, int minPixels, int gapPixels);

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

// One mask with a pruner of its own (the tests' entry point).
CudaStatus pruneStrokesOnDevice(std::uint8_t* mask, int width, int height, int minPixels,
                                int gapPixels);

} // namespace lw::kernels::cuda
