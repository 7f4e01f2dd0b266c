#pragma once

// Method 3 on the CPU: an own software z-buffer rasterizer (see
// lw/kernels/cpu/zbuffer_rasterizer_cpu.h). Per frame:
//   depth pass   the mesh's triangles into zbuffer1 (top-left rule, perspective-correct depth)
//   silhouette   Burns' segment of every triangle from the per-vertex normals, into zbuffer2
//                (nearest segment per pixel, atomic max on the inverted depth as in the paper)
//   colour pass  silhouette where zbuffer2 is not behind zbuffer1 (see resolveSilhouette)
// Chunked (settings.brickCells > 0): the triangles are partitioned by the brick of the cell they
// came from and the bricks go through the depth and silhouette passes one after the other into
// the same buffers; the colour pass runs once. Because both buffers keep a per-pixel maximum,
// the result is identical to the whole-volume pass.

#include "lw/render/iso_surface.h"
#include "lw/render/silhouette_renderer.h"

#include <memory>

namespace lw::render {

class ZBufferSilhouetteRenderer final : public SilhouetteRenderer {
public:
    ZBufferSilhouetteRenderer();
    ~ZBufferSilhouetteRenderer() override;
    ZBufferSilhouetteRenderer(const ZBufferSilhouetteRenderer&) = delete;
    ZBufferSilhouetteRenderer& operator=(const ZBufferSilhouetteRenderer&) = delete;

    SilhouetteMethod method() const override { return SilhouetteMethod::ZBuffer; }
    std::string_view backendName() const override { return "cpu"; }
    void setVolume(const volume::Volume& volume) override;
    SilhouetteFrame render(const Camera& camera, const SilhouetteSettings& settings) override;

    // The mesh of the last frame (cached in mode a); empty before the first frame. The shaded
    // iso-surface panel draws this one, so both panels show the same surface.
    const Mesh& mesh() const;

    // Depth tolerance of the colour pass as a share of the depth-key range of the volume's box
    // for the current camera: 0.2 %, i.e. about one voxel of a 512-voxel-deep volume. It only
    // has to absorb float rounding between the two buffers and the sampling of the surface
    // near a contour; the steep depth at the contour itself is handled by the 3x3 neighbourhood.
    static constexpr double kRelativeDepthEpsilon = 0.002;

private:
    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
