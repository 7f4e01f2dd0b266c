#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"

#include "lw/kernels/silhouette_segment.h"
#include "lw/volume/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace lw::kernels::cpu {
namespace {

// Work items of a few thousand triangles: enough to balance two or more cores dynamically,
// few enough that handing them out costs nothing.
constexpr std::size_t kTrianglesPerChunk = 16384;
constexpr std::size_t kVerticesPerChunk = 32768;
constexpr std::size_t kRowsPerChunk = 16;
// Pixels further off screen than this are not representable in the fixed-point edge functions
// without overflow risk; such vertices only occur with a camera that does not frame the data.
constexpr double kMaxPixelCoordinate = 1 << 20;

std::size_t chunkCount(std::size_t items, std::size_t perChunk) { return (items + perChunk - 1) / perChunk; }

} // namespace

bool projectPoint(const ViewTransform& view, glm::dvec3 world, glm::dvec2& pixel, float& key, float* invW) {
    const glm::dvec4 clip = view.viewProjection * glm::dvec4(world, 1.0);
    if (!(clip.w > 0.0))
        return false;
    const double w = 1.0 / clip.w;
    pixel = {0.5 * (clip.x * w + 1.0) * view.width, 0.5 * (1.0 - clip.y * w) * view.height};
    key = float(1.0 - clip.z * w);
    if (invW)
        *invW = float(w);
    return true;
}

void ScreenVertices::resize(std::size_t count) {
    x.resize(count);
    y.resize(count);
    key.resize(count);
    invW.resize(count);
    facing.resize(count);
}

void projectVertices(const glm::vec3* positions, const glm::vec3* normals, std::size_t count,
                     const ViewTransform& view, ScreenVertices& out, unsigned threads) {
    out.resize(count);
    const glm::vec3 eyeOrDirection = glm::vec3(view.orthographic ? view.toViewer : view.eye);
    volume::parallelFor(
        chunkCount(count, kVerticesPerChunk),
        [&](std::size_t chunk) {
            const std::size_t end = std::min(count, (chunk + 1) * kVerticesPerChunk);
            for (std::size_t i = chunk * kVerticesPerChunk; i < end; ++i) {
                glm::dvec2 pixel;
                float key = 0.0f, invW = 0.0f;
                const bool ok = projectPoint(view, glm::dvec3(positions[i]), pixel, key, &invW) &&
                                std::abs(pixel.x) < kMaxPixelCoordinate && std::abs(pixel.y) < kMaxPixelCoordinate;
                out.x[i] = ok ? std::int32_t(std::lround(pixel.x * double(kSubpixelScale))) : kInvalidVertex;
                out.y[i] = ok ? std::int32_t(std::lround(pixel.y * double(kSubpixelScale))) : kInvalidVertex;
                out.key[i] = key;
                out.invW[i] = invW;
                out.facing[i] = silhouetteDistance(positions[i], normals[i], eyeOrDirection, view.orthographic);
            }
        },
        threads);
}

void DepthBuffer::reset(int width, int height, unsigned threads) {
    m_width = std::max(width, 0);
    m_height = std::max(height, 0);
    const std::size_t count = std::size_t(m_width) * std::size_t(m_height);
    m_bits.resize(count);
    // Clearing in parallel keeps the pages on the cores that will touch them.
    volume::parallelFor(
        chunkCount(std::size_t(m_height), kRowsPerChunk),
        [&](std::size_t chunk) {
            const std::size_t begin = chunk * kRowsPerChunk * std::size_t(m_width);
            const std::size_t end = std::min(count, begin + kRowsPerChunk * std::size_t(m_width));
            std::fill(m_bits.begin() + std::ptrdiff_t(begin), m_bits.begin() + std::ptrdiff_t(end), 0u);
        },
        threads);
}

float DepthBuffer::keyAt(std::size_t index) const {
    float key;
    std::memcpy(&key, &m_bits[index], sizeof key);
    return key;
}

void drawTrianglesDepth(const ScreenVertices& vertices, const std::uint32_t* indices, std::size_t triangleCount,
                        DepthBuffer& depth, unsigned threads) {
    const int width = depth.width(), height = depth.height();
    volume::parallelFor(
        chunkCount(triangleCount, kTrianglesPerChunk),
        [&](std::size_t chunk) {
            const std::size_t end = std::min(triangleCount, (chunk + 1) * kTrianglesPerChunk);
            for (std::size_t t = chunk * kTrianglesPerChunk; t < end; ++t) {
                const std::uint32_t* tri = indices + 3 * t;
                forEachCoveredPixel(vertices, tri[0], tri[1], tri[2], width, height, [&](int x, int y, float key) {
                    depth.writeMax(std::size_t(y) * std::size_t(width) + std::size_t(x), key);
                });
            }
        },
        threads);
}

void drawTrianglesNearest(const ScreenVertices& vertices, const std::uint32_t* indices, std::size_t triangleCount,
                          std::uint32_t firstTriangle, std::vector<std::uint64_t>& nearest, int width, int height,
                          unsigned threads) {
    nearest.resize(std::size_t(std::max(width, 0)) * std::size_t(std::max(height, 0)));
    volume::parallelFor(
        chunkCount(triangleCount, kTrianglesPerChunk),
        [&](std::size_t chunk) {
            const std::size_t end = std::min(triangleCount, (chunk + 1) * kTrianglesPerChunk);
            for (std::size_t t = chunk * kTrianglesPerChunk; t < end; ++t) {
                const std::uint32_t* tri = indices + 3 * t;
                const std::uint64_t id = std::uint64_t(firstTriangle) + t + 1;
                forEachCoveredPixel(vertices, tri[0], tri[1], tri[2], width, height, [&](int x, int y, float key) {
                    if (!(key > 0.0f))
                        return; // outside the near/far range: the packed order needs positive keys
                    std::uint32_t bits;
                    std::memcpy(&bits, &key, sizeof bits);
                    const std::uint64_t packed = (std::uint64_t(bits) << 32) | id;
                    std::atomic_ref<std::uint64_t> cell(nearest[std::size_t(y) * std::size_t(width) + std::size_t(x)]);
                    std::uint64_t old = cell.load(std::memory_order_relaxed);
                    while (old < packed && !cell.compare_exchange_weak(old, packed, std::memory_order_relaxed)) {
                    }
                });
            }
        },
        threads);
}

