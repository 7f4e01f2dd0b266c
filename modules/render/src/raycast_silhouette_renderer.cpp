#include "lw/render/raycast_silhouette_renderer.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/cpu/raycast_silhouette_cpu.h"
#include "lw/render/iso_surface.h"
#include "lw/render/line_raster.h"
#include "lw/volume/bricks.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace lw::render {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

} // namespace

struct RayCastSilhouetteRenderer::Cache {
    kernels::cpu::RayCastSilhouetteCpu kernel;
    double storedIso = 0.0;
    int brickCells = -1;
    bool valid = false;
    bool withCones = false;
    // Per segment chunk of the kernel, reused between frames: the projected lines to draw
    // (pairs of float pixel points) and, along segments, the single pixels of visible steps.
    // Projected points are rounded to float once, and every mode draws from the rounded
    // values, so a visible piece is pixel for pixel part of the line drawn with visibility off.
    std::vector<std::vector<glm::vec2>> chunkLines;
    std::vector<std::vector<glm::ivec2>> chunkDots;
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
    const auto& kernel = m_cache->kernel;
    out.reserve(kernel.segmentCount());
    for (std::size_t c = 0; c < kernel.segmentChunkCount(); ++c)
        for (const auto& s : kernel.segmentChunk(c))
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

SilhouetteFrame RayCastSilhouetteRenderer::renderFrame(const Camera& camera,
                                                  const SilhouetteSettings& settings) {
    if (!m_volume)
        throw core::Error("method 2", "no volume bound (setVolume)");
    const volume::Volume& volume = *m_volume;
    const double storedIso = storedIsoValue(volume, settings.isoReal);
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
        cache.valid = false; // until a prepare completes
        if (!cache.kernel.prepare(volume, grid, storedIso, cachedMode, settings.threads,
                                  settings.cancel))
            throw core::Cancelled();
        cache.withCones = cachedMode;
        cache.storedIso = storedIso;
        cache.brickCells = settings.brickCells;
        cache.valid = true;
        frame.times.extractMs = msSince(start);
    }

    const auto throwIfCancelled = [&] {
        if (settings.cancel && settings.cancel->isCancelled())
            throw core::Cancelled();
    };
    throwIfCancelled();
    start = Clock::now();
    const kernels::cpu::SilhouetteView view = viewOf(camera);
    frame.triangles = cache.kernel.extractSegments(view, settings.threads);
    frame.segments = cache.kernel.segmentCount();
    frame.times.silhouetteMs = msSince(start);

    start = Clock::now();
    const std::size_t chunks = cache.kernel.segmentChunkCount();
    if (cache.chunkLines.size() < chunks) {
        cache.chunkLines.resize(chunks);
        cache.chunkDots.resize(chunks);
    }
    auto pixelOf = [&](glm::dvec3 p) { return glm::vec2(camera.project(p).pixel); };
    core::parallelFor(
        chunks,
        [&](std::size_t c) {
            throwIfCancelled();
            auto& lines = cache.chunkLines[c];
            auto& dots = cache.chunkDots[c];
            lines.clear();
            dots.clear();
            for (const kernels::SegmentEndpoints& segment : cache.kernel.segmentChunk(c)) {
                const glm::dvec3 a(segment.a), b(segment.b);
                if (!settings.visibility) {
                    lines.push_back(pixelOf(a));
                    lines.push_back(pixelOf(b));
                } else if (!settings.testAlongSegment) {
                    if (cache.kernel.isVisible(a, view) && cache.kernel.isVisible(b, view)) {
                        lines.push_back(pixelOf(a));
                        lines.push_back(pixelOf(b));
                    }
                } else {
                    // One test per step of rasterizeLine (at most a pixel apart), with its own
                    // arithmetic, keeping exactly the pixels whose step is visible.
                    const glm::dvec2 pa(pixelOf(a)), pb(pixelOf(b));
                    const glm::dvec2 delta = pb - pa;
                    const int count =
                        int(std::ceil(std::max(std::abs(delta.x), std::abs(delta.y))));
                    for (int step = 0; step <= count; ++step) {
                        const double t = count == 0 ? 0.0 : double(step) / double(count);
                        if (cache.kernel.isVisible(a + t * (b - a), view)) {
                            const glm::dvec2 q = pa + t * delta;
                            dots.push_back({int(std::floor(q.x)), int(std::floor(q.y))});
                        }
                    }
                }
            }
        },
        settings.threads);
    frame.times.visibilityMs = msSince(start);

    // Drawing is serial: a pass over the pieces is cheap and needs no atomic pixel writes.
    start = Clock::now();
    for (std::size_t c = 0; c < chunks; ++c) {
        const auto& lines = cache.chunkLines[c];
        for (std::size_t i = 0; i + 1 < lines.size(); i += 2)
            rasterizeLine(frame.lines, glm::dvec2(lines[i]), glm::dvec2(lines[i + 1]));
        for (const glm::ivec2 dot : cache.chunkDots[c])
            if (frame.lines.contains(dot.x, dot.y))
                frame.lines.set(dot.x, dot.y);
    }
    frame.times.drawMs = msSince(start);
    return frame;
}

} // namespace lw::render
