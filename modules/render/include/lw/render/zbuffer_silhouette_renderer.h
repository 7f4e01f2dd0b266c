#pragma once

// Method 3 on the CPU: an own software z-buffer rasterizer (see
// lw/kernels/cpu/zbuffer_rasterizer_cpu.h). Per frame:
//   depth pass   the mesh's triangles into zbuffer1 (top-left rule, perspective-correct depth)
//   silhouette   Burns' segment of every triangle from the per-vertex normals, into zbuffer2
//                (nearest segment per pixel, atomic max on the inverted depth as in the paper)
//   colour pass  silhouette where zbuffer2 is not behind zbuffer1 (see resolveSilhouette)
// Chunked (settings.brickCells > 0), the paper's L variant for memory-limited devices: no mesh is
// kept. Each active brick (its min/max admit the iso-value) is extracted on its own, its
// silhouette segments drawn into zbuffer2 and its triangles into zbuffer1, and its geometry dropped
// before the next brick (one brick in flight per worker thread); the colour pass runs once. The
// brick's vertices are bit-identical to the whole mesh's and both buffers keep per-pixel maxima, so
// the image is identical to the whole-volume pass. L trades time for memory: it re-extracts every
// frame, mode a included (only the brick grid is cached).

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
    SilhouetteFrame renderFrame(const Camera& camera, const SilhouetteSettings& settings) override;

    // The mesh of the last frame (cached in mode a); empty before the first frame. The shaded
    // iso-surface panel draws this one, so both panels show the same surface. After an L frame
    // the whole mesh is extracted here, on the first call (L frames themselves never hold it).
    const Mesh& mesh() const;
    const Mesh* surfaceMesh() const override { return &mesh(); }

    // Depth tolerance of the colour pass as a share of the depth-key range of the volume's box
    // for the current camera: 0.2 %, i.e. about one voxel of a 512-voxel-deep volume. It only
    // has to absorb float rounding between the two buffers and the sampling of the surface
    // near a contour; the steep depth at the contour itself is handled by the 3x3 neighbourhood.
    static constexpr double kRelativeDepthEpsilon = 0.002;
    // That tolerance in depth keys for `camera` (the CPU and CUDA back-ends both use it).
    static float depthEpsilon(const Camera& camera, const volume::Volume& volume);

private:
    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
