#pragma once

// Method 3's software z-buffer rasterizer on the CPU (the reference for the CUDA kernels).
//
// Conventions:
//   * Screen space is the camera's viewport: x to the right, y down, pixel (i, j) covers
//     [i, i+1) x [j, j+1) and is sampled at its centre (i + 0.5, j + 0.5).
//   * Triangle vertices are snapped to a fixed-point grid of 1/256 pixel so the edge functions
//     are exact integers: two triangles sharing an edge then agree bit for bit on which pixel
//     centres lie on which side, and the top-left rule gives every centre to exactly one of them.
//   * Depth is stored as a key = 1 - NDC depth (GL convention, NDC in [-1, 1]): 0 < key < 2 inside
//     the frustum, larger = nearer, 0 = nothing drawn. NDC depth is an affine function of screen
//     position over a planar triangle (and along a projected 3D line), so interpolating the key
//     linearly in screen space is perspective-correct for both projections. This is the paper's
//     "inverted depth" that makes atomicMax keep the nearest fragment.

#include <algorithm>
#include <atomic>
#include <climits>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace lw::kernels::cpu {

inline constexpr int kSubpixelBits = 8;
inline constexpr std::int64_t kSubpixelScale = std::int64_t(1) << kSubpixelBits;
// x of a vertex that could not be projected (behind the eye or absurdly far off screen).
inline constexpr std::int32_t kInvalidVertex = INT32_MIN;

// What the kernels need from a camera (kernels do not depend on the render module).
struct ViewTransform {
    glm::dmat4 viewProjection{1.0}; // world (patient mm) -> GL clip space
    int width = 0;
    int height = 0;
    bool orthographic = false;
    glm::dvec3 eye{0.0};      // perspective: Burns' d = N . (eye - P)
    glm::dvec3 toViewer{0.0}; // orthographic: d = N . toViewer
};

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

