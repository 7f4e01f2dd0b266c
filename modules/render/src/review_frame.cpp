#include "lw/render/review_frame.h"

#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/suggestive_contours.h"
#include "lw/render/zbuffer_silhouette_renderer.h"

#if LINEWORK_GL
#include "lw/render/geometry_shader_silhouette_renderer.h"
#endif

#include <chrono>
#include <limits>

namespace lw::render {
namespace {

constexpr core::LogCategory kLog("lw.render");

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// What, besides the iso-value, makes one surface differ from another: closed at the border or
// not, and the gradient behind its normals.
struct SurfaceForm {
    bool closed = false;
    GradientStencil stencil = GradientStencil::Central;
    static SurfaceForm of(const SilhouetteSettings& settings) {
        return {settings.closeAtBorder, settings.gradientStencil};
    }
    bool operator==(const SurfaceForm&) const = default;
};

// A host mesh and what it is the surface of.
struct KeptMesh {
    std::shared_ptr<const Mesh> mesh;
    double iso = 0.0;
    SurfaceForm form;
    bool matches(double otherIso, SurfaceForm otherForm) const {
        return mesh && iso == otherIso && form == otherForm;
    }
};

// Makes `context` current for the silhouette and releases it afterwards, whatever the frame
// does: the iso panel's own context may be made current on this thread next.
class CurrentFor {
public:
    explicit CurrentFor(GlContext* context) : m_context(context) {
        if (m_context)
            m_context->makeCurrent();
    }
    ~CurrentFor() {
        if (m_context)
            m_context->doneCurrent();
    }
    CurrentFor(const CurrentFor&) = delete;
    CurrentFor& operator=(const CurrentFor&) = delete;

private:
    GlContext* m_context;
};

} // namespace

bool reviewIsoOnDevice(Backend backend) {
    if (backend == Backend::Cpu)
        return false;
    try {
        return resolveBackend(backend, SilhouetteMethod::GeometryShader) == Backend::Cuda;
    } catch (const core::Error&) {
        return false; // --backend cuda where it cannot be: the frame says so itself
    }
}

struct ReviewFrameRenderer::State {
    std::shared_ptr<const volume::Volume> source; // as loaded
    // What the methods draw: `source` or its resampled copy; everything below is of this volume
    // and goes when it changes.
    std::shared_ptr<const volume::Volume> volume;
    std::optional<VolumeSampling> volumeSampling;
    double volumeIso = 0.0;
    bool volumeDependsOnIso = false;
    // Makes `volume` (on the CUDA device where the shape-based field can be made there).
    std::unique_ptr<DrawnVolumeMaker> volumeMaker;
    Backend volumeMakerBackend = Backend::Auto;
    std::string volumeNote; // why the device stopped making the field: for the next frame

    std::unique_ptr<SilhouetteRenderer> renderer;
    Backend rendererBackend = Backend::Auto;
    std::string backendNote;

    std::unique_ptr<IsoSurfaceExtractor> extractor;
    int extractorBricks = -1;
    SurfaceForm extractorForm;
    KeptMesh kept; // the host mesh handed out last

    std::unique_ptr<SuggestiveContourRenderer> suggestive;
    KeptMesh suggestiveSurface;

#if LINEWORK_GL
    // The frame's GL context: the request's, or a headless one of its own made at first need.
    GlContext* glContext = nullptr;
    std::unique_ptr<EglHeadlessContext> ownContext;
    // The iso panel with GL from a host mesh.
    std::unique_ptr<SilhouetteGlRenderer> isoGl;
    const Mesh* uploadedMesh = nullptr;
    std::shared_ptr<const Mesh> uploadedMeshOwner;
    // The device path: method 1's renderer with the CUDA extraction (its own EGL context), used
    // for the iso panel alone when the silhouette is another method's or chunked.
    std::unique_ptr<GeometryShaderSilhouetteRenderer> deviceIso;
#endif
    // The device path's CUDA shading for a silhouette that keeps no whole surface on the device
    // (method 2, method 3's L): method 3's whole-volume renderer of its own, for the panel alone.
    std::unique_ptr<ZBufferSilhouetteRenderer> cudaIso;
    // What cudaIso last shaded (its surface on the device, until it is rebound).
    struct {
        double iso = std::numeric_limits<double>::quiet_NaN();
        SurfaceForm form;
        bool matches(double otherIso, SurfaceForm otherForm) const {
            return iso == otherIso && form == otherForm;
        }
    } cudaIsoSurface;
    // This build or machine has no CUDA back-end, or its shading failed (until the volume changes).
    bool cudaShadingUnavailable = false;
    std::string deviceUnavailable; // why the device path could not start (once per volume)
    std::size_t hostMeshes = 0;

