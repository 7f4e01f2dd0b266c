// Method 3's CPU kernel set (zbuffer_kernel_set.h): the software z-buffer rasterizer of
// lw/kernels/cpu/zbuffer_rasterizer_cpu.h on all cores.
//   S   the kept mesh, split into triangle clusters; the silhouette pass first, so the depth
//       pass can skip the clusters that cannot reach a pixel the colour pass compares against
//   L   bricks of a volume::BrickGrid handed to the workers: each active brick extracted,
//       drawn into both buffers (per-pixel maxima) and dropped; the brick's vertices are the
//       whole mesh's, so the image is S's
#include "cpu_brick_schedule.h"
#include "lw/core/parallel.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"
#include "lw/volume/bricks.h"
#include "view_transform.h"
#include "zbuffer_kernel_set.h"

#include <algorithm>
#include <chrono>
#include <mutex>

namespace lw::render {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// One worker's scratch for the L variant: one brick's geometry at a time.
struct BrickWorker {
    kernels::cpu::BrickSurface surface;
    kernels::cpu::ScreenVertices screen;
    kernels::cpu::SegmentScratch scratch;
    std::vector<kernels::cpu::ScreenSegment> segments;
    std::size_t triangles = 0, segmentCount = 0;
    double extractMs = 0, silhouetteMs = 0, drawMs = 0, visibilityMs = 0;
};

class CpuZBufferKernels final : public ZBufferKernelSet {
public:
    std::string_view backendName() const override { return "cpu"; }

    void bind(const volume::Volume* volume) override {
        m_volume = volume;
        releaseMesh();
        // Even for a volume of the same size: the brick min/max would cull it with the old one's.
        m_bricks.reset();
        m_cap.clear();
    }

    bool keepsWholeSurface(const Camera&, const SilhouetteSettings&) override { return true; }

    bool extractWhole(double storedIso, const SilhouetteSettings& settings,
                      SilhouetteFrame& frame) override {
        const auto start = Clock::now();
        IsoSurfaceOptions options;
        options.threads = settings.threads;
        options.cancel = settings.cancel;
        options.closeAtBorder = settings.closeAtBorder;
        options.gradientStencil = settings.gradientStencil;
        m_meshKept = false;
        extractIsoSurface(*m_volume, settings.isoReal, options, m_mesh);
        m_clusters.clear();
        kernels::cpu::buildClusters(m_mesh.positions.data(), m_mesh.indices.data(), 0,
                                    std::uint32_t(m_mesh.triangleCount()), m_clusters);
        m_meshKept = true;
        frame.times.extractMs += msSince(start);
        return !surfaceIsClosed(*m_volume, storedIso, settings.closeAtBorder);
    }

    const Mesh* keptMesh() override { return m_meshKept ? &m_mesh : nullptr; }

    void beginFrame(const Camera& camera, const SilhouetteSettings& settings,
                    SilhouetteFrame& frame) override {
        const auto start = Clock::now();
        m_view = toViewTransform(camera);
        if (settings.visibility)
            m_surfaceDepth.reset(camera.width(), camera.height(), settings.threads);
        m_lineDepth.reset(camera.width(), camera.height(), settings.threads);
        frame.times.drawMs += msSince(start);
    }

    void drawWhole(const Camera& camera, const SilhouetteSettings& settings, bool closed,
                   SilhouetteFrame& frame) override;
    void drawPieces(const Camera& camera, const SilhouetteSettings& settings, double storedIso,
                    bool closed, SilhouetteFrame& frame) override;

    void resolve(const SilhouetteSettings& settings, float epsilon,
                 SilhouetteFrame& frame) override {
        const auto start = Clock::now();
        frame.lines = PixelMask(m_lineDepth.width(), m_lineDepth.height());
        kernels::cpu::resolveSilhouette(m_surfaceDepth, m_lineDepth, epsilon, settings.visibility,
                                        frame.lines.pixels().data(), settings.threads);
        frame.times.drawMs += msSince(start);
    }

private:
    // An L frame keeps no whole-mesh buffers (an earlier S frame may have left them).
    void releaseMesh() {
        m_meshKept = false;
        m_mesh = Mesh();
        m_clusters = {};
        m_screen = kernels::cpu::ScreenVertices();
        m_segments = {};
        m_scratch = kernels::cpu::SegmentScratch();
    }
    void drawBrick(const kernels::cpu::BrickSurfaceExtractor& extractor, const volume::Brick& brick,
                   bool visibility, bool closed, BrickWorker& w);
    // One piece of the surface (a brick's, the border cap) into both buffers, on one thread.
    void drawPiece(const Mesh& piece, bool visibility, bool closed, BrickWorker& w);
    std::vector<BrickWorker*> readyWorkers(std::size_t count);