// Calls fn(px, py, key) for every pixel centre covered by the triangle (a, b, c) under the
// top-left rule, key interpolated linearly in screen space. Either winding, unless
// `cullBackFaces`: then triangles that are clockwise on screen (back-facing for a mesh wound
// counter-clockwise seen from outside) cover nothing. Degenerate and invalid triangles cover
// nothing.
template <typename Fn>
[[gnu::always_inline]] inline void
forEachCoveredPixel(const ScreenVertices& v, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                    int width, int height, Fn&& fn, bool cullBackFaces = false,
                    const std::uint8_t* pixelFilter = nullptr) {
    const glm::ivec2 pa = v.xy[a], pb = v.xy[b], pc = v.xy[c];
    std::int64_t x0 = pa.x, y0 = pa.y, x1 = pb.x, y1 = pb.y, x2 = pc.x, y2 = pc.y;
    if (x0 == kInvalidVertex || x1 == kInvalidVertex || x2 == kInvalidVertex)
        return;
    // The pixel-centre grid: centre i sits at i * 256 + 128. Most triangles of a fine mesh hold
    // no centre at all; the bounding box rejects them before any setup.
    const std::int64_t half = kSubpixelScale / 2;
    const std::int64_t minX = std::min({x0, x1, x2}), maxX = std::max({x0, x1, x2});
    const std::int64_t minY = std::min({y0, y1, y2}), maxY = std::max({y0, y1, y2});
    std::int64_t i0 = (minX - half + kSubpixelScale - 1) >> kSubpixelBits; // ceil
    std::int64_t i1 = (maxX - half) >> kSubpixelBits;                      // floor
    std::int64_t j0 = (minY - half + kSubpixelScale - 1) >> kSubpixelBits;
    std::int64_t j1 = (maxY - half) >> kSubpixelBits;
    i0 = std::max<std::int64_t>(i0, 0);
    j0 = std::max<std::int64_t>(j0, 0);
    i1 = std::min<std::int64_t>(i1, width - 1);
    j1 = std::min<std::int64_t>(j1, height - 1);
    if (i0 > i1 || j0 > j1)
        return;
    if (pixelFilter) {
        // Only pixels the caller will read matter; most triangles cover one or two pixels, so
        // checking the box is far cheaper than setting the triangle up.
        bool wanted = false;
        for (std::int64_t j = j0; j <= j1 && !wanted; ++j)
            for (std::int64_t i = i0; i <= i1; ++i)
                if (pixelFilter[j * width + i]) {
                    wanted = true;
                    break;
                }
        if (!wanted)
            return;
    }
    // Edge function of a -> b at p: (b.y - a.y)(p.x - a.x) - (b.x - a.x)(p.y - a.y); with y down
    // it is positive on the interior of a triangle whose area E_01(v2) is positive.
    std::int64_t area = (y1 - y0) * (x2 - x0) - (x1 - x0) * (y2 - y0);
    if (area == 0 || (area < 0 && cullBackFaces))
        return;
    float k0 = v.key[a], k1 = v.key[b], k2 = v.key[c];
    if (area < 0) {
        std::swap(x1, x2);
        std::swap(y1, y2);
        std::swap(k1, k2);
        area = -area;
    }
    // Top-left rule (y down, this winding): an edge is "left" when it runs downward (dy > 0),
    // "top" when horizontal and running to the left (dy == 0, dx < 0). Centres exactly on such an
    // edge are inside; on the other edges they are outside (bias -1 on the integer function).
    auto bias = [](std::int64_t ax, std::int64_t ay, std::int64_t bx,
                   std::int64_t by) -> std::int64_t {
        const std::int64_t dx = bx - ax, dy = by - ay;
        return (dy > 0 || (dy == 0 && dx < 0)) ? 0 : -1;
    };
    const std::int64_t px = i0 * kSubpixelScale + half, py = j0 * kSubpixelScale + half;
    // w0 belongs to edge 1->2 (weight of vertex 0), w1 to 2->0, w2 to 0->1.
    std::int64_t row0 = (y2 - y1) * (px - x1) - (x2 - x1) * (py - y1) + bias(x1, y1, x2, y2);
    std::int64_t row1 = (y0 - y2) * (px - x2) - (x0 - x2) * (py - y2) + bias(x2, y2, x0, y0);
    std::int64_t row2 = (y1 - y0) * (px - x0) - (x1 - x0) * (py - y0) + bias(x0, y0, x1, y1);
    const std::int64_t stepX0 = (y2 - y1) * kSubpixelScale, stepY0 = -(x2 - x1) * kSubpixelScale;
    const std::int64_t stepX1 = (y0 - y2) * kSubpixelScale, stepY1 = -(x0 - x2) * kSubpixelScale;
    const std::int64_t stepX2 = (y1 - y0) * kSubpixelScale, stepY2 = -(x1 - x0) * kSubpixelScale;
    // Key as a plane over pixel indices: exact barycentric weights at (i0, j0), constant steps.
    const double inv = 1.0 / double(area);
    const double d10 = double(k1) - double(k0), d20 = double(k2) - double(k0);
    const double e1 = double(row1 - bias(x2, y2, x0, y0)), e2 = double(row2 - bias(x0, y0, x1, y1));
    const double keyOrigin = double(k0) + (e1 * d10 + e2 * d20) * inv;
    const double keyStepX = (double(stepX1) * d10 + double(stepX2) * d20) * inv;
    const double keyStepY = (double(stepY1) * d10 + double(stepY2) * d20) * inv;
    for (std::int64_t j = j0; j <= j1; ++j) {
        std::int64_t w0 = row0, w1 = row1, w2 = row2;
        for (std::int64_t i = i0; i <= i1; ++i) {
            if ((w0 | w1 | w2) >= 0) {
                const float key =
                    float(keyOrigin + double(i - i0) * keyStepX + double(j - j0) * keyStepY);
                fn(int(i), int(j), key);
            }
            w0 += stepX0;
            w1 += stepX1;
            w2 += stepX2;
        }
        row0 += stepY0;
        row1 += stepY1;
        row2 += stepY2;
    }
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

// A silhouette segment on screen: continuous pixel coordinates and depth keys of its ends.
struct ScreenSegment {
    glm::dvec2 a{0.0};
    glm::dvec2 b{0.0};
    float keyA = 0.0f;
    float keyB = 0.0f;
};

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
