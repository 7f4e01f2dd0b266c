#include "review/render_worker.h"

#include "lw/core/error.h"
#include "review/panel_render_job.h"
#include "review/qt_image.h"

#if LINEWORK_GL
#include "lw/render/geometry_shader_silhouette_renderer.h"
#endif

#include <QObject>
#include <chrono>
#include <cstring>
#include <new>

namespace lw::gui {
namespace {

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

} // namespace

RenderWorker::RenderWorker(std::shared_ptr<const volume::Volume> volume)
    : m_source(std::move(volume)) {}

RenderWorker::~RenderWorker() = default;

void RenderWorker::release() {
    m_textures.reset(); // their CUDA registrations and GL textures, in their context
    if (m_isoGl && m_glContext)
        m_glContext->makeCurrent(); // the iso renderer's GL objects go with it, in its context
    m_isoGl.reset();
    m_glContext.reset();
    m_uploadedMesh = nullptr;
    m_uploadedMeshOwner.reset();
    m_suggestive.reset();
    m_suggestiveMesh.reset();
    m_renderer.reset();
    m_extractor.reset();
    m_mesh.reset();
}

// The volume of the request's sampling: made once (the oversampled copy on this thread, off the
// UI's) -- once per iso-value where it is the shape-based field of thick slices -- and on a
// change everything made of the old one goes with it.
void RenderWorker::prepareVolume(const FrameRequest& request) {
    if (m_volume && m_volumeSampling == request.sampling &&
        (!m_volumeDependsOnIso || m_volumeIso == request.iso))
        return;
    m_suggestive.reset();
    m_suggestiveMesh.reset();
    m_renderer.reset();
    m_extractor.reset();
    m_mesh.reset();
    m_uploadedMesh = nullptr;
    m_uploadedMeshOwner.reset();
    m_volume.reset(); // the old copy goes before a new one is made: one at a time in memory
    m_volume =
        render::volumeToRender(m_source, request.sampling, request.iso, request.settings.threads);
    m_volumeSampling = request.sampling;
    m_volumeIso = request.iso;
    m_volumeDependsOnIso =
        render::samplingPlan(m_source->dims(), m_source->geometry(), request.sampling)
            .dependsOnIso();
}

FrameResult RenderWorker::run(const FrameRequest& request) {
    FrameResult result;
    result.id = request.id;
    result.settingsGeneration = request.settingsGeneration;
    result.iso = request.iso;
    result.camera = request.camera;
    result.method = request.method;
    result.brickCells = request.settings.brickCells;
    try {
        if (request.cancel->isCancelled())
            throw core::Cancelled();
        prepareVolume(request);
        result.refinement = m_volume->geometry().refinement();
        if (request.wantSilhouette)
            renderSilhouette(request, result);
        if (request.cancel->isCancelled())
            throw core::Cancelled();
        if (request.wantMesh || request.wantIsoImage)
            extractMesh(request, result);
        if (request.cancel->isCancelled())
            throw core::Cancelled();
        if (request.wantIsoImage)
            renderIsoImage(request, result);
    } catch (const core::Cancelled&) {
        result.cancelled = true;
    } catch (const core::Error& error) {
        result.error = QString::fromStdString(error.what());
    } catch (const std::bad_alloc&) {
        result.error = QObject::tr("out of memory at iso-value %1 HU: choose a higher iso-value "
                                   "or chunking (settings)")
                           .arg(request.iso);
        release();
    } catch (const std::exception& error) {
        result.error = QObject::tr("internal error: %1").arg(error.what());
    }
    return result;
}

render::SilhouetteRenderer& RenderWorker::rendererFor(const FrameRequest& request,
                                                      FrameResult& result) {
    if (!m_renderer || m_renderer->method() != request.method ||
        m_rendererBackend != request.backend) {
        m_renderer.reset();
        std::string note;
        m_renderer = render::createSilhouetteRenderer(request.method, request.backend, &note);
        m_renderer->setVolume(*m_volume);
        m_rendererBackend = request.backend;
        m_backendNote = QString::fromStdString(note);
    }
    result.backend = QString::fromUtf8(m_renderer->backendName().data(),
                                       qsizetype(m_renderer->backendName().size()));
    result.backendNote = m_backendNote;
    return *m_renderer;
}

void RenderWorker::renderSilhouette(const FrameRequest& request, FrameResult& result) {
    render::SilhouetteSettings settings = request.settings;
    settings.isoReal = request.iso;
    settings.cancel = request.cancel.get(); // a newer iso-value stops this frame in the kernels
    render::SilhouetteRenderer& renderer = rendererFor(request, result);
    std::shared_ptr<const LinesTexture> texture;
    settings.frameTarget = frameTargetFor(request, renderer, texture);
    {
        // The worker's context is current from acquire() to here, whatever the frame does.
        struct ContextDone {
            SilhouetteTextures* textures;
            ~ContextDone() {
                if (textures)
                    textures->done();
            }
        } contextDone{settings.frameTarget ? m_textures.get() : nullptr};
        result.silhouette = renderer.render(request.camera, settings);
    }
    if (result.silhouette->drewToTarget)
        result.linesTexture = std::move(texture);
    keepRendererMesh(request, result);
    if (request.suggestive && !result.silhouette->drewToTarget) // the texture path is off then
        addSuggestive(request, result);
}

// The surface the silhouette frame drew (a copy of the renderer's, or extracted for method 2,
// which keeps none) gets its per-vertex derivatives once per iso-value; each frame then draws
// the suggestive contours into the silhouette's mask.
void RenderWorker::addSuggestive(const FrameRequest& request, FrameResult& result) {
    const SurfaceForm form = SurfaceForm::of(request.settings);
    if (!m_suggestive || m_suggestiveIso != request.iso || m_suggestiveForm != form) {
        m_suggestive.reset();
        if (m_mesh && m_meshIso == request.iso && m_meshForm == form) {
            m_suggestiveMesh = m_mesh;
        } else {
            render::SilhouetteSettings drawn = request.settings;
            drawn.isoReal = request.iso;
            drawn.cancel = request.cancel.get();
            m_suggestiveMesh = std::make_shared<const render::Mesh>(
                render::surfaceOfFrame(*m_renderer, *m_volume, drawn));
        }
        m_suggestive = std::make_unique<render::SuggestiveContourRenderer>(
            *m_volume, *m_suggestiveMesh, request.iso, request.settings.threads, form.stencil);
        m_suggestiveIso = request.iso;
        m_suggestiveForm = form;
    }
    render::SuggestiveContourSettings settings;
    settings.visibility = request.settings.visibility;
    settings.minStrokePixels = request.settings.minStrokePixels;
    settings.threads = request.settings.threads;
    const render::SuggestiveFrame frame = m_suggestive->render(request.camera, settings);
    render::addLines(result.silhouette->lines, frame.lines);
    result.silhouette->times.drawMs += frame.ms;
}

// A texture for this frame where one can be drawn: the panel asks for it, and the renderer can
// draw into one (method 3 on CUDA) with nothing to do on the host mask afterwards. Anywhere
// else no GL context is made for nothing.
render::GlFrameTarget* RenderWorker::frameTargetFor(const FrameRequest& request,
                                                    const render::SilhouetteRenderer& renderer,
                                                    std::shared_ptr<const LinesTexture>& token) {
    const glm::ivec2 size(request.camera.width(), request.camera.height());
    if (!request.silhouetteToTexture || !request.textureSurface ||
        !renderer.drawsToFrameTargets() ||
        render::frameTargetUse(size, size) != render::FrameTargetUse::Texture)
        return nullptr;
    if (!m_textures)
        m_textures = std::make_unique<SilhouetteTextures>(request.textureSurface);
    return m_textures->acquire(size.x, size.y, token);
}

// Methods 1 and 3 (S, CPU or CUDA) keep the mesh they drew: the iso panel shows exactly that
// surface and marching cubes does not run twice for one iso-value.
void RenderWorker::keepRendererMesh(const FrameRequest& request, FrameResult& result) {
    if (!(request.wantMesh || request.wantIsoImage) || request.settings.brickCells != 0)
        return;
    const render::Mesh* mesh = m_renderer->surfaceMesh();
    if (!mesh)
        return;
    if (m_mesh && m_meshIso == request.iso && m_meshForm == SurfaceForm::of(request.settings) &&
        request.settings.mode == render::ExtractionMode::CachedA)
        return; // mode a: the renderer drew the mesh it has already handed out
    const auto start = std::chrono::steady_clock::now();
    m_mesh = std::make_shared<const render::Mesh>(*mesh);
    m_meshIso = request.iso;
    m_meshForm = SurfaceForm::of(request.settings);
    result.mesh = m_mesh;
    // The marching cubes that made it ran inside the renderer's frame (plus this copy).
    result.meshMs = result.silhouette->times.extractMs + millisecondsSince(start);
}

void RenderWorker::renderIsoImage(const FrameRequest& request, FrameResult& result) {
    if (request.isoOnCpu) {
        const auto start = std::chrono::steady_clock::now();
        const std::shared_ptr<const render::Mesh> mesh = result.mesh ? result.mesh : m_mesh;
        result.isoImage = shadeIsoOnCpu(mesh.get(), request.isoCamera, request.isoOptions,
                                        request.settings.threads, &result.isoDepth);
        result.isoCamera = request.isoCamera;
        result.isoRenderMs = millisecondsSince(start);
        return;
    }
#if LINEWORK_GL
    const auto start = std::chrono::steady_clock::now();
    if (!m_glContext) {
        m_glContext = std::make_unique<render::EglHeadlessContext>();
        m_isoGl = std::make_unique<render::SilhouetteGlRenderer>();
    }
    m_glContext->makeCurrent();
    const std::shared_ptr<const render::Mesh> mesh = result.mesh ? result.mesh : m_mesh;
    if (mesh && mesh.get() != m_uploadedMesh) {
        m_isoGl->uploadMesh(*mesh);
        m_uploadedMesh = mesh.get();
        m_uploadedMeshOwner = mesh;
    }
    const core::ImageRgba8 image = m_isoGl->renderImage(request.isoCamera, request.isoOptions);
    result.isoImage = toQImage(image);
    result.isoDepth = m_isoGl->readDepth();
    result.isoCamera = request.isoCamera;
    result.isoRenderMs = millisecondsSince(start);
#else
    (void)request;
    (void)result;
    throw core::Error("iso panel", "this build has no OpenGL");
#endif
}

void RenderWorker::extractMesh(const FrameRequest& request, FrameResult& result) {
    if (result.mesh)
        return;
    const SurfaceForm form = SurfaceForm::of(request.settings);
    if (m_meshForm != form)
        m_mesh.reset(); // the kept mesh is another surface (open / closed, other normals)
    if (m_mesh && m_meshIso == request.iso && !request.forceExtract && !request.wantMesh)
        return; // the iso image re-draws the mesh it has
    if (m_mesh && m_meshIso == request.iso && !request.forceExtract) {
        result.mesh = m_mesh;
        return;
    }
    const auto start = std::chrono::steady_clock::now();
    // The iso panel's mesh is the same whatever the brick schedule (canonical order), so the
    // extractor keeps one brick grid and reuses it across iso-values.
    const int bricks = request.settings.brickCells;
    if (!m_extractor || m_extractorBricks != bricks || m_extractorForm != form) {
        render::IsoSurfaceOptions options;
        options.brickCells = bricks;
        options.threads = request.settings.threads;
        options.closeAtBorder = form.closed;
        options.gradientStencil = form.stencil;
        m_extractor = std::make_unique<render::IsoSurfaceExtractor>(*m_volume, options);
        m_extractorBricks = bricks;
        m_extractorForm = form;
    }
    auto mesh = std::make_shared<render::Mesh>();
    m_extractor->extract(request.iso, *mesh, nullptr, request.cancel.get());
    m_mesh = std::move(mesh);
    m_meshIso = request.iso;
    m_meshForm = form;
    result.mesh = m_mesh;
    result.meshMs = millisecondsSince(start);
}

} // namespace lw::gui
