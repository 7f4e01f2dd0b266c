#pragma once

// Method 1 behind the common SilhouetteRenderer interface: marching cubes on the CPU
// (extractIsoSurface), the mesh uploaded into GL buffers, and SilhouetteGlRenderer's two passes
// (depth, then the geometry shader's silhouette segments depth-tested against it), read back
// into a PixelMask so it can be compared and benchmarked like methods 2 and 3.
//
// Mode a extracts and uploads only when the volume, iso-value or brick size changed; mode b
// extracts and uploads every frame. StageTimes: extractMs = marching cubes + upload (the paper's
// CUDA path writes straight into the GL buffers, so the upload belongs to getting the mesh there);
// drawMs = both GL passes, glFinish'ed so the GPU work is inside the interval, plus read-back and
// mask conversion.
//
// L variant (settings.brickCells > 0), the paper's chunked method 1 for volumes whose mesh does
// not fit in memory: the bricks of a volume::BrickGrid that may hold the surface are processed
// serially, one brick's geometry held at a time on the CPU and the GPU. Each brick's surface
// (kernels::cpu::BrickSurfaceExtractor: the whole mesh's triangles of that brick, bit-identical
// vertices) is uploaded, its surface drawn into depth and, in the background colour, into colour
// (polygon offset as in S), then its silhouette lines depth-tested, writing their depth. A later
// nearer surface paints over an earlier hidden line and an earlier nearer surface or line rejects
// a later one, so the mask equals S's whatever the brick order (SilhouetteGlOptions). Visibility
// off: lines only, no depth test. L trades time for memory: even in mode a it caches nothing big
// (only the brick grid's per-brick min/max) and re-extracts every active brick every frame;
// mode b also rebuilds the grid. extractMs = grid + per-brick extraction and upload; drawMs =
// clear + per-brick draws + read-back. An L frame frees the whole mesh (mesh() is then empty);
// renderIsoPanel() still extracts and draws the whole mesh. With the CUDA extraction the pieces
// are the CUDA back-end's streamed slabs instead of CPU bricks (cell layers cropped to the rows
// that can hold the surface, through settings.gpuMemoryBudget, written into the GL buffers by
// interop): the same triangles, so the same mask.
//
// Only built with LINEWORK_GL=1 (src/gl/); use createSilhouetteRenderer() to get one portably.

#include "lw/core/image.h"
#include "lw/render/iso_surface.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/silhouette_renderer.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace lw::render {

class GlContext;

// What the last render() held and drew (S: the whole mesh as one "brick").
struct GeometryShaderFrameStats {
    std::size_t peakUploadedTriangles = 0; // most triangles in the GL buffers at once
    std::size_t bricksDrawn = 0;           // bricks with triangles, uploaded and drawn
};

class GeometryShaderSilhouetteRenderer final : public SilhouetteRenderer {
public:
    // Creates its own headless EGL context; throws core::Error naming why none could be made.
    GeometryShaderSilhouetteRenderer();
    // Uses the caller's context, which must outlive this renderer (GUI: QOpenGLWidget's).
    explicit GeometryShaderSilhouetteRenderer(GlContext& context);
    ~GeometryShaderSilhouetteRenderer() override;
    GeometryShaderSilhouetteRenderer(const GeometryShaderSilhouetteRenderer&) = delete;
    GeometryShaderSilhouetteRenderer& operator=(const GeometryShaderSilhouetteRenderer&) = delete;

    SilhouetteMethod method() const override { return SilhouetteMethod::GeometryShader; }
    // "gl", or "cuda+gl" after useCudaExtraction().
    std::string_view backendName() const override;
    void setVolume(const volume::Volume& volume) override;
    void setVolumeWithDeviceCopy(const volume::Volume& volume, DeviceVoxelCopy copy) override;
    void releaseVolume() override;
    SilhouetteFrame renderFrame(const Camera& camera, const SilhouetteSettings& settings) override;

    // Whole-volume (S) frames extract on the CUDA back-end, which writes the GL buffers directly
    // (CUDA-GL interop; through host memory where interop fails). Throws core::Error where this
    // build has no CUDA with GL interop. L frames then stream slabs through the device.
    void useCudaExtraction();

    // The shaded iso-surface panel for the same camera and settings (extracts first if the
    // cached mesh does not match them), RGBA8 top row first: `render --panel both`'s left half.
    core::ImageRgba8 renderIsoPanel(const Camera& camera, const SilhouetteSettings& settings);
    std::optional<core::ImageRgba8> shadedIsoPanel(const Camera& camera,
                                                   const SilhouetteSettings& settings) override {
        return renderIsoPanel(camera, settings);
    }

    // The review's iso panel in the caller's look (`options`, its panel Iso): the whole mesh
    // (extracted when the cached one is of other settings, or always with `forceExtract`),
    // shaded for `camera`, with its surface depth where `depth` is given (top row first, [0, 1],
    // 1 where nothing was drawn: for picking). With the CUDA extraction the mesh never leaves
    // the device: the GL buffers it was written into are drawn as they are.
    struct IsoPanelFrame {
        core::ImageRgba8 image;
        std::size_t triangles = 0; // in the GL buffers (the device's count with CUDA)
        double extractMs = 0.0;    // 0 when the cached mesh was drawn
        double drawMs = 0.0;       // draw and read-back
    };
    // With `cudaShading` and the CUDA extraction, the panel is lit on the device from CUDA's own
    // copy of the surface (as shadeSurfaceCpu would light it) instead of drawn by GL, unless
    // options.linesOnIso asks GL's lines over it.
    IsoPanelFrame renderIsoPanel(const Camera& camera, const SilhouetteSettings& settings,
                                 const SilhouetteGlOptions& options, bool forceExtract,
                                 std::vector<float>* depth, bool cudaShading = false);
    // Whether whole meshes are extracted on the CUDA device (useCudaExtraction).
    bool extractsOnDevice() const;

    // The mesh of the last S frame or iso panel (cached in mode a); empty before the first frame
    // and after an L frame.
    const Mesh& mesh() const;
    // mesh(), or null where the renderer keeps none (before the first frame, after an L frame):
    // the caller then extracts the surface itself (surfaceOfFrame).
    const Mesh* surfaceMesh() const override;
    std::optional<Mesh> contourTriangles(const Camera& camera) const override;
    const GeometryShaderFrameStats& lastFrameStats() const;
    // The triangle count of each brick that may hold the surface, in the order an L frame
    // with `brickCells` draws them (the same per-brick extraction; for checks and tooling).
    static std::vector<std::size_t> brickTriangleCounts(const volume::Volume& volume,
                                                        double isoReal, int brickCells);
    // "vendor | renderer | version" of the context in use.
    std::string contextDescription() const;

private:
    SilhouetteFrame renderBricks(const Camera& camera, const SilhouetteSettings& settings);

    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
