#pragma once

// The review's work that can take longer than a frame: marching cubes for the iso panel and the
// CPU silhouette methods (2, 3, and method 1's chunked variant on a headless context). It runs
// on one worker thread, one request at a time; RenderScheduler (render_scheduler.h) feeds it and
// keeps the UI thread free.

#include "lw/core/progress.h"
#include "lw/render/camera.h"
#include "lw/render/gl_context.h"
#include "lw/render/iso_surface.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/render/suggestive_contours.h"
#include "lw/render/surface_sampling.h"
#include "lw/volume/volume.h"
#include "review/silhouette_textures.h"

#include <QImage>
#include <QString>
#include <cstdint>
#include <memory>
#include <optional>

class QOffscreenSurface;

namespace lw::gui {

struct FrameRequest {
    std::uint64_t id = 0;
    std::uint64_t settingsGeneration = 0; // results of older settings are dropped
    double iso = 0.0;
    bool wantMesh = false;       // the iso panel (and method 1 S) need the mesh at `iso`
    bool forceExtract = false;   // mode b: extract again even if the mesh is cached
    bool wantSilhouette = false; // render the silhouette here (methods 2, 3, method 1 L)
    bool suggestive = false;     // with the silhouette: its suggestive contours too
    // Render the shaded iso panel here too, on the worker's own headless GL context (the same
    // shaders as the panel's): used where the panels' GL is a software rasterizer, whose
    // vertex work would otherwise stall the UI thread.
    bool wantIsoImage = false;
    render::Camera isoCamera;
    render::SilhouetteGlOptions isoOptions;
    // Shade it with the CPU rasterizer (the same light and colours) instead of the worker's GL:
    // on a software OpenGL the rasterizer of method 3 is several times faster than llvmpipe.
    bool isoOnCpu = false;
    render::SilhouetteMethod method = render::SilhouetteMethod::ZBuffer;
    render::Backend backend = render::Backend::Auto;
    render::SilhouetteSettings settings;
    // The volume the methods draw: as loaded, or oversampled where its cells are coarse or its
    // slices thick (render/surface_sampling.h); the worker keeps the copy while this stays.
    render::VolumeSampling sampling;
    render::Camera camera;
    // The silhouette panel can draw a texture (its GL view): method 3 on CUDA then writes its
    // lines into one of the worker's textures (silhouette_textures.h) instead of host memory.
    bool silhouetteToTexture = false;
    // For those textures: made on the UI thread by RenderScheduler, which outlives the worker.
    QOffscreenSurface* textureSurface = nullptr;
    std::shared_ptr<core::CancelToken> cancel = std::make_shared<core::CancelToken>();
};

struct FrameResult {
    std::uint64_t id = 0;
    std::uint64_t settingsGeneration = 0;
    double iso = 0.0;
    render::Camera camera;
    std::shared_ptr<const render::Mesh> mesh; // set when the request wanted one
    double meshMs = 0.0;
    std::optional<render::SilhouetteFrame> silhouette;
    // Set when the silhouette went into a texture (silhouette->lines is then empty).
    std::shared_ptr<const LinesTexture> linesTexture;
    QImage isoImage;             // when the request wanted it
    std::vector<float> isoDepth; // its depth buffer, top row first (picking)
    render::Camera isoCamera;
    double isoRenderMs = 0.0;
    render::SilhouetteMethod method = render::SilhouetteMethod::ZBuffer;
    int brickCells = 0;
    glm::ivec3 refinement{1}; // how the drawn volume split the loaded one's cells (oversampling)
    QString backend;          // the back-end that actually ran
    QString backendNote;
    QString error; // empty on success
    bool cancelled = false;
};

class RenderWorker {
public:
    explicit RenderWorker(std::shared_ptr<const volume::Volume> volume);
    ~RenderWorker();
    RenderWorker(const RenderWorker&) = delete;
    RenderWorker& operator=(const RenderWorker&) = delete;

    // On the worker thread only. Never throws: errors and cancellation come back in the result.
    FrameResult run(const FrameRequest& request);
    // Drops renderers and caches (on the worker thread, before it stops: a headless GL context
    // belongs to the thread that made it).
    void release();

private:
    void prepareVolume(const FrameRequest& request);
    void renderSilhouette(const FrameRequest& request, FrameResult& result);
    void extractMesh(const FrameRequest& request, FrameResult& result);
    render::SilhouetteRenderer& rendererFor(const FrameRequest& request, FrameResult& result);
    void renderIsoImage(const FrameRequest& request, FrameResult& result);
    void keepRendererMesh(const FrameRequest& request, FrameResult& result);
    void addSuggestive(const FrameRequest& request, FrameResult& result);
    render::GlFrameTarget* frameTargetFor(const FrameRequest& request,
                                          const render::SilhouetteRenderer& renderer,
                                          std::shared_ptr<const LinesTexture>& token);

    // What, besides the iso-value, makes one surface differ from another: closed at the border
    // or not, and the gradient behind its normals.
    struct SurfaceForm {
        bool closed = false;
        render::GradientStencil stencil = render::GradientStencil::Central;
        static SurfaceForm of(const render::SilhouetteSettings& settings) {
            return {settings.closeAtBorder, settings.gradientStencil};
        }
        bool operator==(const SurfaceForm&) const = default;
    };

    std::shared_ptr<const volume::Volume> m_source; // as loaded
    // What the methods draw: m_source, or its oversampled copy (m_volumeSampling); everything
    // below is of this volume and goes when it changes.
    std::shared_ptr<const volume::Volume> m_volume;
    std::optional<render::VolumeSampling> m_volumeSampling;
    double m_volumeIso = 0.0;          // the iso-value of a shape-based copy
    bool m_volumeDependsOnIso = false; // thick slices: the copy is of one iso-value
    std::unique_ptr<render::IsoSurfaceExtractor> m_extractor;
    int m_extractorBricks = -1;
    SurfaceForm m_extractorForm; // the extractor's IsoSurfaceOptions
    std::unique_ptr<render::SilhouetteRenderer> m_renderer;
    render::Backend m_rendererBackend = render::Backend::Auto;
    QString m_backendNote;
    std::shared_ptr<const render::Mesh> m_mesh;
    double m_meshIso = 0.0;
    SurfaceForm m_meshForm; // m_mesh's (whoever extracted it)
    // Suggestive contours: the per-vertex derivatives of one iso-value's surface, kept while the
    // camera turns (the mesh they were computed on is held with them).
    std::unique_ptr<render::SuggestiveContourRenderer> m_suggestive;
    std::shared_ptr<const render::Mesh> m_suggestiveMesh;
    double m_suggestiveIso = 0.0;
    SurfaceForm m_suggestiveForm;
    // The worker's own GL for the iso panel (made on this thread at first use).
    std::unique_ptr<render::GlContext> m_glContext;
    std::unique_ptr<render::SilhouetteGlRenderer> m_isoGl;
    const render::Mesh* m_uploadedMesh = nullptr;
    std::shared_ptr<const render::Mesh> m_uploadedMeshOwner;
    // The silhouette panel's textures (made at the first request for one).
    std::unique_ptr<SilhouetteTextures> m_textures;
};

} // namespace lw::gui
