#include "lw/render/raycast_silhouette_renderer.h"

#include "lw/core/error.h"
#include "lw/kernels/cpu/raycast_silhouette_cpu.h"
#include "lw/render/line_raster.h"
#include "lw/volume/bricks.h"
#include "lw/volume/parallel.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace lw::render {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Segments per visibility work item: big enough to amortise the hand-out, small enough to
// balance rays of very different lengths.
constexpr std::size_t kVisibilityChunk = 256;

struct Piece {
    glm::dvec2 a;
    glm::dvec2 b;
};

} // namespace

struct RayCastSilhouetteRenderer::Cache {
    kernels::cpu::RayCastSilhouetteCpu kernel;
    double storedIso = 0.0;
    int brickCells = -1;
    bool valid = false;
    bool withCones = false;
    std::vector<kernels::SegmentEndpoints> segments;
    std::vector<std::vector<Piece>> chunkPieces; // reused between frames
};

RayCastSilhouetteRenderer::RayCastSilhouetteRenderer() : m_cache(std::make_unique<Cache>()) {}
RayCastSilhouetteRenderer::~RayCastSilhouetteRenderer() = default;

void RayCastSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    m_volume = &volume;
    m_cache = std::make_unique<Cache>();
}

std::size_t RayCastSilhouetteRenderer::activeCellCount() const {
    return m_cache->kernel.activeCellCount();
}

std::vector<RayCastSilhouetteRenderer::Segment> RayCastSilhouetteRenderer::lastSegments() const {
    std::vector<Segment> out;
    out.reserve(m_cache->segments.size());
    for (const auto& s : m_cache->segments)
        out.push_back({s.a, s.b});
    return out;
}

static kernels::cpu::SilhouetteView viewOf(const Camera& camera) {
    kernels::cpu::SilhouetteView view;
    view.orthographic = camera.isOrthographic();
    view.eyeOrDirection = view.orthographic ? -camera.forward() : camera.eye();
    return view;
}

bool RayCastSilhouetteRenderer::isPointVisible(const Camera& camera, glm::dvec3 point) const {
    if (!m_cache->kernel.isPrepared())
        throw core::Error("method 2", "isPointVisible() needs a render() first");
    return m_cache->kernel.isVisible(point, viewOf(camera));
}

SilhouetteFrame RayCastSilhouetteRenderer::render(const Camera& camera,
                                                  const SilhouetteSettings& settings) {
    if (!m_volume)
        throw core::Error("method 2", "no volume bound (setVolume)");
    const volume::Volume& volume = *m_volume;
    const auto& mapping = volume.valueMapping();
    if (!(mapping.slope > 0.0))
        throw core::Error("method 2", "the volume's value mapping needs a positive slope");
    const double storedIso = mapping.toStored(settings.isoReal);
    Cache& cache = *m_cache;

    SilhouetteFrame frame;
    frame.lines = PixelMask(camera.width(), camera.height());

    auto start = Clock::now();
    const bool cachedMode = settings.mode == ExtractionMode::CachedA;
    const bool stale = !cache.valid || cache.storedIso != storedIso ||
                       cache.brickCells != settings.brickCells || (cachedMode && !cache.withCones);
    if (stale || !cachedMode) {
        const glm::ivec3 cells = glm::max(volume.dims() - 1, glm::ivec3(0));
        const int edge = settings.brickCells > 0 ? settings.brickCells
                                                 : std::max({cells.x, cells.y, cells.z, 1});
        const volume::BrickGrid grid = volume::BrickGrid::build(volume, glm::ivec3(edge));
        // Normal cones pay off only when the cells serve several views (mode a).
        cache.kernel.prepare(volume, grid, storedIso, cachedMode, settings.threads);
        cache.withCones = cachedMode;
        cache.storedIso = storedIso;
        cache.brickCells = settings.brickCells;
        cache.valid = true;
        frame.times.extractMs = msSince(start);
    }

    start = Clock::now();
    const kernels::cpu::SilhouetteView view = viewOf(camera);
    frame.triangles = cache.kernel.extractSegments(view, cache.segments, settings.threads);
    frame.segments = cache.segments.size();
    frame.times.silhouetteMs = msSince(start);

    start = Clock::now();
    const std::size_t chunks = (cache.segments.size() + kVisibilityChunk - 1) / kVisibilityChunk;
    if (cache.chunkPieces.size() < chunks)
        cache.chunkPieces.resize(chunks);
    volume::parallelFor(
        chunks,
        [&](std::size_t c) {
            auto& pieces = cache.chunkPieces[c];
            pieces.clear();
            const std::size_t end = std::min(cache.segments.size(), (c + 1) * kVisibilityChunk);
            for (std::size_t i = c * kVisibilityChunk; i < end; ++i) {
                const glm::dvec3 a(cache.segments[i].a), b(cache.segments[i].b);
                const glm::dvec2 pa = camera.project(a).pixel, pb = camera.project(b).pixel;
                if (!settings.visibility) {
                    pieces.push_back({pa, pb});
                } else if (!settings.testAlongSegment) {
                    if (cache.kernel.isVisible(a, view) && cache.kernel.isVisible(b, view))
                        pieces.push_back({pa, pb});
                } else {
                    // One test per step of the line rasterizer (rasterizeLine's own parameter
                    // steps, at most a pixel apart), drawing exactly the pixels whose step is
                    // visible: the visible pieces are then pixel for pixel part of the full line.
                    const glm::dvec2 delta = pb - pa;
                    const int count =
                        int(std::ceil(std::max(std::abs(delta.x), std::abs(delta.y))));
                    for (int s = 0; s <= count; ++s) {
                        const double t = count == 0 ? 0.0 : double(s) / double(count);
                        if (cache.kernel.isVisible(a + t * (b - a), view)) {
                            const glm::dvec2 q = pa + t * delta;
                            pieces.push_back({q, q});
                        }
                    }
                }
            }
        },
        settings.threads);
    frame.times.visibilityMs = msSince(start);

    // Drawing is serial: a pass over the pieces is cheap and needs no atomic pixel writes.
    start = Clock::now();
    for (std::size_t c = 0; c < chunks; ++c)
        for (const Piece& piece : cache.chunkPieces[c])
            rasterizeLine(frame.lines, piece.a, piece.b);
    frame.times.drawMs = msSince(start);
    return frame;
}

} // namespace lw::render
