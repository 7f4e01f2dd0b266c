#include "lw/render/zbuffer_silhouette_renderer.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"
#include "lw/volume/bricks.h"
#include "view_transform.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <mutex>
#include <optional>

namespace lw::render {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

} // namespace

struct ZBufferSilhouetteRenderer::State {
    const volume::Volume* volume = nullptr;
    Mesh mesh;
    bool meshValid = false;
    double meshIso = std::numeric_limits<double>::quiet_NaN();
    int meshBrickCells = -1;
    bool meshClosed = false; // the surface does not reach the volume's border

    // L variant: only the brick grid (min/max per brick, one scan of the volume) and the
    // per-worker scratch of one brick's geometry survive a frame.
    volume::BrickGrid grid;
    int gridBrickCells = -1;
    double closedIso = std::numeric_limits<double>::quiet_NaN(); // meshClosed is for this iso
    struct BrickWorker {
        kernels::cpu::BrickSurface surface;
        kernels::cpu::ScreenVertices screen;
        kernels::cpu::SegmentScratch scratch;
        std::vector<kernels::cpu::ScreenSegment> segments;
        std::size_t triangles = 0, segmentCount = 0;
        double extractMs = 0, silhouetteMs = 0, drawMs = 0, visibilityMs = 0;
    };
    std::vector<std::unique_ptr<BrickWorker>> workers;
    // Set by the last frame, for mesh() on demand after an L frame.
    double lastIso = std::numeric_limits<double>::quiet_NaN();
    int lastBrickCells = 0;
    unsigned lastThreads = 0;

    // Triangle clusters of the index buffer in use (never straddling a brick in the L variant).
    std::vector<kernels::cpu::TriangleCluster> clusters;
    kernels::cpu::TileMask needed;

    kernels::cpu::ScreenVertices screen;
    kernels::cpu::DepthBuffer surfaceDepth; // zbuffer1
    kernels::cpu::DepthBuffer lineDepth;    // zbuffer2
    kernels::cpu::SegmentScratch scratch;
    std::vector<kernels::cpu::ScreenSegment> segments;

    void buildClusters() {
        clusters.clear();
        kernels::cpu::buildClusters(mesh.positions.data(), mesh.indices.data(), 0,
                                    std::uint32_t(mesh.triangleCount()), clusters);
    }

    // The L variant keeps no whole-mesh buffers (an earlier S frame may have left them).
    void releaseMesh() {
        meshValid = false;
        mesh = Mesh();
        clusters = {};
        screen = kernels::cpu::ScreenVertices();
        segments = {};
        scratch = kernels::cpu::SegmentScratch();
    }

    void renderChunked(const Camera& camera, const SilhouetteSettings& settings,
                       SilhouetteFrame& frame);
    void colourPass(const Camera& camera, const SilhouetteSettings& settings,
                    SilhouetteFrame& frame);
};

ZBufferSilhouetteRenderer::ZBufferSilhouetteRenderer() : m_state(std::make_unique<State>()) {}
ZBufferSilhouetteRenderer::~ZBufferSilhouetteRenderer() = default;

void ZBufferSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    State& s = *m_state;
    s.volume = &volume;
    s.meshValid = false;
    // Everything cached from the previous volume goes, even when the dims are the same: the L
    // path's brick min/max would otherwise cull the new volume with the old one's ranges.
    s.gridBrickCells = -1;
    s.closedIso = std::numeric_limits<double>::quiet_NaN();
}

const Mesh& ZBufferSilhouetteRenderer::mesh() const {
    State& s = *m_state;
    if (!s.meshValid && s.volume && s.lastBrickCells > 0) {
        // After an L frame: the whole mesh only now, for a caller that asks for it.
        IsoSurfaceOptions options;
        options.brickCells = s.lastBrickCells;
        options.threads = s.lastThreads;
        extractIsoSurface(*s.volume, s.lastIso, options, s.mesh);
        s.meshValid = true;
        s.meshIso = s.lastIso;
        s.meshBrickCells = s.lastBrickCells;
    }
    return s.mesh;
}

