#pragma once

// Method 3's software z-buffer rasterizer on the CPU (the reference for the CUDA kernels).
//
// The per-vertex, per-triangle, per-segment and per-pixel rules (fixed-point snapping, top-left
// rule, depth key, segment stepping, colour pass) live in lw/kernels/zbuffer_rules.h, shared with
// the CUDA back-end; this file adds the CPU's buffers, threading and culling around them.

#include "lw/kernels/zbuffer_rules.h"

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace lw::kernels::cpu {

using kernels::kInvalidVertex;
using kernels::kSubpixelBits;
using kernels::kSubpixelScale;

using kernels::ViewTransform;

// One projected point: continuous pixel coordinates and the depth key. Returns false when the
// point is behind the eye plane.
bool projectPoint(const ViewTransform& view, glm::dvec3 world, glm::dvec2& pixel, float& key,
                  float* invW = nullptr);

// Per-vertex screen data, structure of arrays so the triangle loop touches only what it uses.
struct ScreenVertices {
    // Fixed-point position (1/256 px), x and y side by side so the triangle loop loads one cache
    // line per vertex; x == kInvalidVertex when the vertex could not be projected.
    std::vector<glm::ivec2> xy;
    std::vector<float> key;          // depth key (see above)
    std::vector<float> invW;         // 1 / clip w, for perspective-correct attribute interpolation
    std::vector<float> facing;       // Burns' d at the vertex (>= 0: front-facing)
    std::vector<std::uint8_t> front; // facing >= 0, one byte so the segment pass reads little

    void resize(std::size_t count);
    std::size_t size() const { return xy.size(); }
};

// Projects `count` vertices and evaluates Burns' d with their normals, on `threads` threads.
void projectVertices(const glm::vec3* positions, const glm::vec3* normals, std::size_t count,
                     const ViewTransform& view, ScreenVertices& out, unsigned threads = 0);
// Burns' d (facing, front) alone, the screen fields left as they are: what the silhouette pass
// reads (its segments' ends are projected where they are found), for a frame that rasterizes no
// surface (visibility off).
void evaluateFacing(const glm::vec3* positions, const glm::vec3* normals, std::size_t count,
                    const ViewTransform& view, ScreenVertices& out, unsigned threads = 0);

// Depth keys of one viewport, 0 = empty. Writes keep the largest key (the nearest fragment)
// through an atomic max on the float's bit pattern (positive IEEE floats order like their bits
// read as unsigned integers), so multi-threaded drawing gives the same buffer in any order.
class DepthBuffer {
public:
    // Sizes the buffer (reusing its memory) and clears it to 0.
    void reset(int width, int height, unsigned threads = 0);
    int width() const { return m_width; }
    int height() const { return m_height; }
    float at(int x, int y) const {
        return keyAt(std::size_t(y) * std::size_t(m_width) + std::size_t(x));
    }
    float keyAt(std::size_t index) const;
    std::uint32_t* bits() { return m_bits.data(); }
    const std::uint32_t* bits() const { return m_bits.data(); }

    void writeMax(std::size_t index, float key) {
        std::uint32_t bits;
        static_assert(sizeof bits == sizeof key);
        __builtin_memcpy(&bits, &key, sizeof bits);
        std::atomic_ref<std::uint32_t> cell(m_bits[index]);
        std::uint32_t old = cell.load(std::memory_order_relaxed);
        while (old < bits && !cell.compare_exchange_weak(old, bits, std::memory_order_relaxed)) {
        }
    }

private:
    int m_width = 0;
    int m_height = 0;
    std::vector<std::uint32_t> m_bits;
};

// forEachCoveredPixel (zbuffer_rules.h) for triangle (a, b, c) of `v`.
template <typename Fn>
[[gnu::always_inline]] inline void
forEachCoveredPixel(const ScreenVertices& v, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                    int width, int height, Fn&& fn, bool cullBackFaces = false,
                    const std::uint8_t* pixelFilter = nullptr) {
    kernels::forEachCoveredPixel(v.xy[a], v.xy[b], v.xy[c], v.key[a], v.key[b], v.key[c], width,
                                 height, fn, cullBackFaces, pixelFilter);
}

// zbuffer1: every triangle's depth (indices: three per triangle). `cullBackFaces` is only exact
// for a closed surface, where a back face always lies behind a front face on the same pixel.
void drawTrianglesDepth(const ScreenVertices& vertices, const std::uint32_t* indices,
                        std::size_t triangleCount, DepthBuffer& depth, unsigned threads = 0,
                        bool cullBackFaces = false);

// A run of consecutive triangles (marching cubes emits them cell by cell, so a run is spatially
// compact) with the box around its vertices. Built once per mesh; per frame the box's projection
// tells whether the run can touch any pixel that the colour pass will look at.
struct TriangleCluster {
    std::uint32_t first = 0; // triangle index into the index buffer the cluster was built from
    std::uint32_t count = 0;
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
};
inline constexpr std::uint32_t kTrianglesPerCluster = 256;

// Appends the clusters of triangles [first, first + count) of `indices` (never crossing `first`
// or the end, so per-brick ranges keep their own clusters).
void buildClusters(const glm::vec3* positions, const std::uint32_t* indices, std::uint32_t first,
                   std::uint32_t count, std::vector<TriangleCluster>& out);

// Which 8 x 8 pixel tiles the colour pass reads: the tiles under every segment pixel's 3x3
// neighbourhood (resolveSilhouette compares against those surface depths only).
class TileMask {
public:
    static constexpr int kTileBits = 3;
    void markAroundLines(const DepthBuffer& lines, unsigned threads = 0);
    int tilesX() const { return m_tilesX; }
    int tilesY() const { return m_tilesY; }
    bool any(int tx0, int ty0, int tx1, int ty1) const; // inclusive, clamped
    std::size_t count() const;
    // The same at pixel level: 1 for every pixel in a segment pixel's 3x3 neighbourhood.
    const std::uint8_t* pixels() const { return m_pixels.data(); }

private:
    int m_tilesX = 0;
    int m_tilesY = 0;
    std::vector<std::uint8_t> m_needed;
    std::vector<std::uint8_t> m_pixels;
};

// zbuffer1 where the colour pass needs it: draws the clusters whose projected box overlaps a
// needed tile and, in them, the triangles whose pixel box holds a needed pixel, so every needed
// pixel gets exactly the depth drawTrianglesDepth would give it; other pixels may stay empty.
void drawClustersDepth(const ScreenVertices& vertices, const std::uint32_t* indices,
                       const TriangleCluster* clusters, std::size_t clusterCount,
                       const ViewTransform& view, const TileMask& needed, DepthBuffer& depth,
                       unsigned threads = 0, bool cullBackFaces = false);

// The nearest triangle per pixel, packed as (key bits << 32) | (triangle index + 1) and kept by
// an atomic max, so equal depths resolve to the larger index whatever the thread order. 0 = empty.
void drawTrianglesNearest(const ScreenVertices& vertices, const std::uint32_t* indices,
                          std::size_t triangleCount, std::uint32_t firstTriangle,
                          std::vector<std::uint64_t>& nearest, int width, int height,
                          unsigned threads = 0);

using kernels::ScreenSegment;

// Reusable per-chunk scratch for findSilhouetteSegments (no allocation once warmed up).
struct SegmentScratch {
    std::vector<std::vector<ScreenSegment>> chunks;
};

// Burns' segment of every triangle whose vertices' d values differ in sign (facing from
// projectVertices), projected; appended to `out` in triangle order (deterministic).
void findSilhouetteSegments(const glm::vec3* positions, const ScreenVertices& vertices,
                            const std::uint32_t* indices, std::size_t triangleCount,
                            const ViewTransform& view, SegmentScratch& scratch,
                            std::vector<ScreenSegment>& out, unsigned threads = 0);

// zbuffer2: each segment's depth along the pixels that lw::render::rasterizeLine would set (one
// pixel per step along the major axis), the nearest segment kept per pixel.
void drawSegmentsDepth(const ScreenSegment* segments, std::size_t count, DepthBuffer& lines,
                       unsigned threads = 0);

// The colour pass. A pixel holding a segment is drawn when visibility is off, or when the
// segment is not behind the surface:
//   lineKey >= min(surface keys of the 3x3 neighbourhood) - epsilon.
// The neighbourhood is there because at an occluding contour the surface turns edge-on: the
// pixel centre next to the contour point can see the surface far in front of it (depth grows like
// sqrt(2 R s) with the curvature radius R and the screen distance s), whereas across the contour
// a neighbour sees the background or the surface behind the fold. An occluder that covers the
// whole neighbourhood hides the segment. mask: width * height bytes, 1 = silhouette.
void resolveSilhouette(const DepthBuffer& surface, const DepthBuffer& lines, float epsilon,
                       bool visibility, std::uint8_t* mask, unsigned threads = 0);

} // namespace lw::kernels::cpu
