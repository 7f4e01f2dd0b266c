#include "lw/render/geometry_shader_silhouette_renderer.h"

#include "../cpu_brick_schedule.h"
#include "gl_api.h"
#include "gl_mesh_source.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/core/parallel.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/silhouette_segment.h"
#include "lw/render/gl_context.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/visibility_tolerance.h"
#include "lw/volume/bricks.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <optional>

namespace lw::render {
namespace {

constexpr core::LogCategory kLog("lw.render");

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The silhouette panel's colours: black lines on white, so "not background" is a line pixel.
constexpr core::Rgba8 kBackground{255, 255, 255, 255};

} // namespace

struct GeometryShaderSilhouetteRenderer::State {
    std::unique_ptr<GlContext> ownedContext;
    GlContext* context = nullptr;
    SilhouetteGlRenderer gl;
    const volume::Volume* volume = nullptr;
    Mesh mesh;
    // The CUDA back-end's extraction (useCudaExtraction); null: the CPU's. With it `mesh` is
    // downloaded only when asked for (meshOnHost false until then).
    std::unique_ptr<GlMeshSource> source;
    bool meshOnHost = true;
    bool lastFrameChunked = false;
    bool lastFrameOnSource = false; // an L frame the source streamed (else the CPU's bricks)
    // What the uploaded mesh was extracted with; empty when there is none (or the volume changed).
    std::optional<double> meshIso;
    int meshBrickCells = 0;
    bool meshClosing = false;
    GradientStencil meshStencil = GradientStencil::Central;
    // L frames: the border cap, drawn as the last piece (settings.closeAtBorder).
    BorderCapCache cap;
    // Whether the open surface at closedIso is closed (touches no border voxel): pass 1 may cull.
    std::optional<double> closedIso;
    bool closed = false;
    GeometryShaderFrameStats stats;

    // L variant: the brick grid (per-brick min/max: small) is all that mode a keeps between
    // frames; the one brick's surface is scratch reused from brick to brick.
    CpuBrickSchedule bricks;
    kernels::cpu::BrickSurface brick;
    // Host line candidates (hostLineCandidates): per chunk of triangles, then all of them.
    std::vector<std::vector<std::uint32_t>> chunkCandidates;
    std::vector<std::uint32_t> candidates;
    bool softwareGl = false; // the context is a software rasterizer: candidates on the host

    // Drops the whole mesh (CPU and GPU) so that an L frame holds one brick at a time.
    bool surfaceClosed(const SilhouetteSettings& settings) {
        if (settings.closeAtBorder)
            return true;
        const double isoReal = settings.isoReal;
        if (closedIso != isoReal) {
            closed = !surfaceTouchesBorder(*volume, storedIsoValue(*volume, isoReal));
            closedIso = isoReal;
        }
        return closed;
    }

    // The L frame's pieces on the CPU: the active bricks of the brick grid (kept in mode a,
    // rebuilt in mode b, as S's mode b rebuilds its extractor), each extracted and uploaded
    // (billed to extraction, as S's upload is), then drawn.
    void drawCpuBricks(const SilhouetteSettings& settings, double storedIso, SilhouetteFrame& frame,
                       const std::function<void(std::size_t)>& drawPiece) {
        auto start = Clock::now();
        const CpuBrickPass pass =
            bricks.pass(*volume, settings.brickCells, storedIso, settings.gradientStencil,
                        settings.mode == ExtractionMode::EveryFrameB);
        frame.times.extractMs += msSince(start);
        for (std::size_t i = 0; i < pass.size(); ++i) {
            start = Clock::now();
            pass.extractor.extract(pass.brick(i), brick);
            const std::size_t triangles = brick.triangleCount();
            if (triangles > 0) {
                gl.uploadMesh(brick.positions, brick.normals, brick.indices);
                glFinish();
            }
            frame.times.extractMs += msSince(start);
            if (triangles > 0)
                drawPiece(triangles);
        }
    }