SilhouetteFrame ZBufferSilhouetteRenderer::renderFrame(const Camera& camera,
                                                  const SilhouetteSettings& settings) {
    State& s = *m_state;
    if (!s.volume)
        throw core::Error("method 3 (z-buffer)", "no volume bound: call setVolume first");
    if (settings.brickCells < 0)
        throw core::Error("method 3 (z-buffer)", "brickCells must be 0 (whole volume) or positive");
    const unsigned threads = settings.threads;
    SilhouetteFrame frame;

    s.lastIso = settings.isoReal;
    s.lastBrickCells = settings.brickCells;
    s.lastThreads = threads;
    if (settings.brickCells > 0) {
        s.renderChunked(camera, settings, frame);
        return frame;
    }

    const bool reuse = settings.mode == ExtractionMode::CachedA && s.meshValid &&
                       s.meshIso == settings.isoReal && s.meshBrickCells == settings.brickCells;
    if (!reuse) {
        const auto start = Clock::now();
        s.meshValid = false;
        IsoSurfaceOptions options;
        options.threads = threads;
        options.cancel = settings.cancel;
        extractIsoSurface(*s.volume, settings.isoReal, options, s.mesh);
        s.buildClusters();
        s.meshClosed =
            !surfaceTouchesBorder(*s.volume, s.volume->valueMapping().toStored(settings.isoReal));
        s.closedIso = settings.isoReal;
        s.meshValid = true;
        s.meshIso = settings.isoReal;
        s.meshBrickCells = settings.brickCells;
        frame.times.extractMs = msSince(start);
    }
    frame.triangles = s.mesh.triangleCount();

    const kernels::cpu::ViewTransform view = toViewTransform(camera);
    const int width = camera.width(), height = camera.height();

    auto start = Clock::now();
    kernels::cpu::projectVertices(s.mesh.positions.data(), s.mesh.normals.data(),
                                  s.mesh.vertexCount(), view, s.screen, threads);
    frame.times.silhouetteMs += msSince(start);

    start = Clock::now();
    if (settings.visibility)
        s.surfaceDepth.reset(width, height, threads);
    s.lineDepth.reset(width, height, threads);
    frame.times.drawMs += msSince(start);

    // The silhouette pass runs first so the depth pass can skip the clusters and triangles that
    // cannot reach a pixel the colour pass compares against: zbuffer1 is exact wherever it is read.
    const std::uint32_t* indices = s.mesh.indices.data();
    s.segments.clear();
    start = Clock::now();
    kernels::cpu::findSilhouetteSegments(s.mesh.positions.data(), s.screen, indices,
                                         frame.triangles, view, s.scratch, s.segments, threads);
    frame.times.silhouetteMs += msSince(start);

    start = Clock::now();
    kernels::cpu::drawSegmentsDepth(s.segments.data(), s.segments.size(), s.lineDepth, threads);
    frame.times.drawMs += msSince(start);

    if (settings.visibility) {
        start = Clock::now();
        s.needed.markAroundLines(s.lineDepth, threads);
        kernels::cpu::drawClustersDepth(s.screen, indices, s.clusters.data(), s.clusters.size(),
                                        view, s.needed, s.surfaceDepth, threads, s.meshClosed);
        frame.times.visibilityMs += msSince(start);
    }
    frame.segments = s.segments.size();

    s.colourPass(camera, settings, frame);
    return frame;
}

