#pragma once

// Method 3: an own z-buffer rasterizer, on the CPU (lw/kernels/cpu/zbuffer_rasterizer_cpu.h) or
// the CUDA back-end (lw/kernels/cuda/zbuffer_cuda.h) behind one frame logic. Per frame:
//   depth pass   the surface's triangles into zbuffer1 (top-left rule, perspective-correct depth)
//   silhouette   Burns' segment of every triangle from the per-vertex normals, into zbuffer2
//                (nearest segment per pixel, atomic max on the inverted depth as in the paper)
//   colour pass  silhouette where zbuffer2 is not behind zbuffer1 (see resolveSilhouette)
// What every back-end shares is this class: mode a keeps the whole surface between frames at one
// iso-value, mode b extracts every frame; whether the surface is closed (then back faces are
// culled); the depth tolerance; and, out of device memory, the next way down (CUDA: whole volume
// -> slabs -> the CPU, logged). What a back-end does is its kernel set (src/zbuffer_kernel_set.h).
// Chunked (settings.brickCells > 0), the paper's L variant for memory-limited devices: no surface
// is kept. Each piece (CPU: an active brick, its min/max admitting the iso-value; CUDA: a slab of
// cell layers streamed through the device budget) is extracted on its own, its silhouette
// segments drawn into zbuffer2 and its triangles into zbuffer1, and its geometry dropped before
// the next; the colour pass runs once. A piece's vertices are bit-identical to the whole
// surface's and both buffers keep per-pixel maxima, so the image is identical to S's. L trades
// time for memory: it re-extracts every frame, mode a included.

#include "lw/core/image.h"
#include "lw/render/iso_surface.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/render/visibility_tolerance.h"

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

namespace lw::render {

class ZBufferSilhouetteRenderer final : public SilhouetteRenderer {
public:
    // Backend::Cuda throws core::Error where this build has no CUDA back-end; Auto is the CPU
    // here (renderer_factory resolves Auto).
    explicit ZBufferSilhouetteRenderer(Backend backend = Backend::Cpu);
    ~ZBufferSilhouetteRenderer() override;
    ZBufferSilhouetteRenderer(const ZBufferSilhouetteRenderer&) = delete;
    ZBufferSilhouetteRenderer& operator=(const ZBufferSilhouetteRenderer&) = delete;

    SilhouetteMethod method() const override { return SilhouetteMethod::ZBuffer; }
    // The back-end of the last frame: "cuda", or "cpu" (also after a fall back to the CPU).
    std::string_view backendName() const override;
    bool drawsToFrameTargets() const override;
    void setVolume(const volume::Volume& volume) override;
    void setVolumeWithDeviceCopy(const volume::Volume& volume, DeviceVoxelCopy copy) override;
    void releaseVolume() override;
    SilhouetteFrame renderFrame(const Camera& camera, const SilhouetteSettings& settings) override;

    // The surface of the last frame (kept in mode a); empty before the first frame. The shaded
    // iso-surface panel draws this one, so both panels show the same surface. After a frame
    // that kept none (L) the whole surface is extracted here, on the first call.
    const Mesh& mesh() const;
    const Mesh* surfaceMesh() const override { return &mesh(); }
    std::optional<Mesh> contourTriangles(const Camera& camera) const override;

    // The shaded iso panel on the device (CUDA): the kept whole surface of settings' iso-value
    // (extracted here when the kept one is of another, or in mode b) rasterized at `camera` and
    // lit there, as shadeSurfaceCpu would light the host mesh. Only the image and its depth
    // leave the device; no host mesh is made. nullopt where this renderer cannot: the CPU
    // back-end, L (brickCells), a volume over the device budget, after a fall back, or out of
    // device memory (then logged, and the next frame starts afresh).
    struct DeviceShadedSurface {
        core::ImageRgba8 image;
        std::vector<float> depth; // with wantDepth: shadeSurfaceCpu's depth
        std::size_t triangles = 0;
        double extractMs = 0.0; // 0 when the kept surface was shaded
        double shadeMs = 0.0;   // rasterizing, lighting and the copy to the host (CUDA events)
    };
    std::optional<DeviceShadedSurface> shadeOnDevice(const Camera& camera,
                                                     const SilhouetteSettings& settings,
                                                     const SurfaceShading& shading, bool wantDepth);

    // Depth tolerance of the colour pass: lw/render/visibility_tolerance.h (method 1's resolve
    // uses the same), in depth keys for `camera` and the volume's box (the CPU and CUDA
    // back-ends both use it).
    static float depthEpsilon(const Camera& camera, const volume::Volume& volume);

private:
    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