    const volume::Volume* m_volume = nullptr;
    Mesh m_mesh;
    bool m_meshKept = false;
    // Triangle clusters of the kept mesh and the tiles the colour pass will read.
    std::vector<kernels::cpu::TriangleCluster> m_clusters;
    kernels::cpu::TileMask m_needed;
    kernels::cpu::ViewTransform m_view{};
    kernels::cpu::ScreenVertices m_screen;
    kernels::cpu::DepthBuffer m_surfaceDepth; // zbuffer1
    kernels::cpu::DepthBuffer m_lineDepth;    // zbuffer2
    kernels::cpu::SegmentScratch m_scratch;
    std::vector<kernels::cpu::ScreenSegment> m_segments;
    // L: the brick grid (min/max per brick, one scan of the volume) and the workers' scratch.
    CpuBrickSchedule m_bricks;
    std::vector<std::unique_ptr<BrickWorker>> m_workers;
    BorderCapCache m_cap;
};

void CpuZBufferKernels::drawWhole(const Camera&, const SilhouetteSettings& settings, bool closed,
                                  SilhouetteFrame& frame) {
    const unsigned threads = settings.threads;
    auto start = Clock::now();
    // Without visibility no surface is drawn: the vertices' facing is all the frame needs.
    (settings.visibility ? kernels::cpu::projectVertices : kernels::cpu::evaluateFacing)(
        m_mesh.positions.data(), m_mesh.normals.data(), m_mesh.vertexCount(), m_view, m_screen,
        threads);
    const std::uint32_t* indices = m_mesh.indices.data();
    m_segments.clear();
    kernels::cpu::findSilhouetteSegments(m_mesh.positions.data(), m_screen, indices,
                                         m_mesh.triangleCount(), m_view, m_scratch, m_segments,
                                         threads);
    frame.times.silhouetteMs += msSince(start);

    start = Clock::now();
    kernels::cpu::drawSegmentsDepth(m_segments.data(), m_segments.size(), m_lineDepth, threads);
    frame.times.drawMs += msSince(start);
    if (settings.visibility) {
        start = Clock::now();
        m_needed.markAroundLines(m_lineDepth, threads);
        kernels::cpu::drawClustersDepth(m_screen, indices, m_clusters.data(), m_clusters.size(),
                                        m_view, m_needed, m_surfaceDepth, threads, closed);
        frame.times.visibilityMs += msSince(start);
    }
    frame.triangles = m_mesh.triangleCount();
    frame.segments = m_segments.size();
}

void CpuZBufferKernels::drawBrick(const kernels::cpu::BrickSurfaceExtractor& extractor,
                                  const volume::Brick& brick, bool visibility, bool closed,
                                  BrickWorker& w) {
    const auto t = Clock::now();
    extractor.extract(brick, w.surface);
    w.extractMs += msSince(t);
    drawPiece(w.surface, visibility, closed, w);
}

void CpuZBufferKernels::drawPiece(const Mesh& piece, bool visibility, bool closed, BrickWorker& w) {
    const std::size_t triangles = piece.triangleCount();
    if (triangles == 0)
        return;
    auto t = Clock::now();
    (visibility ? kernels::cpu::projectVertices : kernels::cpu::evaluateFacing)(
        piece.positions.data(), piece.normals.data(), piece.positions.size(), m_view, w.screen, 1);
    w.segments.clear();
    kernels::cpu::findSilhouetteSegments(piece.positions.data(), w.screen, piece.indices.data(),
                                         triangles, m_view, w.scratch, w.segments, 1);
    w.silhouetteMs += msSince(t);
    t = Clock::now();
    kernels::cpu::drawSegmentsDepth(w.segments.data(), w.segments.size(), m_lineDepth, 1);
    w.drawMs += msSince(t);
    if (visibility) {
        t = Clock::now();
        kernels::cpu::drawTrianglesDepth(w.screen, piece.indices.data(), triangles, m_surfaceDepth,
                                         1, closed);
        w.visibilityMs += msSince(t);
    }
    w.triangles += triangles;
    w.segmentCount += w.segments.size();
}

std::vector<BrickWorker*> CpuZBufferKernels::readyWorkers(std::size_t count) {
    while (m_workers.size() < count)
        m_workers.push_back(std::make_unique<BrickWorker>());
    std::vector<BrickWorker*> idle;
    for (std::size_t w = 0; w < count; ++w) {
        BrickWorker& worker = *m_workers[w];
        worker.triangles = worker.segmentCount = 0;
        worker.extractMs = worker.silhouetteMs = worker.drawMs = worker.visibilityMs = 0.0;
        idle.push_back(&worker);
    }
    return idle;
}

// Memory: the volume, the two buffers and one brick's surface per worker. Time: the extraction
// runs every frame, mode a included (caching the mesh would defeat the purpose), and zbuffer1 is
// drawn in full, because the segments that decide which tiles the colour pass reads are only
// complete after the last brick.
void CpuZBufferKernels::drawPieces(const Camera&, const SilhouetteSettings& settings,
                                   double storedIso, bool closed, SilhouetteFrame& frame) {
    const unsigned threads = settings.threads == 0 ? core::workerCount() : settings.threads;
    releaseMesh();
    auto start = Clock::now();
    // S beyond no budget never comes here on the CPU: brickCells > 0. The grid is kept in mode
    // b too: method 3 extracts every frame in both modes.
    const CpuBrickPass pass =
        m_bricks.pass(*m_volume, settings.brickCells, storedIso, settings.gradientStencil, false);
    frame.times.extractMs += msSince(start);

    // Bricks are handed out dynamically; a worker's scratch is checked out for one brick at a time.
    const std::size_t workerCount =
        std::min<std::size_t>(threads, std::max<std::size_t>(pass.size(), 1));
    std::vector<BrickWorker*> idle = readyWorkers(workerCount);
    std::mutex idleMutex;
    start = Clock::now();
    core::parallelFor(
        pass.size(),
        [&](std::size_t i) {
            if (settings.cancel && settings.cancel->isCancelled())
                throw core::Cancelled(); // parallelFor stops the other bricks and rethrows
            BrickWorker* worker = nullptr;
            {
                std::lock_guard lock(idleMutex);
                worker = idle.back();
                idle.pop_back();
            }
            drawBrick(pass.extractor, pass.brick(i), settings.visibility, closed, *worker);
            std::lock_guard lock(idleMutex);
            idle.push_back(worker);
        },
        threads);
    if (settings.closeAtBorder) // one more piece, after the bricks (the buffers keep maxima)
        drawPiece(m_cap.cap(*m_volume, storedIso, settings.gradientStencil), settings.visibility,
                  closed, *idle.back());
    const double loopMs = msSince(start);

    // Stage times: the workers' summed times, scaled to the loop's wall time.
    double extractMs = 0, silhouetteMs = 0, drawMs = 0, visibilityMs = 0;
    for (std::size_t w = 0; w < workerCount; ++w) {
        const BrickWorker& worker = *m_workers[w];
        frame.triangles += worker.triangles;
        frame.segments += worker.segmentCount;
        extractMs += worker.extractMs;
        silhouetteMs += worker.silhouetteMs;
        drawMs += worker.drawMs;
        visibilityMs += worker.visibilityMs;
    }
    const double busy = extractMs + silhouetteMs + drawMs + visibilityMs;
    const double scale = busy > 0.0 ? loopMs / busy : 0.0;
    frame.times.extractMs += extractMs * scale;
    frame.times.silhouetteMs += silhouetteMs * scale;
    frame.times.drawMs += drawMs * scale;
    frame.times.visibilityMs += visibilityMs * scale;
}

} // namespace

std::unique_ptr<ZBufferKernelSet> makeCpuZBufferKernels() {
    return std::make_unique<CpuZBufferKernels>();
}

#if !LINEWORK_CUDA
std::unique_ptr<ZBufferKernelSet> makeCudaZBufferKernels() {
    return nullptr;
}
#endif

} // namespace lw::render