// The L variant: one brick's geometry at a time per worker. Each active brick (min/max admit the
// iso-value) is extracted, its silhouette segments go into zbuffer2 and its triangles into
// zbuffer1, and its geometry is dropped before the worker takes the next brick; the colour pass
// runs once. Both buffers keep per-pixel maxima and a brick's vertices are bit-identical to the
// whole mesh's, so the image equals S's. Memory: the volume, the two buffers and one brick's
// surface per worker. Time: the extraction runs every frame, mode a included (caching the mesh
// would defeat the purpose), and zbuffer1 is drawn in full, because the segments that decide which
// tiles the colour pass reads are only complete after the last brick. L trades time for memory.
void ZBufferSilhouetteRenderer::State::renderChunked(const Camera& camera,
                                                     const SilhouetteSettings& settings,
                                                     SilhouetteFrame& frame) {
    const unsigned threads = settings.threads == 0 ? core::workerCount() : settings.threads;
    releaseMesh();
    const double storedIso = storedIsoValue(*volume, settings.isoReal);

    auto start = Clock::now();
    if (gridBrickCells != settings.brickCells) {
        grid = volume::BrickGrid::build(*volume, glm::ivec3(settings.brickCells));
        gridBrickCells = settings.brickCells;
    }
    if (!(closedIso == settings.isoReal)) {
        meshClosed = !surfaceTouchesBorder(*volume, storedIso);
        closedIso = settings.isoReal;
    }
    const std::vector<int> active = grid.activeBricks(storedIso);
    const kernels::cpu::BrickSurfaceExtractor extractor(*volume, storedIso);
    const double setupMs = msSince(start);

    const kernels::cpu::ViewTransform view = toViewTransform(camera);
    start = Clock::now();
    if (settings.visibility)
        surfaceDepth.reset(camera.width(), camera.height(), threads);
    lineDepth.reset(camera.width(), camera.height(), threads);
    const double clearMs = msSince(start);

    // Bricks are handed out dynamically; a worker's scratch is checked out for one brick at a time.
    const std::size_t workerCount =
        std::min<std::size_t>(threads, std::max<std::size_t>(active.size(), 1));
    while (workers.size() < workerCount)
        workers.push_back(std::make_unique<BrickWorker>());
    std::vector<BrickWorker*> idle;
    for (std::size_t w = 0; w < workerCount; ++w) {
        BrickWorker& worker = *workers[w];
        worker.triangles = worker.segmentCount = 0;
        worker.extractMs = worker.silhouetteMs = worker.drawMs = worker.visibilityMs = 0.0;
        idle.push_back(&worker);
    }
    std::mutex idleMutex;
    start = Clock::now();
    core::parallelFor(
        active.size(),
        [&](std::size_t i) {
            if (settings.cancel && settings.cancel->isCancelled())
                throw core::Cancelled(); // parallelFor stops the other bricks and rethrows
            BrickWorker* worker = nullptr;
            {
                std::lock_guard lock(idleMutex);
                worker = idle.back();
                idle.pop_back();
            }
            BrickWorker& w = *worker;
            auto t = Clock::now();
            extractor.extract(grid.bricks()[std::size_t(active[i])], w.surface);
            w.extractMs += msSince(t);
            const std::size_t triangles = w.surface.triangleCount();
            if (triangles > 0) {
                t = Clock::now();
                kernels::cpu::projectVertices(w.surface.positions.data(), w.surface.normals.data(),
                                              w.surface.positions.size(), view, w.screen, 1);
                w.segments.clear();
                kernels::cpu::findSilhouetteSegments(w.surface.positions.data(), w.screen,
                                                     w.surface.indices.data(), triangles, view,
                                                     w.scratch, w.segments, 1);
                w.silhouetteMs += msSince(t);
                t = Clock::now();
                kernels::cpu::drawSegmentsDepth(w.segments.data(), w.segments.size(), lineDepth, 1);
                w.drawMs += msSince(t);
                if (settings.visibility) {
                    t = Clock::now();
                    kernels::cpu::drawTrianglesDepth(w.screen, w.surface.indices.data(), triangles,
                                                     surfaceDepth, 1, meshClosed);
                    w.visibilityMs += msSince(t);
                }
                w.triangles += triangles;
                w.segmentCount += w.segments.size();
            }
            std::lock_guard lock(idleMutex);
            idle.push_back(worker);
        },
        threads);
    const double loopMs = msSince(start);

    // Stage times: the workers' summed times, scaled to the loop's wall time.
    double extractMs = 0, silhouetteMs = 0, drawMs = 0, visibilityMs = 0;
    for (std::size_t w = 0; w < workerCount; ++w) {
        const BrickWorker& worker = *workers[w];
        frame.triangles += worker.triangles;
        frame.segments += worker.segmentCount;
        extractMs += worker.extractMs;
        silhouetteMs += worker.silhouetteMs;
        drawMs += worker.drawMs;
        visibilityMs += worker.visibilityMs;
    }
    const double busy = extractMs + silhouetteMs + drawMs + visibilityMs;
    const double scale = busy > 0.0 ? loopMs / busy : 0.0;
    frame.times.extractMs = setupMs + extractMs * scale;
    frame.times.silhouetteMs = silhouetteMs * scale;
    frame.times.drawMs = clearMs + drawMs * scale;
    frame.times.visibilityMs = visibilityMs * scale;
    colourPass(camera, settings, frame);
}

float ZBufferSilhouetteRenderer::depthEpsilon(const Camera& camera, const volume::Volume& volume) {
    // Depth-key range of the volume's box for this camera.
    const Aabb box = volumeBounds(volume);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i < 8; ++i) {
        const double key = 1.0 - camera.project(box.corner(i)).ndcDepth;
        lo = std::min(lo, key);
        hi = std::max(hi, key);
    }
    return float(kRelativeDepthEpsilon * (hi - lo));
}

void ZBufferSilhouetteRenderer::State::colourPass(const Camera& camera,
                                                  const SilhouetteSettings& settings,
                                                  SilhouetteFrame& frame) {
    const int width = camera.width(), height = camera.height();
    const auto start = Clock::now();
    const float epsilon =
        settings.visibility ? ZBufferSilhouetteRenderer::depthEpsilon(camera, *volume) : 0.0f;
    frame.lines = PixelMask(width, height);
    kernels::cpu::resolveSilhouette(surfaceDepth, lineDepth, epsilon, settings.visibility,
                                    frame.lines.pixels().data(), settings.threads);
    frame.times.drawMs += msSince(start);
}

} // namespace lw::render