void findSilhouetteSegments(const glm::vec3* positions, const ScreenVertices& vertices, const std::uint32_t* indices,
                            std::size_t triangleCount, const ViewTransform& view, SegmentScratch& scratch,
                            std::vector<ScreenSegment>& out, unsigned threads) {
    const std::size_t chunks = chunkCount(triangleCount, kTrianglesPerChunk);
    if (scratch.chunks.size() < chunks)
        scratch.chunks.resize(chunks);
    volume::parallelFor(
        chunks,
        [&](std::size_t chunk) {
            std::vector<ScreenSegment>& local = scratch.chunks[chunk];
            local.clear();
            const std::size_t end = std::min(triangleCount, (chunk + 1) * kTrianglesPerChunk);
            for (std::size_t t = chunk * kTrianglesPerChunk; t < end; ++t) {
                const std::uint32_t* tri = indices + 3 * t;
                const float d[3] = {vertices.facing[tri[0]], vertices.facing[tri[1]], vertices.facing[tri[2]]};
                // Cheap sign test first: almost every triangle is entirely front- or back-facing.
                const bool f0 = d[0] >= 0.0f, f1 = d[1] >= 0.0f, f2 = d[2] >= 0.0f;
                if (f0 == f1 && f1 == f2)
                    continue;
                const glm::vec3 p[3] = {positions[tri[0]], positions[tri[1]], positions[tri[2]]};
                SegmentEndpoints ends;
                if (!silhouetteSegment(p, d, ends))
                    continue;
                ScreenSegment segment;
                if (!projectPoint(view, glm::dvec3(ends.a), segment.a, segment.keyA) ||
                    !projectPoint(view, glm::dvec3(ends.b), segment.b, segment.keyB))
                    continue;
                local.push_back(segment);
            }
        },
        threads);
    for (std::size_t chunk = 0; chunk < chunks; ++chunk)
        out.insert(out.end(), scratch.chunks[chunk].begin(), scratch.chunks[chunk].end());
}

void drawSegmentsDepth(const ScreenSegment* segments, std::size_t count, DepthBuffer& lines, unsigned threads) {
    const int width = lines.width(), height = lines.height();
    constexpr std::size_t kSegmentsPerChunk = 4096;
    volume::parallelFor(
        chunkCount(count, kSegmentsPerChunk),
        [&](std::size_t chunk) {
            const std::size_t end = std::min(count, (chunk + 1) * kSegmentsPerChunk);
            for (std::size_t s = chunk * kSegmentsPerChunk; s < end; ++s) {
                const ScreenSegment& segment = segments[s];
                // The same stepping as lw::render::rasterizeLine, so methods 2 and 3 set the same
                // pixels for the same segment; the key is affine along the projected line.
                const glm::dvec2 delta = segment.b - segment.a;
                const double steps = std::max(std::abs(delta.x), std::abs(delta.y));
                if (!(steps < kMaxPixelCoordinate))
                    continue;
                const int stepCount = int(std::ceil(steps));
                for (int i = 0; i <= stepCount; ++i) {
                    const double t = stepCount == 0 ? 0.0 : double(i) / double(stepCount);
                    const glm::dvec2 p = segment.a + t * delta;
                    const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
                    if (x < 0 || y < 0 || x >= width || y >= height)
                        continue;
                    const float key = float(double(segment.keyA) + t * (double(segment.keyB) - double(segment.keyA)));
                    // Keys <= 0 lie beyond the far plane; they would read as "empty".
                    lines.writeMax(std::size_t(y) * std::size_t(width) + std::size_t(x),
                                   std::max(key, 1e-30f));
                }
            }
        },
        threads);
}

void resolveSilhouette(const DepthBuffer& surface, const DepthBuffer& lines, float epsilon, bool visibility,
                       std::uint8_t* mask, unsigned threads) {
    const int width = lines.width(), height = lines.height();
    volume::parallelFor(
        chunkCount(std::size_t(height), kRowsPerChunk),
        [&](std::size_t chunk) {
            const int yEnd = int(std::min<std::size_t>(std::size_t(height), (chunk + 1) * kRowsPerChunk));
            for (int y = int(chunk * kRowsPerChunk); y < yEnd; ++y) {
                for (int x = 0; x < width; ++x) {
                    const std::size_t index = std::size_t(y) * std::size_t(width) + std::size_t(x);
                    const float lineKey = lines.keyAt(index);
                    if (!(lineKey > 0.0f)) {
                        mask[index] = 0;
                        continue;
                    }
                    if (!visibility) {
                        mask[index] = 1;
                        continue;
                    }
                    float farthest = surface.keyAt(index);
                    for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1) && farthest > 0.0f; ++ny)
                        for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx)
                            farthest = std::min(farthest, surface.at(nx, ny));
                    mask[index] = lineKey >= farthest - epsilon ? 1 : 0;
                }
            }
        },
        threads);
}

} // namespace lw::kernels::cpu
