#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"

#include "lw/core/parallel.h"
#include "lw/kernels/silhouette_segment.h"

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
std::size_t chunkCount(std::size_t items, std::size_t perChunk) {
    return (items + perChunk - 1) / perChunk;
}

} // namespace

namespace {

inline bool projectInline(const ScreenProjection& view, const glm::dvec3& world, glm::dvec2& pixel,
                          float& key, float& invW) {
    return projectToScreen(view, world.x, world.y, world.z, pixel.x, pixel.y, key, invW);
}

} // namespace

bool projectPoint(const ViewTransform& view, glm::dvec3 world, glm::dvec2& pixel, float& key,
                  float* invW) {
    float w = 0.0f;
    const bool ok = projectInline(view.projection(), world, pixel, key, w);
    if (invW)
        *invW = w;
    return ok;
}

void ScreenVertices::resize(std::size_t count) {
    xy.resize(count);
    key.resize(count);
    invW.resize(count);
    facing.resize(count);
    front.resize(count);
}

namespace {

// The per-vertex pass: Burns' d always, the screen position only when `Screen` (a frame without
// visibility draws no surface, so its vertices need not be projected).
template <bool Screen>
void vertexPass(const glm::vec3* positions, const glm::vec3* normals, std::size_t count,
                const ViewTransform& view, ScreenVertices& out, unsigned threads) {
    out.resize(count);
    const glm::vec3 eyeOrDirection = glm::vec3(view.orthographic ? view.toViewer : view.eye);
    const ScreenProjection projection = view.projection();
    core::parallelForRanges(
        count, kVerticesPerChunk,
        [&](std::size_t begin, std::size_t end) {
            for (std::size_t i = begin; i < end; ++i) {
                if constexpr (Screen) {
                    glm::dvec2 pixel;
                    float key = 0.0f, invW = 0.0f;
                    const bool ok =
                        projectInline(projection, glm::dvec3(positions[i]), pixel, key, invW);
                    out.xy[i] = snapVertex(ok, pixel.x, pixel.y);
                    out.key[i] = key;
                    out.invW[i] = invW;
                }
                out.facing[i] =
                    silhouetteDistance(positions[i], normals[i], eyeOrDirection, view.orthographic);
                out.front[i] = out.facing[i] >= 0.0f ? 1 : 0;
            }
        },
        threads);
}

} // namespace

void projectVertices(const glm::vec3* positions, const glm::vec3* normals, std::size_t count,
                     const ViewTransform& view, ScreenVertices& out, unsigned threads) {
    vertexPass<true>(positions, normals, count, view, out, threads);
}

void evaluateFacing(const glm::vec3* positions, const glm::vec3* normals, std::size_t count,
                    const ViewTransform& view, ScreenVertices& out, unsigned threads) {
    vertexPass<false>(positions, normals, count, view, out, threads);
}

void DepthBuffer::reset(int width, int height, unsigned threads) {
    m_width = std::max(width, 0);
    m_height = std::max(height, 0);
    const std::size_t count = std::size_t(m_width) * std::size_t(m_height);
    m_bits.resize(count);
    // Clearing in parallel keeps the pages on the cores that will touch them.
    core::parallelForRanges(
        count, kRowsPerChunk * std::size_t(m_width),
        [&](std::size_t begin, std::size_t end) {
            std::fill(m_bits.begin() + std::ptrdiff_t(begin), m_bits.begin() + std::ptrdiff_t(end),
                      0u);
        },
        threads);
}

float DepthBuffer::keyAt(std::size_t index) const {
    float key;
    std::memcpy(&key, &m_bits[index], sizeof key);
    return key;
}