    // The border cap as the L frame's last piece (uploaded from the host: it is small).
    void drawCap(double storedIso, const SilhouetteSettings& settings, SilhouetteFrame& frame,
                 const std::function<void(std::size_t)>& drawPiece) {
        const auto start = Clock::now();
        const Mesh& piece = cap.cap(*volume, storedIso, settings.gradientStencil);
        if (piece.isEmpty())
            return;
        gl.uploadMesh(piece);
        glFinish();
        frame.times.extractMs += msSince(start);
        drawPiece(piece.triangleCount());
    }

    // The frame's line mask (thresholded and flipped on the GPU where GL runs compute shaders:
    // SilhouetteGlRenderer::readRedMask); strokes under minStrokePixels are pruned on the CUDA
    // source's device where there is one (the host's search is single-threaded), else by the
    // caller on the host.
    void readLines(const Camera& camera, const SilhouetteSettings& settings,
                   SilhouetteFrame& frame) {
        frame.lines = PixelMask(camera.width(), camera.height());
        gl.readRedMask(kBackground.r, frame.lines.pixels());
        const int minPixels = settings.minStrokePixels;
        frame.strokesPruned = minPixels > 1 && source &&
                              source->pruneStrokes(frame.lines, minPixels, kStrokeGapPixels);
    }

    // Pass 2's candidates from the host mesh (the CPU extraction): the triangles whose facing can
    // change for `camera` (mayHoldContour, the rule the CUDA source applies on the device) into
    // gl's candidate buffer; `indices` gets their count times 3. On a software rasterizer the
    // geometry shader runs on these same cores, and the test per triangle costs a fraction of
    // sending it through the shader.
    bool hostLineCandidates(const Camera& camera, unsigned threads, std::size_t& indices) {
        if (!meshOnHost || mesh.triangleCount() == 0)
            return false;
        const glm::vec4 viewer = camera.viewerHomogeneous();
        constexpr std::size_t kChunk = 1 << 16;
        const std::size_t triangles = mesh.triangleCount();
        const std::size_t chunks = (triangles + kChunk - 1) / kChunk;
        chunkCandidates.resize(chunks);
        core::parallelForRanges(
            triangles, kChunk,
            [&](std::size_t begin, std::size_t end) {
                std::vector<std::uint32_t>& out = chunkCandidates[begin / kChunk];
                out.clear();
                for (std::size_t t = begin; t < end; ++t) {
                    const std::uint32_t* v = &mesh.indices[3 * t];
                    const glm::vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]],
                                            mesh.positions[v[2]]};
                    const glm::vec3 n[3] = {mesh.normals[v[0]], mesh.normals[v[1]],
                                            mesh.normals[v[2]]};
                    if (kernels::mayHoldContour(p, n, viewer))
                        out.insert(out.end(), v, v + 3);
                }
            },
            threads);
        candidates.clear();
        for (const std::vector<std::uint32_t>& chunk : chunkCandidates)
            candidates.insert(candidates.end(), chunk.begin(), chunk.end());
        gl.reserveLineCandidates(triangles);
        gl.writeLineCandidatesTail(0, candidates);
        indices = candidates.size();
        return true;
    }

    void dropWholeMesh() {
        meshIso.reset();
        mesh = Mesh{};
        meshOnHost = true;
        gl.clearMesh();
    }

    // Extracts and uploads when `force` or the cached mesh was made with other settings;
    // returns the time spent (0 when the cache was used).
    double ensureMesh(const SilhouetteSettings& settings, bool force) {
        if (!volume)
            throw core::Error("method 1", "render called before setVolume");
        if (!force && meshIso && *meshIso == settings.isoReal &&
            meshBrickCells == settings.brickCells && meshClosing == settings.closeAtBorder &&
            meshStencil == settings.gradientStencil)
            return 0.0;
        const auto start = Clock::now();
        IsoSurfaceOptions options;
        options.brickCells = settings.brickCells;
        options.threads = settings.threads;
        options.cancel = settings.cancel;
        options.closeAtBorder = settings.closeAtBorder;
        options.gradientStencil = settings.gradientStencil;
        meshIso.reset(); // a failed extraction or upload leaves no stale cache behind
        if (source) {
            mesh = Mesh{};
            meshOnHost = false;
            source->extractInto(gl, settings);
        } else {
            extractIsoSurface(*volume, settings.isoReal, options, mesh);
            meshOnHost = true;
            gl.uploadMesh(mesh);
        }
        glFinish(); // the upload is part of this stage, not of the next draw
        meshIso = settings.isoReal;
        meshBrickCells = settings.brickCells;
        meshClosing = settings.closeAtBorder;
        meshStencil = settings.gradientStencil;
        return msSince(start);
    }
};

