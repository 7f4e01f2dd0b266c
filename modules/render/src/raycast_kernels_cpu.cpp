#include "raycast_kernels_cpu.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/pixel_camera.h"
#include "lw/kernels/voxel_ray_walk.h"
#include "lw/render/line_raster.h"
#include "lw/volume/bricks.h"
#include "mesh_silhouette.h"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace lw::render {
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

kernels::cpu::SilhouetteView viewOf(const Camera& camera) {
    kernels::cpu::SilhouetteView view;
    view.orthographic = camera.isOrthographic();
    view.eyeOrDirection = view.orthographic ? -camera.forward() : camera.eye();
    view.pixelSpan = kernels::rayPixelSpan(camera.halfHeight(), camera.height());
    return view;
}

void throwIfCancelled(const SilhouetteSettings& settings) {
    if (settings.cancel && settings.cancel->isCancelled())
        throw core::Cancelled();
}

} // namespace

void CpuRayCastKernels::bind(const volume::Volume* volume) {
    m_volume = volume;
    m_kernel = std::make_unique<kernels::cpu::RayCastSilhouetteCpu>();
    m_chunkLines.clear();
    m_chunkDots.clear();
    m_cap.clear();
    m_capSegments.clear();
}

void CpuRayCastKernels::prepare(double storedIso, const SilhouetteSettings& settings,
                                SilhouetteFrame& frame) {
    const auto start = Clock::now();
    const glm::ivec3 cells = glm::max(m_volume->dims() - 1, glm::ivec3(0));
    const int edge =
        settings.brickCells > 0 ? settings.brickCells : std::max({cells.x, cells.y, cells.z, 1});
    const volume::BrickGrid grid = volume::BrickGrid::forExtraction(*m_volume, glm::ivec3(edge));
    // Normal cones pay off only when the cells serve several views (mode a).
    const bool cones = settings.mode == ExtractionMode::CachedA;
    if (!m_kernel->prepare(*m_volume, grid, storedIso, cones, settings.threads, settings.cancel,
                           settings.gradientStencil))
        throw core::Cancelled();
    m_storedIso = storedIso;
    if (settings.closeAtBorder)
        m_cap.cap(*m_volume, storedIso, settings.gradientStencil);
    frame.times.extractMs += msSince(start);
}

bool CpuRayCastKernels::isPointVisible(const Camera& camera, glm::dvec3 point) const {
    if (!m_kernel->isPrepared())
        throw core::Error("method 2", "isPointVisible() needs a render() first");
    return m_kernel->isVisible(point, viewOf(camera));
}

// Per chunk of segments, in parallel: the lines or pixels that pass the visibility rule.
void CpuRayCastKernels::testVisibility(const Camera& camera, const SilhouetteSettings& settings) {
    const kernels::cpu::SilhouetteView view = viewOf(camera);
    const std::size_t chunks = chunkCount();
    if (m_chunkLines.size() < chunks) {
        m_chunkLines.resize(chunks);
        m_chunkDots.resize(chunks);
        m_chunkMemos.resize(chunks);
    }
    auto pixelOf = [&](glm::dvec3 p) { return glm::vec2(camera.project(p).pixel); };
    core::parallelFor(
        chunks,
        [&](std::size_t c) {
            throwIfCancelled(settings);
            auto& lines = m_chunkLines[c];
            auto& dots = m_chunkDots[c];
            auto& memo = m_chunkMemos[c];
            lines.clear();
            dots.clear();
            const bool endpointsOnly = settings.visibility && !settings.testAlongSegment;
            if (endpointsOnly)
                memo.reset(2 * chunk(c).size());
            auto visibleOf = [&](glm::dvec3 p) { return m_kernel->isVisible(p, view); };
            for (const kernels::SegmentEndpoints& segment : chunk(c)) {
                const glm::dvec3 a(segment.a), b(segment.b);
                if (!settings.visibility) {
                    lines.push_back(pixelOf(a));
                    lines.push_back(pixelOf(b));
                } else if (!settings.testAlongSegment) {
                    kernels::SegmentSpan span;
                    if (!kernels::drawnSpanOfSegment(memo.visible(segment.a, visibleOf),
                                                     memo.visible(segment.b, visibleOf), span))
                        continue;
                    if (span.from == 0.0 && span.to == 1.0) {
                        lines.push_back(pixelOf(a));
                        lines.push_back(pixelOf(b));
                    } else {
                        kernels::forEachLinePixel(
                            glm::dvec2(pixelOf(a)), glm::dvec2(pixelOf(b)), camera.width(),
                            camera.height(),
                            [&](int x, int y) {
                                dots.push_back({x, y});
                            },
                            span);
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
                        if (m_kernel->isVisible(a + t * (b - a), view)) {
                            const glm::dvec2 q = pa + t * delta;
                            dots.push_back({int(std::floor(q.x)), int(std::floor(q.y))});
                        }
                    }
                }
            }
        },
        settings.threads);
}

void CpuRayCastKernels::drawView(const Camera& camera, const SilhouetteSettings& settings,
                                 SilhouetteFrame& frame) {
    throwIfCancelled(settings);
    frame.lines = PixelMask(camera.width(), camera.height());
    auto start = Clock::now();
    const kernels::cpu::SilhouetteView view = viewOf(camera);
    frame.triangles = m_kernel->extractSegments(view, settings.threads);
    m_capSegments.clear();
    if (settings.closeAtBorder) {
        const Mesh& cap = m_cap.cap(*m_volume, m_storedIso, settings.gradientStencil);
        appendMeshSilhouette(cap, glm::vec3(view.eyeOrDirection), view.orthographic, m_capSegments);
        frame.triangles += cap.triangleCount();
    }
    frame.segments = m_kernel->segmentCount() + m_capSegments.size();
    frame.times.silhouetteMs += msSince(start);

    start = Clock::now();
    testVisibility(camera, settings);
    frame.times.visibilityMs += msSince(start);

    // Drawing is serial: a pass over the pieces is cheap and needs no atomic pixel writes.
    start = Clock::now();
    for (std::size_t c = 0; c < chunkCount(); ++c) {
        const auto& lines = m_chunkLines[c];
        for (std::size_t i = 0; i + 1 < lines.size(); i += 2)
            rasterizeLine(frame.lines, glm::dvec2(lines[i]), glm::dvec2(lines[i + 1]));
        for (const glm::ivec2 dot : m_chunkDots[c])
            if (frame.lines.contains(dot.x, dot.y))
                frame.lines.set(dot.x, dot.y);
    }
    frame.times.drawMs += msSince(start);
}

std::unique_ptr<CpuRayCastKernels> makeCpuRayCastKernels() {
    return std::make_unique<CpuRayCastKernels>();
}

#if !LINEWORK_CUDA
std::unique_ptr<RayCastKernelSet> makeCudaRayCastKernels() {
    return nullptr;
}
#endif

} // namespace lw::render