void drawTrianglesDepth(const ScreenVertices& vertices, const std::uint32_t* indices,
                        std::size_t triangleCount, DepthBuffer& depth, unsigned threads,
                        bool cullBackFaces) {
    const int width = depth.width(), height = depth.height();
    core::parallelForRanges(
        triangleCount, kTrianglesPerChunk,
        [&](std::size_t begin, std::size_t end) {
            for (std::size_t t = begin; t < end; ++t) {
                const std::uint32_t* tri = indices + 3 * t;
                forEachCoveredPixel(
                    vertices, tri[0], tri[1], tri[2], width, height,
                    [&](int x, int y, float key) {
                        depth.writeMax(std::size_t(y) * std::size_t(width) + std::size_t(x), key);
                    },
                    cullBackFaces);
            }
        },
        threads);
}

void buildClusters(const glm::vec3* positions, const std::uint32_t* indices, std::uint32_t first,
                   std::uint32_t count, std::vector<TriangleCluster>& out) {
    for (std::uint32_t begin = first; begin < first + count; begin += kTrianglesPerCluster) {
        TriangleCluster cluster;
        cluster.first = begin;
        cluster.count = std::min(kTrianglesPerCluster, first + count - begin);
        cluster.min = cluster.max = positions[indices[3 * std::size_t(begin)]];
        for (std::size_t i = 3 * std::size_t(begin); i < 3 * (std::size_t(begin) + cluster.count);
             ++i) {
            cluster.min = glm::min(cluster.min, positions[indices[i]]);
            cluster.max = glm::max(cluster.max, positions[indices[i]]);
        }
        out.push_back(cluster);
    }
}

void TileMask::markAroundLines(const DepthBuffer& lines, unsigned threads) {
    const int width = lines.width(), height = lines.height();
    m_tilesX = (width + (1 << kTileBits) - 1) >> kTileBits;
    m_tilesY = (height + (1 << kTileBits) - 1) >> kTileBits;
    m_needed.assign(std::size_t(m_tilesX) * std::size_t(m_tilesY), 0);
    m_pixels.assign(std::size_t(width) * std::size_t(height), 0);
    // One tile row per work item, so no two threads write the same byte... except the rows a
    // 3x3 neighbourhood reaches across: writes of the value 1 are idempotent, done atomically.
    core::parallelFor(
        std::size_t(m_tilesY),
        [&](std::size_t tileRow) {
            const int yEnd = std::min(height, int(tileRow + 1) << kTileBits);
            for (int y = int(tileRow) << kTileBits; y < yEnd; ++y)
                for (int x = 0; x < width; ++x) {
                    if (lines.bits()[std::size_t(y) * std::size_t(width) + std::size_t(x)] == 0)
                        continue;
                    for (int ny = std::max(0, y - 1); ny <= std::min(height - 1, y + 1); ++ny)
                        for (int nx = std::max(0, x - 1); nx <= std::min(width - 1, x + 1); ++nx) {
                            std::atomic_ref<std::uint8_t>(
                                m_pixels[std::size_t(ny) * std::size_t(width) + std::size_t(nx)])
                                .store(1, std::memory_order_relaxed);
                            std::atomic_ref<std::uint8_t> cell(
                                m_needed[std::size_t(ny >> kTileBits) * std::size_t(m_tilesX) +
                                         std::size_t(nx >> kTileBits)]);
                            cell.store(1, std::memory_order_relaxed);
                        }
                }
        },
        threads);
}

bool TileMask::any(int tx0, int ty0, int tx1, int ty1) const {
    tx0 = std::max(tx0, 0);
    ty0 = std::max(ty0, 0);
    tx1 = std::min(tx1, m_tilesX - 1);
    ty1 = std::min(ty1, m_tilesY - 1);
    for (int ty = ty0; ty <= ty1; ++ty)
        for (int tx = tx0; tx <= tx1; ++tx)
            if (m_needed[std::size_t(ty) * std::size_t(m_tilesX) + std::size_t(tx)])
                return true;
    return false;
}

std::size_t TileMask::count() const {
    return std::size_t(std::count(m_needed.begin(), m_needed.end(), 1));
}