GeometryShaderSilhouetteRenderer::GeometryShaderSilhouetteRenderer()
    : m_state(std::make_unique<State>()) {
    m_state->ownedContext = std::make_unique<EglHeadlessContext>();
    m_state->context = m_state->ownedContext.get();
    m_state->softwareGl = isSoftwareRenderer(m_state->context->description());
    kLog.info("method 1 on " + m_state->context->description());
}

GeometryShaderSilhouetteRenderer::GeometryShaderSilhouetteRenderer(GlContext& context)
    : m_state(std::make_unique<State>()) {
    m_state->context = &context;
    m_state->softwareGl = isSoftwareRenderer(context.description());
}

GeometryShaderSilhouetteRenderer::~GeometryShaderSilhouetteRenderer() {
    // GL objects belong to the context: they must go while it is still alive and current. The
    // source's interop registrations go here; the renderer's GL objects go with State, whose
    // renderer is destroyed before the context it owns (declared after it).
    try {
        m_state->context->makeCurrent();
        if (m_state->source)
            m_state->source->releaseGl();
    } catch (const std::exception& error) {
        kLog.warning(std::string("method 1: GL objects not released: ") + error.what());
    }
}

std::string_view GeometryShaderSilhouetteRenderer::backendName() const {
    // L frames stream slabs on the source's device (CUDA) or extract bricks on the CPU.
    const bool onSource = !m_state->lastFrameChunked || m_state->lastFrameOnSource;
    return m_state->source && onSource ? m_state->source->backendName() : "gl";
}

void GeometryShaderSilhouetteRenderer::useCudaExtraction() {
    std::unique_ptr<GlMeshSource> source = makeCudaGlMeshSource();
    if (!source)
        throw core::Error("method 1", "this build has no CUDA back-end with OpenGL interop");
    if (m_state->volume)
        source->setVolume(*m_state->volume);
    m_state->source = std::move(source);
    m_state->meshIso.reset();
}

void GeometryShaderSilhouetteRenderer::releaseVolume() {
    State& s = *m_state;
    if (s.source)
        s.source->releaseVolume();
    s.volume = nullptr;
    s.meshIso.reset();
    s.closedIso.reset();
    s.cap.clear();
    s.mesh = Mesh{};
    s.bricks.reset();
}

void GeometryShaderSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    if (m_state->source)
        m_state->source->setVolume(volume);
    m_state->volume = &volume;
    m_state->meshIso.reset();
    m_state->closedIso.reset();
    m_state->cap.clear();
    m_state->mesh = Mesh{};
    m_state->bricks.reset();
}

void GeometryShaderSilhouetteRenderer::setVolumeWithDeviceCopy(const volume::Volume& volume,
                                                               DeviceVoxelCopy copy) {
    setVolume(volume);
    if (m_state->source)
        m_state->source->useDeviceCopy(copy);
}

const GeometryShaderFrameStats& GeometryShaderSilhouetteRenderer::lastFrameStats() const {
    return m_state->stats;
}

const Mesh& GeometryShaderSilhouetteRenderer::mesh() const {
    State& s = *m_state;
    if (!s.meshOnHost && s.source && s.meshIso) {
        s.source->download(s.mesh);
        s.meshOnHost = true;
    }
    return s.mesh;
}

const Mesh* GeometryShaderSilhouetteRenderer::surfaceMesh() const {
    return m_state->meshIso ? &mesh() : nullptr;
}

// Only while the surface is on the device alone: once downloaded, the host has it whole.
std::optional<Mesh> GeometryShaderSilhouetteRenderer::contourTriangles(const Camera& camera) const {
    State& s = *m_state;
    if (s.meshOnHost || !s.source || !s.meshIso)
        return std::nullopt;
    return s.source->contourTriangles(camera);
}

std::string GeometryShaderSilhouetteRenderer::contextDescription() const {
    return m_state->context->description();
}