    void dropVolumeCaches() {
        suggestive.reset();
        suggestiveSurface = {};
        renderer.reset();
        extractor.reset();
        kept = {};
#if LINEWORK_GL
        if (isoGl && glContext)
            glContext->makeCurrent(); // its GL objects go in the context they were made in
        isoGl.reset();
        uploadedMesh = nullptr;
        uploadedMeshOwner.reset();
        deviceIso.reset();
#endif
        cudaIso.reset();
        cudaShadingUnavailable = false;
        deviceUnavailable.clear();
    }

    // A new copy of the same grid (the shape-based field at a new iso-value): the renderers keep
    // their GL and device objects -- made again, method 1's interop buffers alone cost tens of
    // milliseconds -- and take the new voxels (setVolume drops what they kept of the old ones);
    // what was made on the host of the old surface goes.
    void rebindVolume() {
        suggestive.reset();
        suggestiveSurface = {};
        extractor.reset();
        kept = {};
        if (renderer)
            bindDrawnVolume(*renderer);
        if (cudaIso)
            bindDrawnVolume(*cudaIso);
#if LINEWORK_GL
        uploadedMesh = nullptr; // the GL panel uploads the new surface at its next frame
        uploadedMeshOwner.reset();
        if (deviceIso)
            bindDrawnVolume(*deviceIso);
#endif
    }

    // The drawn volume bound to a renderer, with its voxels on the device where the maker made
    // them there: the CUDA back-ends copy them device to device instead of uploading them.
    void bindDrawnVolume(SilhouetteRenderer& drawing) const {
        drawing.setVolumeWithDeviceCopy(*volume, volumeMaker ? volumeMaker->deviceCopy()
                                                             : DeviceVoxelCopy{});
    }