void drawClustersDepth(const ScreenVertices& vertices, const std::uint32_t* indices,
                       const TriangleCluster* clusters, std::size_t clusterCount,
                       const ViewTransform& view, const TileMask& needed, DepthBuffer& depth,
                       unsigned threads, bool cullBackFaces) {
    const int width = depth.width(), height = depth.height();
    constexpr std::size_t kClustersPerChunk = 64;
    const ScreenProjection projection = view.projection();
    core::parallelForRanges(
        clusterCount, kClustersPerChunk,
        [&](std::size_t begin, std::size_t end) {
            for (std::size_t c = begin; c < end; ++c) {
                const TriangleCluster& cluster = clusters[c];
                // The projected box: its 8 corners bound the projection of everything inside as
                // long as all lie in front of the eye; otherwise draw the cluster unconditionally.
                double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
                for (int corner = 0; corner < 8; ++corner) {
                    const glm::dvec3 p((corner & 1) ? cluster.max.x : cluster.min.x,
                                       (corner & 2) ? cluster.max.y : cluster.min.y,
                                       (corner & 4) ? cluster.max.z : cluster.min.z);
                    glm::dvec2 pixel;
                    float key = 0.0f, invW = 0.0f;
                    if (!projectInline(projection, p, pixel, key, invW)) {
                        x0 = y0 = -1e300;
                        x1 = y1 = 1e300;
                        break;
                    }
                    x0 = std::min(x0, pixel.x);
                    y0 = std::min(y0, pixel.y);
                    x1 = std::max(x1, pixel.x);
                    y1 = std::max(y1, pixel.y);
                }
                // One pixel of slack covers the snapping of vertices to 1/256 pixel.
                auto tile = [](double v) {
                    return int(std::clamp(std::floor(v), -1.0, 1e6)) >> TileMask::kTileBits;
                };
                if (!needed.any(tile(x0 - 1.0), tile(y0 - 1.0), tile(x1 + 1.0), tile(y1 + 1.0)))
                    continue;
                const std::uint32_t* tri = indices + 3 * std::size_t(cluster.first);
                for (std::uint32_t t = 0; t < cluster.count; ++t, tri += 3)
                    forEachCoveredPixel(
                        vertices, tri[0], tri[1], tri[2], width, height,
                        [&](int x, int y, float key) {
                            depth.writeMax(std::size_t(y) * std::size_t(width) + std::size_t(x),
                                           key);
                        },
                        cullBackFaces, needed.pixels());
            }
        },
        threads);
}

void drawTrianglesNearest(const ScreenVertices& vertices, const std::uint32_t* indices,
                          std::size_t triangleCount, std::uint32_t firstTriangle,
                          std::vector<std::uint64_t>& nearest, int width, int height,
                          unsigned threads) {
    nearest.resize(std::size_t(std::max(width, 0)) * std::size_t(std::max(height, 0)));
    core::parallelForRanges(
        triangleCount, kTrianglesPerChunk,
        [&](std::size_t begin, std::size_t end) {
            for (std::size_t t = begin; t < end; ++t) {
                const std::uint32_t* tri = indices + 3 * t;
                const std::uint64_t id = std::uint64_t(firstTriangle) + t + 1;
                forEachCoveredPixel(
                    vertices, tri[0], tri[1], tri[2], width, height, [&](int x, int y, float key) {
                        if (!(key > 0.0f))
                            return; // outside the near/far range: the packed order needs positive
                                    // keys
                        std::uint32_t bits;
                        std::memcpy(&bits, &key, sizeof bits);
                        const std::uint64_t packed = (std::uint64_t(bits) << 32) | id;
                        std::atomic_ref<std::uint64_t> cell(
                            nearest[std::size_t(y) * std::size_t(width) + std::size_t(x)]);
                        std::uint64_t old = cell.load(std::memory_order_relaxed);
                        while (old < packed && !cell.compare_exchange_weak(
                                                   old, packed, std::memory_order_relaxed)) {
                        }
                    });
            }
        },
        threads);
}