SilhouetteFrame GeometryShaderSilhouetteRenderer::renderFrame(const Camera& camera,
                                                              const SilhouetteSettings& settings) {
    m_state->lastFrameChunked = settings.brickCells > 0;
    if (settings.brickCells > 0)
        return renderBricks(camera, settings);
    State& s = *m_state;
    s.context->makeCurrent();
    SilhouetteFrame frame;
    frame.times.extractMs = s.ensureMesh(settings, settings.mode == ExtractionMode::EveryFrameB);

    SilhouetteGlOptions options;
    options.panel = GlPanel::Silhouette;
    options.visibility = settings.visibility;
    options.lineColour = {0.0f, 0.0f, 0.0f, 1.0f};
    options.background = {1.0f, 1.0f, 1.0f, 1.0f};
    options.countSegments = true;
    options.timePasses = true;
    options.depthTolerance = windowDepthTolerance(camera, volumeBounds(*s.volume));
    options.cullBackFacesInDepthPass = settings.visibility && s.surfaceClosed(settings);
    // Pass 2 sends only the triangles whose facing can change (a few percent): the rest would
    // enter the geometry shader only to emit nothing. The GPU culls them in the frame's own
    // context; a software rasterizer (whose shaders run on these same cores) gets them from the
    // host; a context without compute shaders sends every triangle.
    glFinish();
    const auto start = Clock::now();
    if (s.softwareGl)
        options.useLineCandidates =
            s.hostLineCandidates(camera, settings.threads, options.lineCandidateIndices);
    else
        options.cullLineCandidatesOnGpu = true;
    options.maskOnly = true; // readLines reads the mask alone
    // The mask's stage is queued behind the passes before the host waits for any of them: one
    // wait a frame, and the GPU never idles between the passes and the mask.
    s.gl.queueRender(camera, options);
    s.readLines(camera, settings, frame);
    SilhouetteGlStats stats = s.gl.queuedStats();
    if (stats.incomplete) { // more segments than the GPU's buffer held, which has grown since
        stats = s.gl.render(camera, options);
        s.readLines(camera, settings, frame);
    }
    // The passes' GPU times (timer queries) as visibility (pass 1: the depth to test against) and
    // silhouette (passes 2 and 3); draw is the rest of the frame's wall time: setup, and the
    // read-back (with CUDA also the pruning) of the mask (a software rasterizer's timer queries
    // may bill a deferred pass to the wrong query, so the rest can come out negative).
    frame.times.visibilityMs = stats.surfacePassMs;
    frame.times.silhouetteMs = stats.linePassMs;
    frame.times.drawMs = std::max(0.0, msSince(start) - stats.surfacePassMs - stats.linePassMs);
    frame.triangles = stats.triangles;
    frame.segments = stats.segments;
    s.stats = {};
    s.stats.bricksDrawn = stats.triangles > 0 ? 1 : 0;
    s.stats.peakUploadedTriangles = s.gl.triangleCount();
    return frame;
}

std::vector<std::size_t>
GeometryShaderSilhouetteRenderer::brickTriangleCounts(const volume::Volume& volume, double isoReal,
                                                      int brickCells) {
    if (brickCells <= 0)
        throw core::Error("brick triangle counts", "brickCells must be positive");
    const double storedIso = volume.valueMapping().toStored(isoReal);
    CpuBrickSchedule schedule;
    const CpuBrickPass pass =
        schedule.pass(volume, brickCells, storedIso, GradientStencil::Central, true);
    kernels::cpu::BrickSurface surface;
    std::vector<std::size_t> counts;
    for (std::size_t i = 0; i < pass.size(); ++i) {
        pass.extractor.extract(pass.brick(i), surface);
        counts.push_back(surface.triangleCount());
    }
    return counts;
}

