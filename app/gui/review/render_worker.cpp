#include "review/render_worker.h"

#include "lw/core/error.h"
#include "review/qt_image.h"

#include <QObject>
#include <new>

namespace lw::gui {
namespace {

// The silhouette textures' Qt context as the engine's GlContext: made current for the
// silhouette alone, released before the iso panel's context is made current on this thread.
class TextureContext final : public render::GlContext {
public:
    explicit TextureContext(SilhouetteTextures& textures) : m_textures(textures) {}
    void makeCurrent() override { m_textures.makeCurrent(); }
    void doneCurrent() override { m_textures.done(); }
    std::string description() const override { return "the silhouette panel's textures"; }

private:
    SilhouetteTextures& m_textures;
};

// Whatever a frame made current in the textures' context is finished and released after it:
// the panels' contexts draw what it wrote next.
class ReleasedAfter {
public:
    explicit ReleasedAfter(SilhouetteTextures* textures) : m_textures(textures) {}
    ~ReleasedAfter() {
        if (m_textures)
            m_textures->done();
    }
    ReleasedAfter(const ReleasedAfter&) = delete;
    ReleasedAfter& operator=(const ReleasedAfter&) = delete;

private:
    SilhouetteTextures* m_textures;
};

} // namespace

RenderWorker::RenderWorker(std::shared_ptr<const volume::Volume> volume)
    : m_frames(std::move(volume)) {}

RenderWorker::~RenderWorker() = default;

void RenderWorker::release() {
    m_frames.release(); // its GL objects first, in the shared context where they live
    m_sharedContext.reset();
    m_textures.reset(); // their CUDA registrations and GL textures, in their context
}

SilhouetteTextures& RenderWorker::textures(QOffscreenSurface* surface) {
    if (!m_textures) {
        m_textures = std::make_unique<SilhouetteTextures>(surface);
        m_sharedContext = std::make_unique<TextureContext>(*m_textures);
    }
    return *m_textures;
}

FrameResult RenderWorker::run(const FrameRequest& request) {
    const auto start = std::chrono::steady_clock::now();
    FrameResult result;
    result.requested = request.requested;
    result.id = request.id;
    result.settingsGeneration = request.settingsGeneration;
    result.iso = request.frame.iso;
    result.camera = request.frame.camera;
    result.method = request.frame.method;
    result.brickCells = request.frame.settings.brickCells;
    try {
        render::ReviewFrameRequest frame = request.frame;
        frame.cancel = request.cancel.get(); // a newer request stops this frame in the kernels
        std::shared_ptr<const LinesTexture> texture;
        frame.silhouetteTarget = frameTargetFor(request, texture);
        if (frame.silhouetteTarget)
            frame.silhouetteTargetContext = m_sharedContext.get();
        if (request.sharedGl && request.textureSurface) {
            textures(request.textureSurface);
            frame.glContext = m_sharedContext.get();
        }
        const ReleasedAfter release(m_textures.get());
        render::ReviewFrame made = m_frames.render(frame);
        if (made.silhouette && made.silhouette->drewToTarget)
            result.linesTexture = std::move(texture);
        takeFrame(std::move(made), request.appearance, result);
        if (!result.isoImage.isNull())
            result.isoCamera = request.frame.isoCamera;
    } catch (const core::Cancelled&) {
        result.cancelled = true;
    } catch (const core::Error& error) {
        result.error = QString::fromStdString(error.what());
    } catch (const std::bad_alloc&) {
        result.error = QObject::tr("out of memory at iso-value %1 HU: choose a higher iso-value "
                                   "or chunking (settings)")
                           .arg(request.frame.iso);
        release();
    } catch (const std::exception& error) {
        result.error = QObject::tr("internal error: %1").arg(error.what());
    }
    result.workerMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

std::pair<QImage, QImage> RenderWorker::renderPanels(const PanelRenderJob& job,
                                                     QOffscreenSurface* surface,
                                                     PanelVectors* vectors) {
    render::ReviewFrameRequest frame = panelFrameRequest(job, vectors != nullptr);
    if (surface) {
        textures(surface);
        frame.glContext = m_sharedContext.get();
    }
    const ReleasedAfter release(m_textures.get());
    return panelsOfFrame(m_frames.render(frame), job, vectors);
}

void RenderWorker::takeFrame(render::ReviewFrame&& frame, const ReviewSettings& appearance,
                             FrameResult& result) const {
    result.mesh = std::move(frame.mesh);
    result.meshMs = frame.meshMs;
    result.surfaceTriangles = frame.surfaceTriangles;
    result.silhouette = std::move(frame.silhouette);
    if (result.silhouette && !result.silhouette->drewToTarget) {
        const render::PixelMask& lines = result.silhouette->lines;
        result.silhouetteImage = frame.polylines.hidden.empty()
                                     ? linesToImage(lines, appearance, false, appearance.lineWidth)
                                     : linesOverHiddenLines(lines, frame.polylines.hidden,
                                                            appearance, appearance.lineWidth);
        if (appearance.silhouetteOnIso)
            result.isoOverlay = linesToImage(lines, appearance, true, appearance.lineWidth);
    }
    if (frame.isoImage) {
        result.isoImage = toQImage(*frame.isoImage);
        result.isoDepth = std::move(frame.isoDepth);
    }
    result.isoRenderMs = frame.isoRenderMs;
    result.stageMs = frame.stageMs;
    result.isoOnDevice = frame.isoOnDevice;
    result.refinement = frame.refinement;
    result.drawnVolume = std::move(frame.drawnVolume);
    result.backend = QString::fromStdString(frame.backend);
    result.backendNote = QString::fromStdString(frame.backendNote);
}

// A texture for this frame where one can be drawn: the panel asks for it (the engine draws
// there only where the renderer can: method 3 on CUDA). The context is released until the
// engine makes it current for the silhouette.
render::GlFrameTarget* RenderWorker::frameTargetFor(const FrameRequest& request,
                                                    std::shared_ptr<const LinesTexture>& token) {
    const render::Camera& camera = request.frame.camera;
    const glm::ivec2 size(camera.width(), camera.height());
    if (!request.silhouetteToTexture || !request.textureSurface ||
        render::frameTargetUse(size, size) != render::FrameTargetUse::Texture)
        return nullptr;
    render::GlFrameTarget* target = textures(request.textureSurface).acquire(size.x, size.y, token);
    m_textures->done();
    return target;
}

} // namespace lw::gui
