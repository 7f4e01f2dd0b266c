#pragma once

// Method 2 on the CUDA back-end (lw/kernels/cuda/raycast_silhouette_cuda.h) behind the
// SilhouetteRenderer interface, with the CPU RayCastSilhouetteRenderer's mode a/b rules: the
// active cells (and the macro occupancy the visibility rays skip with) are kept while the
// iso-value stays (mode a) or rebuilt every frame (mode b). The volume is uploaded on the first
// frame after setVolume. The chunked variant (brickCells > 0) runs on the CPU renderer for now
// (no streaming through a device memory budget yet), and so does every frame of a volume for which
// the device ran out of memory; backendName() then says "cpu".

#include "lw/render/raycast_silhouette_renderer.h"
#include "lw/render/silhouette_renderer.h"

#include <memory>

namespace lw::render {

class CudaRayCastSilhouetteRenderer final : public SilhouetteRenderer {
public:
    CudaRayCastSilhouetteRenderer();
    ~CudaRayCastSilhouetteRenderer() override;
    CudaRayCastSilhouetteRenderer(const CudaRayCastSilhouetteRenderer&) = delete;
    CudaRayCastSilhouetteRenderer& operator=(const CudaRayCastSilhouetteRenderer&) = delete;

    SilhouetteMethod method() const override { return SilhouetteMethod::RayCastVisibility; }
    std::string_view backendName() const override;
    void setVolume(const volume::Volume& volume) override;
    void releaseVolume() override;
    SilhouetteFrame renderFrame(const Camera& camera, const SilhouetteSettings& settings) override;

private:
    SilhouetteFrame renderOnGpu(const Camera& camera, const SilhouetteSettings& settings);

    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