void findSilhouetteSegments(const glm::vec3* positions, const ScreenVertices& vertices,
                            const std::uint32_t* indices, std::size_t triangleCount,
                            const ViewTransform& view, SegmentScratch& scratch,
                            std::vector<ScreenSegment>& out, unsigned threads) {
    const ScreenProjection projection = view.projection();
    const std::size_t chunks = chunkCount(triangleCount, kTrianglesPerChunk);
    if (scratch.chunks.size() < chunks)
        scratch.chunks.resize(chunks);
    core::parallelForRanges(
        triangleCount, kTrianglesPerChunk,
        [&](std::size_t begin, std::size_t end) {
            std::vector<ScreenSegment>& local = scratch.chunks[begin / kTrianglesPerChunk];
            local.clear();
            for (std::size_t t = begin; t < end; ++t) {
                const std::uint32_t* tri = indices + 3 * t;
                // Cheap sign test first: almost every triangle is entirely front- or back-facing.
                const unsigned sides = unsigned(vertices.front[tri[0]]) + vertices.front[tri[1]] +
                                       vertices.front[tri[2]];
                if (sides == 0 || sides == 3)
                    continue;
                const float d[3] = {vertices.facing[tri[0]], vertices.facing[tri[1]],
                                    vertices.facing[tri[2]]};
                const glm::vec3 p[3] = {positions[tri[0]], positions[tri[1]], positions[tri[2]]};
                SegmentEndpoints ends;
                if (!silhouetteSegment(p, d, ends))
                    continue;
                ScreenSegment segment;
                float invW = 0.0f;
                if (!projectInline(projection, glm::dvec3(ends.a), segment.a, segment.keyA, invW) ||
                    !projectInline(projection, glm::dvec3(ends.b), segment.b, segment.keyB, invW))
                    continue;
                local.push_back(segment);
            }
        },
        threads);
    // Reserved once at the total: appended chunk by chunk, the output would grow by doubling,
    // and at a 4 GiB volume's millions of segments the old and the new buffer side by side
    // raised the frame's peak memory by tens of MiB.
    std::size_t total = out.size();
    for (std::size_t chunk = 0; chunk < chunks; ++chunk)
        total += scratch.chunks[chunk].size();
    out.reserve(total);
    for (std::size_t chunk = 0; chunk < chunks; ++chunk)
        out.insert(out.end(), scratch.chunks[chunk].begin(), scratch.chunks[chunk].end());
}

void drawSegmentsDepth(const ScreenSegment* segments, std::size_t count, DepthBuffer& lines,
                       unsigned threads) {
    const int width = lines.width(), height = lines.height();
    constexpr std::size_t kSegmentsPerChunk = 4096;
    core::parallelForRanges(
        count, kSegmentsPerChunk,
        [&](std::size_t begin, std::size_t end) {
            for (std::size_t s = begin; s < end; ++s) {
                forEachSegmentPixel(segments[s], width, height, [&](int x, int y, float key) {
                    lines.writeMax(std::size_t(y) * std::size_t(width) + std::size_t(x), key);
                });
            }
        },
        threads);
}

void resolveSilhouette(const DepthBuffer& surface, const DepthBuffer& lines, float epsilon,
                       bool visibility, std::uint8_t* mask, unsigned threads) {
    const int width = lines.width(), height = lines.height();
    core::parallelForRanges(
        std::size_t(height), kRowsPerChunk,
        [&](std::size_t rowBegin, std::size_t rowEnd) {
            for (int y = int(rowBegin); y < int(rowEnd); ++y) {
                for (int x = 0; x < width; ++x)
                    mask[std::size_t(y) * std::size_t(width) + std::size_t(x)] = resolvePixel(
                        surface.bits(), lines.bits(), x, y, width, height, epsilon, visibility);
            }
        },
        threads);
}

} // namespace lw::kernels::cpu