    void prepareVolume(const ReviewFrameRequest& request);
    SilhouetteRenderer& rendererFor(const ReviewFrameRequest& request, ReviewFrame& frame);
    // `deviceIso`: the iso panel is to be shaded on the device (where it still can be).
    void renderSilhouette(const ReviewFrameRequest& request, bool deviceIso, ReviewFrame& frame);
    void finishLines(const ReviewFrameRequest& request, ReviewFrame& frame);
    void addSuggestive(const ReviewFrameRequest& request, ReviewFrame& frame);
    std::shared_ptr<const Mesh> hostSurface(const ReviewFrameRequest& request);
    std::shared_ptr<const Mesh> contourSurface(const ReviewFrameRequest& request);
    void keepRendererMesh(const ReviewFrameRequest& request, bool deviceIso, ReviewFrame& frame);
    void extractMesh(const ReviewFrameRequest& request, ReviewFrame& frame);
    void renderIsoOnHost(const ReviewFrameRequest& request, ReviewFrame& frame);
    bool renderIsoOnDevice(const ReviewFrameRequest& request, ReviewFrame& frame);
    bool shadeIsoWithCuda(const ReviewFrameRequest& request, ReviewFrame& frame);
#if LINEWORK_GL
    GeometryShaderSilhouetteRenderer* deviceIsoRenderer(const ReviewFrameRequest& request);
    GlContext& contextFor(const ReviewFrameRequest& request) {
        if (!glContext) {
            if (request.glContext) {
                glContext = request.glContext;
            } else {
                ownContext = std::make_unique<EglHeadlessContext>();
                glContext = ownContext.get();
            }
        }
        return *glContext;
    }
    std::unique_ptr<SilhouetteRenderer> createRenderer(const ReviewFrameRequest& request);
#endif
};

ReviewFrameRenderer::ReviewFrameRenderer(std::shared_ptr<const volume::Volume> source)
    : m_state(std::make_unique<State>()) {
    m_state->source = std::move(source);
}

ReviewFrameRenderer::~ReviewFrameRenderer() {
    release();
}

void ReviewFrameRenderer::release() {
    State& s = *m_state;
    s.dropVolumeCaches();
#if LINEWORK_GL
    s.ownContext.reset();
    s.glContext = nullptr;
#endif
    s.volume.reset();
    s.volumeSampling.reset();
    s.volumeMaker.reset();
}

std::size_t ReviewFrameRenderer::hostMeshesMade() const {
    return m_state->hostMeshes;
}

// The volume of the request's sampling: made once -- once per iso-value where it is the
// shape-based field of thick slices -- and on a change everything made of the old one goes,
// except where only the iso-value of the shape-based field changed: the grid is the same, and
// the renderers are rebound to the new copy.
void ReviewFrameRenderer::State::prepareVolume(const ReviewFrameRequest& request) {
    const bool sameSampling = volume && volumeSampling == request.sampling;
    if (sameSampling && (!volumeDependsOnIso || volumeIso == request.iso))
        return;
    if (sameSampling && volumeMaker && volumeMakerBackend == request.backend) {
        // The old copy stays until the renderers let go of it: two copies of a bounded grid (the
        // shape-based copy has at most kMaxOversamplingFactor times the slices) for a moment.
        const std::shared_ptr<const volume::Volume> previous = volume;
        volume = volumeMaker->make(request.sampling, request.iso, request.settings.threads);
        volumeNote = volumeMaker->takeNote();
        volumeIso = request.iso;
        rebindVolume();
        return;
    }
    dropVolumeCaches();
    volume.reset(); // the old copy goes before a new one is made: one at a time in memory
    if (!volumeMaker || volumeMakerBackend != request.backend) {
        volumeMaker = std::make_unique<DrawnVolumeMaker>(source, request.backend);
        volumeMakerBackend = request.backend;
    }
    volume = volumeMaker->make(request.sampling, request.iso, request.settings.threads);
    volumeNote = volumeMaker->takeNote();
    volumeSampling = request.sampling;
    volumeIso = request.iso;
    volumeDependsOnIso =
        samplingPlan(source->dims(), source->geometry(), request.sampling).dependsOnIso();
}

ReviewFrame ReviewFrameRenderer::render(const ReviewFrameRequest& request) {
    State& s = *m_state;
    if (request.cancel && request.cancel->isCancelled())
        throw core::Cancelled();
    ReviewFrame frame;
    auto stage = Clock::now();
    const auto lap = [&stage] {
        const double ms = msSince(stage);
        stage = Clock::now();
        return ms;
    };
    s.prepareVolume(request);
    frame.stageMs.volume = lap();
    frame.refinement = s.volume->geometry().refinement();
    frame.drawnVolume = s.volume;
    // CUDA's shading needs no GL: a software-GL display (isoOnCpu) still gets it.
    const bool deviceIso = request.wantIsoImage && reviewIsoOnDevice(request.backend) &&
                           (!request.isoOnCpu || request.isoShadedByCuda);
    if (request.wantSilhouette)
        s.renderSilhouette(request, deviceIso, frame);
    frame.stageMs.silhouette = lap();
    if (request.cancel && request.cancel->isCancelled())
        throw core::Cancelled();
    const bool isoDone = deviceIso && s.renderIsoOnDevice(request, frame);
    if (request.wantMesh || (request.wantIsoImage && !isoDone))
        s.extractMesh(request, frame);
    if (request.cancel && request.cancel->isCancelled())
        throw core::Cancelled();
    if (request.wantIsoImage && !isoDone)
        s.renderIsoOnHost(request, frame);
    frame.stageMs.isoPanel = lap();
    s.finishLines(request, frame);
    frame.stageMs.silhouette += lap();
    if (!s.deviceUnavailable.empty())
        frame.backendNote += (frame.backendNote.empty() ? "" : "; ") + s.deviceUnavailable;
    if (!s.volumeNote.empty())
        frame.backendNote +=
            (frame.backendNote.empty() ? "" : "; ") + std::exchange(s.volumeNote, {});
    return frame;
}

SilhouetteRenderer& ReviewFrameRenderer::State::rendererFor(const ReviewFrameRequest& request,
                                                            ReviewFrame& frame) {
    if (!renderer || renderer->method() != request.method || rendererBackend != request.backend) {
        renderer.reset();
#if LINEWORK_GL
        renderer = createRenderer(request);
#else
        renderer = createSilhouetteRenderer(request.method, request.backend, &backendNote);
#endif
        bindDrawnVolume(*renderer);
        rendererBackend = request.backend;
    }
    frame.backend = std::string(renderer->backendName());
    frame.backendNote = backendNote;
    return *renderer;
}

void ReviewFrameRenderer::State::renderSilhouette(const ReviewFrameRequest& request, bool deviceIso,
                                                  ReviewFrame& frame) {
    SilhouetteSettings settings = request.settings;
    settings.isoReal = request.iso;
    settings.cancel = request.cancel;
    SilhouetteRenderer& drawing = rendererFor(request, frame);
    if (request.silhouetteTarget && drawing.drawsToFrameTargets())
        settings.frameTarget = request.silhouetteTarget;
    {
        const CurrentFor current(settings.frameTarget ? request.silhouetteTargetContext : nullptr);
        frame.silhouette = drawing.render(request.camera, settings);
    }
    keepRendererMesh(request, deviceIso, frame);
}

// After the iso panel: its CUDA renderer (method 2's panel) then holds this iso-value's surface
// on the device, which the vector lines can be chained from (contourSurface).
void ReviewFrameRenderer::State::finishLines(const ReviewFrameRequest& request,
                                             ReviewFrame& frame) {
    if (!frame.silhouette || frame.silhouette->drewToTarget)
        return;
    if (request.wantPolylines) {
        const auto start = Clock::now();
        const std::shared_ptr<const Mesh> surface = contourSurface(request);
        frame.polylineSurfaceMs = msSince(start);
        frame.polylines = splitPolylines(*surface, request.camera, frame.silhouette->lines,
                                         request.polylineOptions,
                                         request.hiddenLines && request.settings.visibility);
        frame.polylinesMs = msSince(start);
    }
    if (request.suggestive)
        addSuggestive(request, frame);
}

// What the vector lines are chained from: the host surface where it is kept already; else,
// where the renderer's surface is on the device -- or, for a method that keeps none (method 2),
// the iso panel's CUDA renderer's of this iso-value -- only its triangles that may hold the
// camera's contour, downloaded for this camera (the same lines from a few in a hundred of the
// triangles); else the host surface, made and kept.
std::shared_ptr<const Mesh>
ReviewFrameRenderer::State::contourSurface(const ReviewFrameRequest& request) {
    const SurfaceForm form = SurfaceForm::of(request.settings);
    if (!kept.matches(request.iso, form)) {
        std::optional<Mesh> part = renderer->contourTriangles(request.camera);
        if (!part && cudaIso && cudaIsoSurface.matches(request.iso, form))
            part = cudaIso->contourTriangles(request.camera);
        if (part)
            return std::make_shared<const Mesh>(std::move(*part));
    }
    return hostSurface(request);
}

// The surface the silhouette frame drew, on the host: the kept one of this iso-value, or the
// renderer's own (downloaded where it is on the device), or extracted for a method that keeps
// none -- then kept.
std::shared_ptr<const Mesh>
ReviewFrameRenderer::State::hostSurface(const ReviewFrameRequest& request) {
    const SurfaceForm form = SurfaceForm::of(request.settings);
    if (kept.matches(request.iso, form))
        return kept.mesh;
    SilhouetteSettings drawn = request.settings;
    drawn.isoReal = request.iso;
    drawn.cancel = request.cancel;
    kept = {std::make_shared<const Mesh>(surfaceOfFrame(*renderer, *volume, drawn)), request.iso,
            form};
    ++hostMeshes;
    return kept.mesh;
}

// The surface the silhouette frame drew (kept, or extracted for a method that keeps none) gets
// its per-vertex derivatives once per iso-value; each frame then draws the suggestive contours
// into the silhouette's mask.
void ReviewFrameRenderer::State::addSuggestive(const ReviewFrameRequest& request,
                                               ReviewFrame& frame) {
    const SurfaceForm form = SurfaceForm::of(request.settings);
    if (!suggestive || !suggestiveSurface.matches(request.iso, form)) {
        suggestive.reset();
        suggestiveSurface = {hostSurface(request), request.iso, form};
        suggestive = std::make_unique<SuggestiveContourRenderer>(
            *volume, *suggestiveSurface.mesh, request.iso, request.settings.threads, form.stencil);
    }
    SuggestiveContourSettings settings;
    settings.visibility = request.settings.visibility;
    settings.minStrokePixels = request.settings.minStrokePixels;
    settings.threads = request.settings.threads;
    const SuggestiveFrame contours = suggestive->render(request.camera, settings);
    addLines(frame.silhouette->lines, contours.lines);
    frame.silhouette->times.drawMs += contours.ms;
    if (request.wantPolylines) {
        const std::vector<Polyline> more = visiblePolylines(
            chainSegments(contours.kept), request.camera, contours.lines, request.polylineOptions);
        frame.polylines.visible.insert(frame.polylines.visible.end(), more.begin(), more.end());
    }
}

// Methods 1 and 3 (S) keep the mesh they drew: where the host needs the surface (a panel that
// draws it, the host path of the iso panel) it is that one, and marching cubes does not run
// twice for one iso-value.
void ReviewFrameRenderer::State::keepRendererMesh(const ReviewFrameRequest& request, bool deviceIso,
                                                  ReviewFrame& frame) {
    const bool hostIso = request.wantIsoImage && (!deviceIso || !deviceUnavailable.empty());
    if (!(request.wantMesh || hostIso) || request.settings.brickCells != 0)
        return;
    const SurfaceForm form = SurfaceForm::of(request.settings);
    if (kept.matches(request.iso, form) && request.settings.mode == ExtractionMode::CachedA)
        return; // mode a: the renderer drew the mesh it has already handed out
    const auto start = Clock::now();
    const Mesh* mesh = renderer->surfaceMesh();
    if (!mesh)
        return;
    kept = {std::make_shared<const Mesh>(*mesh), request.iso, form};
    ++hostMeshes;
    frame.mesh = kept.mesh;
    frame.surfaceTriangles = kept.mesh->triangleCount();
    // The marching cubes that made it ran inside the renderer's frame (plus this copy).
    frame.meshMs = frame.silhouette->times.extractMs + msSince(start);
}

void ReviewFrameRenderer::State::extractMesh(const ReviewFrameRequest& request,
                                             ReviewFrame& frame) {
    if (frame.mesh)
        return;
    const SurfaceForm form = SurfaceForm::of(request.settings);
    if (kept.matches(request.iso, form) && !request.forceExtract) {
        if (request.wantMesh)
            frame.mesh = kept.mesh; // else the iso image re-draws the mesh it has
        frame.surfaceTriangles = kept.mesh->triangleCount();
        return;
    }
    const auto start = Clock::now();
    // The iso panel's mesh is the same whatever the brick schedule (canonical order), so the
    // extractor keeps one brick grid and reuses it across iso-values.
    const int bricks = request.settings.brickCells;
    if (!extractor || extractorBricks != bricks || extractorForm != form) {
        IsoSurfaceOptions options;
        options.brickCells = bricks;
        options.threads = request.settings.threads;
        options.closeAtBorder = form.closed;
        options.gradientStencil = form.stencil;
        extractor = std::make_unique<IsoSurfaceExtractor>(*volume, options);
        extractorBricks = bricks;
        extractorForm = form;
    }
    auto mesh = std::make_shared<Mesh>();
    extractor->extract(request.iso, *mesh, nullptr, request.cancel);
    ++hostMeshes;
    kept = {std::move(mesh), request.iso, form};
    frame.mesh = kept.mesh;
    frame.surfaceTriangles = kept.mesh->triangleCount();
    frame.meshMs = msSince(start);
}

void ReviewFrameRenderer::State::renderIsoOnHost(const ReviewFrameRequest& request,
                                                 ReviewFrame& frame) {
    const auto start = Clock::now();
    const std::shared_ptr<const Mesh> mesh = frame.mesh ? frame.mesh : kept.mesh;
    if (request.isoOnCpu) {
        SurfaceShading shading = glPanelShading(request.isoCamera, request.isoOptions);
        shading.threads = request.settings.threads;
        frame.isoImage =
            shadeSurfaceCpu(mesh ? *mesh : Mesh(), request.isoCamera, shading, &frame.isoDepth);
        frame.isoRenderMs = msSince(start);
        return;
    }
#if LINEWORK_GL
    contextFor(request).makeCurrent();
    if (!isoGl)
        isoGl = std::make_unique<SilhouetteGlRenderer>();
    if (mesh && mesh.get() != uploadedMesh) {
        isoGl->uploadMesh(*mesh);
        uploadedMesh = mesh.get();
        uploadedMeshOwner = mesh;
    }
    frame.isoImage = isoGl->renderImage(request.isoCamera, request.isoOptions);
    frame.isoDepth = isoGl->readDepth();
    frame.isoRenderMs = msSince(start);
#else
    throw core::Error("iso panel", "this build has no OpenGL");
#endif
}

#if LINEWORK_GL
// Method 1's whole-volume renderer on CUDA draws the iso panel from its own buffers; any other
// silhouette gets a second renderer of that kind for the panel alone. Null (logged once) where
// it cannot be made.
GeometryShaderSilhouetteRenderer*
ReviewFrameRenderer::State::deviceIsoRenderer(const ReviewFrameRequest& request) {
    if (!deviceUnavailable.empty())
        return nullptr;
    if (auto* method1 = dynamic_cast<GeometryShaderSilhouetteRenderer*>(renderer.get());
        method1 && method1->extractsOnDevice() && request.settings.brickCells == 0 &&
        request.wantSilhouette) {
        deviceIso.reset();
        return method1;
    }
    if (deviceIso)
        return deviceIso.get();
    try {
        auto made = std::make_unique<GeometryShaderSilhouetteRenderer>(contextFor(request));
        made->useCudaExtraction();
        bindDrawnVolume(*made);
        deviceIso = std::move(made);
    } catch (const core::Error& error) {
        deviceUnavailable = std::string("iso panel on the host: ") + error.what();
        kLog.warning(deviceUnavailable);
    }
    return deviceIso.get();
}

// Method 1 draws in the frame's context (the factory's would be a headless one of its own);
// the other methods as the factory makes them.
std::unique_ptr<SilhouetteRenderer>
ReviewFrameRenderer::State::createRenderer(const ReviewFrameRequest& request) {
    if (request.method != SilhouetteMethod::GeometryShader || !request.glContext)
        return createSilhouetteRenderer(request.method, request.backend, &backendNote);
    const Backend backend = resolveBackend(request.backend, request.method, &backendNote);
    auto method1 = std::make_unique<GeometryShaderSilhouetteRenderer>(contextFor(request));
    if (backend == Backend::Cuda)
        method1->useCudaExtraction();
    return method1;
}
#endif

// The iso panel shaded by CUDA where the surface is on the device already or can be: method 3's
// whole-volume renderer on CUDA shades the surface its silhouette frame kept (one extraction for
// both panels); method 2 and method 3's L get such a renderer for the panel alone. Method 1's
// panel comes from its own renderer (renderIsoOnDevice), which shades its CUDA extraction the
// same way. False where CUDA cannot shade it here.
bool ReviewFrameRenderer::State::shadeIsoWithCuda(const ReviewFrameRequest& request,
                                                  ReviewFrame& frame) {
    if ((request.method == SilhouetteMethod::GeometryShader && request.wantSilhouette) ||
        request.isoOptions.linesOnIso || !request.isoShadedByCuda || cudaShadingUnavailable) {
        cudaIso.reset(); // its volume and surface on the device are of no use to GL's panel
        return false;
    }
    SilhouetteSettings settings = request.settings;
    settings.isoReal = request.iso;
    settings.cancel = request.cancel;
    auto* method3 = dynamic_cast<ZBufferSilhouetteRenderer*>(renderer.get());
    ZBufferSilhouetteRenderer* shading = nullptr;
    if (method3 && request.wantSilhouette && request.settings.brickCells == 0 &&
        method3->drawsToFrameTargets()) {
        shading = method3;
        settings.mode = ExtractionMode::CachedA; // its silhouette frame extracted for mode b
        cudaIso.reset();
    } else {
        if (!cudaIso) {
            try {
                cudaIso = std::make_unique<ZBufferSilhouetteRenderer>(Backend::Cuda);
                bindDrawnVolume(*cudaIso);
            } catch (const core::Error& error) {
                kLog.info(std::string("iso panel: no CUDA shading (") + error.what() + ")");
                cudaShadingUnavailable = true;
                return false;
            }
        }
        shading = cudaIso.get();
        settings.brickCells = 0;
        settings.mode =
            request.forceExtract ? ExtractionMode::EveryFrameB : ExtractionMode::CachedA;
    }
    std::optional<ZBufferSilhouetteRenderer::DeviceShadedSurface> shaded;
    try {
        shaded =
            shading->shadeOnDevice(request.isoCamera, settings,
                                   glPanelShading(request.isoCamera, request.isoOptions), true);
    } catch (const core::Error& error) {
        // A kernel or a copy failed: GL shades the panel from now on (until the volume
        // changes), said once; the silhouette's own frames go on as they are.
        kLog.warning(std::string("iso panel: CUDA's shading failed (") + error.what() +
                     "); GL shades it");
        cudaShadingUnavailable = true;
        cudaIso.reset();
        return false;
    }
    if (!shaded)
        return false;
    if (shading == cudaIso.get())
        cudaIsoSurface = {request.iso, SurfaceForm::of(settings)};
    frame.isoImage = std::move(shaded->image);
    frame.isoDepth = std::move(shaded->depth);
    frame.isoRenderMs = shaded->shadeMs;
    const bool extractedBySilhouette = shading == method3 && frame.silhouette;
    frame.meshMs = extractedBySilhouette ? frame.silhouette->times.extractMs : shaded->extractMs;
    frame.surfaceTriangles = shaded->triangles;
    frame.isoOnDevice = true;
    return true;
}

bool ReviewFrameRenderer::State::renderIsoOnDevice(const ReviewFrameRequest& request,
                                                   ReviewFrame& frame) {
    if (shadeIsoWithCuda(request, frame))
        return true;
#if LINEWORK_GL
    GeometryShaderSilhouetteRenderer* device = deviceIsoRenderer(request);
    if (!device)
        return false;
    SilhouetteSettings settings = request.settings;
    settings.isoReal = request.iso;
    settings.cancel = request.cancel;
    const auto start = Clock::now();
    GeometryShaderSilhouetteRenderer::IsoPanelFrame iso;
    try {
        iso =
            device->renderIsoPanel(request.isoCamera, settings, request.isoOptions,
                                   request.forceExtract, &frame.isoDepth, request.isoShadedByCuda);
    } catch (const core::Error& error) {
        // The context or the interop failed at draw time: the host path from now on (until the
        // volume changes), said once.
        deviceUnavailable = std::string("iso panel on the host: ") + error.what();
        kLog.warning(deviceUnavailable);
        deviceIso.reset();
        return false;
    }
    frame.isoImage = std::move(iso.image);
    frame.isoRenderMs = msSince(start) - iso.extractMs;
    // Method 1's own renderer extracted inside its silhouette frame, when the iso-value changed.
    const bool extractedBySilhouette = device == renderer.get() && frame.silhouette;
    frame.meshMs = extractedBySilhouette ? frame.silhouette->times.extractMs : iso.extractMs;
    frame.surfaceTriangles = iso.triangles;
    frame.isoOnDevice = true;
    return true;
#else
    (void)request;
    (void)frame;
    return false;
#endif
}

} // namespace lw::render
