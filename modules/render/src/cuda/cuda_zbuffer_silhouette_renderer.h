#pragma once

// Method 3 on the CUDA back-end: marching cubes and the z-buffer rasterizer as CUDA kernels
// (lw/kernels/cuda), behind the same SilhouetteRenderer interface and with the same mode a/b
// rules as the CPU ZBufferSilhouetteRenderer. The image equals the CPU's: both back-ends evaluate
// kernels/common's rules.
//
// Where the volume lives (gpu_memory_plan.h), decided per frame from settings.gpuMemoryBudget:
//   whole volume  uploaded once per setVolume; mode a keeps the mesh on the device and only the
//                 view passes run per frame
//   slabs         the chunked (L) variant, and any volume too large for the budget: slabs of cell
//                 layers stream from host memory through two device slots, each slab's mesh drawn
//                 into the shared z-buffers and dropped; re-extracted every frame (as the CPU L)
// Out of device memory, a frame falls back from the whole volume to slabs, and from slabs to the
// CPU renderer (logged; backendName() then says "cpu").

#include "lw/render/gpu_memory_plan.h"
#include "lw/render/iso_surface.h"
#include "lw/render/silhouette_renderer.h"

#include <memory>

namespace lw::render {

class CudaZBufferSilhouetteRenderer final : public SilhouetteRenderer {
public:
    CudaZBufferSilhouetteRenderer();
    ~CudaZBufferSilhouetteRenderer() override;
    CudaZBufferSilhouetteRenderer(const CudaZBufferSilhouetteRenderer&) = delete;
    CudaZBufferSilhouetteRenderer& operator=(const CudaZBufferSilhouetteRenderer&) = delete;

    SilhouetteMethod method() const override { return SilhouetteMethod::ZBuffer; }
    std::string_view backendName() const override;
    void setVolume(const volume::Volume& volume) override;
    void releaseVolume() override;
    SilhouetteFrame renderFrame(const Camera& camera, const SilhouetteSettings& settings) override;
    const Mesh* surfaceMesh() const override;

    // Host -> device copy of the voxels of the bound volume (0 before the first whole-volume
    // frame).
    double uploadMs() const;
    GpuResidency lastResidency() const;

private:
    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
