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
// L variant (settings.brickCells > 0): the extraction runs brick by brick, and because marching
// cubes orders the mesh canonically the mesh is identical to the S variant's. The bricks are not
// drawn one by one: the mesh does not record which brick a triangle came from, and a z-buffer
// draw of the same triangles in any grouping gives the same image, so L = chunked extraction +
// one draw.
//
// Only built with LINEWORK_GL=1 (src/gl/); use createSilhouetteRenderer() to get one portably.

#include "lw/core/image.h"
#include "lw/render/iso_surface.h"
#include "lw/render/silhouette_renderer.h"

#include <memory>
#include <string>

namespace lw::render {

class GlContext;
class SilhouetteGlRenderer;

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
    std::string_view backendName() const override { return "gl"; }
    void setVolume(const volume::Volume& volume) override;
    SilhouetteFrame render(const Camera& camera, const SilhouetteSettings& settings) override;

    // The shaded iso-surface panel for the same camera and settings (extracts first if the
    // cached mesh does not match them), RGBA8 top row first: `render --panel both`'s left half.
    core::ImageRgba8 renderIsoPanel(const Camera& camera, const SilhouetteSettings& settings);

    // The mesh of the last frame (cached in mode a); empty before the first frame.
    const Mesh& mesh() const;
    // "vendor | renderer | version" of the context in use.
    std::string contextDescription() const;

private:
    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
