#pragma once

// The review's work that can take longer than a frame: both panels' pictures for one iso-value
// and camera, which the engine's ReviewFrameRenderer makes (render/review_frame.h: the surface,
// the silhouette, the shaded iso panel on the device or the host). It runs on one worker thread,
// one request at a time; RenderScheduler (render_scheduler.h) feeds it and keeps the UI thread
// free. The worker adds what is Qt's: the silhouette panel's shared textures, QImage results.

#include "lw/core/progress.h"
#include "lw/render/review_frame.h"
#include "lw/volume/volume.h"
#include "review/panel_render_job.h"
#include "review/silhouette_textures.h"

#include <QImage>
#include <QString>
#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>

class QOffscreenSurface;

namespace lw::gui {

struct FrameRequest {
    std::uint64_t id = 0;
    std::uint64_t settingsGeneration = 0; // results of older settings are dropped
    // What both panels show (render/review_frame.h): the worker asks the engine for it once.
    // Its cancel token is set from `cancel` by the worker.
    render::ReviewFrameRequest frame;
    // The silhouette panel can draw a texture (its GL view): method 3 on CUDA then writes its
    // lines into one of the worker's textures (silhouette_textures.h) instead of host memory.
    bool silhouetteToTexture = false;
    // The engine's GL work (method 1, the iso panel) goes into the worker's context that shares
    // the panels' (a real GPU's display: a thread that used GLX cannot make EGL current).
    bool sharedGl = false;
    // For those textures and that context: made on the UI thread by RenderScheduler, which outlives
    // the worker.
    QOffscreenSurface* textureSurface = nullptr;
    std::shared_ptr<core::CancelToken> cancel = std::make_shared<core::CancelToken>();
    std::chrono::steady_clock::time_point requested; // set by RenderScheduler::request
    // The lines' colour, width and background, and whether they go over the iso panel too: the
    // worker draws the host mask into the panels' images, so the UI thread only shows them.
    ReviewSettings appearance;
};

struct FrameResult {
    std::uint64_t id = 0;
    std::uint64_t settingsGeneration = 0;
    double iso = 0.0;
    render::Camera camera;
    std::shared_ptr<const render::Mesh> mesh; // set when the request wanted one
    double meshMs = 0.0;
    // The surface's triangles, wherever it was made (the device's count on the device path).
    std::optional<std::size_t> surfaceTriangles;
    std::optional<render::SilhouetteFrame> silhouette;
    // Set when the silhouette went into a texture (silhouette->lines is then empty).
    std::shared_ptr<const LinesTexture> linesTexture;
    // Otherwise the silhouette panel's image (linesToImage in the request's appearance), and the
    // lines over the iso panel where the appearance asks for them.
    QImage silhouetteImage;
    QImage isoOverlay;
    QImage isoImage;             // when the request wanted it
    std::vector<float> isoDepth; // its depth buffer, top row first (picking)
    render::Camera isoCamera;
    double isoRenderMs = 0.0;
    bool isoOnDevice = false; // the iso image came from the device (no host mesh)
    render::SilhouetteMethod method = render::SilhouetteMethod::ZBuffer;
    int brickCells = 0;
    glm::ivec3 refinement{1}; // how the drawn volume split the loaded one's cells (oversampling)
    std::shared_ptr<const volume::Volume> drawnVolume; // render::ReviewFrame::drawnVolume
    QString backend;                                   // the back-end that actually ran
    QString backendNote;
    QString error; // empty on success
    bool cancelled = false;
    std::chrono::steady_clock::time_point requested; // the request's
    double workerMs = 0.0;                           // run() from start to end
    render::ReviewFrame::StageMs stageMs;            // the engine's part of it, by stage
};

class RenderWorker {
public:
    explicit RenderWorker(std::shared_ptr<const volume::Volume> volume);
    ~RenderWorker();
    RenderWorker(const RenderWorker&) = delete;
    RenderWorker& operator=(const RenderWorker&) = delete;

    // On the worker thread only. Never throws: errors and cancellation come back in the result.
    FrameResult run(const FrameRequest& request);
    // An export's panels (panel_render_job.h) with this worker's engine and GL, on the worker
    // thread; `surface` as FrameRequest::textureSurface. Throws core::Error.
    std::pair<QImage, QImage> renderPanels(const PanelRenderJob& job, QOffscreenSurface* surface,
                                           PanelVectors* vectors);
    // Drops renderers, contexts and caches (on the worker thread, before it stops: a GL context
    // belongs to the thread that made it).
    void release();

private:
    render::GlFrameTarget* frameTargetFor(const FrameRequest& request,
                                          std::shared_ptr<const LinesTexture>& token);
    void takeFrame(render::ReviewFrame&& frame, const ReviewSettings& appearance,
                   FrameResult& result) const;

    SilhouetteTextures& textures(QOffscreenSurface* surface);

    // The silhouette panel's textures and their context (made at the first request for one),
    // declared before the engine's frames, whose GL objects live in that context: destroyed
    // after them.
    std::unique_ptr<SilhouetteTextures> m_textures;
    std::unique_ptr<render::GlContext> m_sharedContext; // m_textures' context for the engine
    render::ReviewFrameRenderer m_frames;
};

} // namespace lw::gui