SilhouetteFrame GeometryShaderSilhouetteRenderer::renderBricks(const Camera& camera,
                                                               const SilhouetteSettings& settings) {
    State& s = *m_state;
    if (!s.volume)
        throw core::Error("method 1", "render called before setVolume");
    const double storedIso = storedIsoValue(*s.volume, settings.isoReal);
    s.context->makeCurrent();
    s.dropWholeMesh(); // no-op after the first L frame
    s.stats = {};
    SilhouetteFrame frame;

    SilhouetteGlOptions options;
    options.panel = GlPanel::Silhouette;
    options.visibility = settings.visibility;
    options.lineColour = {0.0f, 0.0f, 0.0f, 1.0f};
    options.background = {1.0f, 1.0f, 1.0f, 1.0f};
    options.countSegments = true;
    options.depthTolerance = windowDepthTolerance(camera, volumeBounds(*s.volume));
    options.clear = false;
    options.resolve = false;
    options.cullBackFacesInDepthPass = settings.visibility && s.surfaceClosed(settings);
    options.cullLineCandidatesOnGpu = !s.softwareGl; // each piece culls its own triangles

    glFinish();
    auto start = Clock::now();
    s.gl.clear(camera.width(), camera.height(), options.background);
    glFinish();
    frame.times.drawMs += msSince(start);
    // Each piece of the surface, once in the GL buffers, adds its surface depth and its lines'
    // depth to the frame's two depth buffers; one resolve at the end colours the visible lines.
    const auto drawPiece = [&](std::size_t triangles) {
        if (settings.cancel && settings.cancel->isCancelled())
            throw core::Cancelled();
        const auto drawStart = Clock::now();
        const SilhouetteGlStats stats = s.gl.render(camera, options);
        glFinish();
        frame.times.drawMs += msSince(drawStart);
        frame.triangles += stats.triangles;
        frame.segments += stats.segments;
        s.stats.peakUploadedTriangles = std::max(s.stats.peakUploadedTriangles, triangles);
        ++s.stats.bricksDrawn;
    };
    // The CUDA source streams slabs through its device budget; the CPU extracts bricks.
    start = Clock::now();
    const double drawnBefore = frame.times.drawMs;
    s.lastFrameOnSource = s.source && s.source->extractPiecesInto(s.gl, settings, drawPiece);
    if (s.lastFrameOnSource)
        frame.times.extractMs += msSince(start) - (frame.times.drawMs - drawnBefore);
    else
        s.drawCpuBricks(settings, storedIso, frame, drawPiece);
    if (settings.closeAtBorder)
        s.drawCap(storedIso, settings, frame, drawPiece);
    start = Clock::now();
    s.gl.resolve(options);
    s.readLines(camera, settings, frame);
    frame.times.drawMs += msSince(start);
    return frame;
}

core::ImageRgba8
GeometryShaderSilhouetteRenderer::renderIsoPanel(const Camera& camera,
                                                 const SilhouetteSettings& settings) {
    State& s = *m_state;
    s.context->makeCurrent();
    s.ensureMesh(settings, false);
    SilhouetteGlOptions options;
    options.panel = GlPanel::Iso;
    options.visibility = settings.visibility;
    return s.gl.renderImage(camera, options);
}

GeometryShaderSilhouetteRenderer::IsoPanelFrame GeometryShaderSilhouetteRenderer::renderIsoPanel(
    const Camera& camera, const SilhouetteSettings& settings, const SilhouetteGlOptions& options,
    bool forceExtract, std::vector<float>* depth, bool cudaShading) {
    State& s = *m_state;
    s.context->makeCurrent();
    SilhouetteSettings whole = settings;
    whole.brickCells = 0; // the panel shows the whole surface, whatever the silhouette's chunking
    IsoPanelFrame frame;
    frame.extractMs = s.ensureMesh(whole, forceExtract);
    const auto start = Clock::now();
    if (cudaShading && s.source && !options.linesOnIso &&
        s.source->shadeWhole(camera, glPanelShading(camera, options), frame.image, depth,
                             frame.triangles)) {
        frame.drawMs = msSince(start);
        return frame;
    }
    SilhouetteGlOptions iso = options;
    iso.panel = GlPanel::Iso;
    iso.useLineCandidates = false;
    frame.image = s.gl.renderImage(camera, iso);
    if (depth)
        *depth = s.gl.readDepth();
    frame.drawMs = msSince(start);
    frame.triangles = s.gl.triangleCount();
    return frame;
}

bool GeometryShaderSilhouetteRenderer::extractsOnDevice() const {
    return m_state->source != nullptr;
}

} // namespace lw::render
