#pragma once

// Method 3 on the CUDA back-end: marching cubes and the z-buffer rasterizer as CUDA kernels
// (lw/kernels/cuda), behind the same SilhouetteRenderer interface and with the same mode a/b
// rules as the CPU ZBufferSilhouetteRenderer. The volume is uploaded once per setVolume (lazily,
// on the first frame); mode a keeps the mesh on the device and only the view passes run per frame.
// The image equals the CPU's: both back-ends evaluate kernels/common's rules.
//
// The chunked variant (brickCells > 0) runs on the CPU renderer for now (streaming bricks through
// a device memory budget is not built yet); backendName() then says "cpu".

#include "lw/render/iso_surface.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/render/zbuffer_silhouette_renderer.h"

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
    SilhouetteFrame render(const Camera& camera, const SilhouetteSettings& settings) override;
    const Mesh* surfaceMesh() const override;

    // Host -> device copy of the voxels of the bound volume (0 before the first frame).
    double uploadMs() const;

private:
    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
