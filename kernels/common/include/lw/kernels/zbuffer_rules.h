#pragma once

// Method 3's rasterization rules, host+device: the CPU rasterizer (kernels/cpu) and the CUDA one
// (kernels/cuda) call these same functions per vertex, triangle, segment and pixel, so the two
// back-ends give the same depth buffers bit for bit (the CUDA code is compiled with --fmad=false
// so that no multiply-add is contracted where the host compiler keeps two roundings).
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
//     "inverted depth" that makes an atomic max keep the nearest fragment: positive IEEE floats
//     order like their bit patterns read as unsigned integers.

#include "lw/kernels/host_device.h"

#include <climits>
#include <cstdint>
#include <cstring>
#include <glm/glm.hpp>

namespace lw::kernels {

inline constexpr int kSubpixelBits = 8;
inline constexpr std::int64_t kSubpixelScale = std::int64_t(1) << kSubpixelBits;
// x of a vertex that could not be projected (behind the eye or absurdly far off screen).
inline constexpr std::int32_t kInvalidVertex = INT32_MIN;
// Pixels further off screen than this are not representable in the fixed-point edge functions
// without overflow risk; such vertices only occur with a camera that does not frame the data.
inline constexpr double kMaxPixelCoordinate = 1 << 20;

// The camera as the kernels see it: a plain copyable value (no render types), passed by value to
// CUDA kernels. `m` is the world (patient mm) -> GL clip-space matrix, column-major as GLM's.
struct ScreenProjection {
    double m[4][4];
    int width = 0;
    int height = 0;
};

inline ScreenProjection makeScreenProjection(const glm::dmat4& viewProjection, int width,
                                             int height) {
    ScreenProjection p{};
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            p.m[c][r] = viewProjection[c][r];
    p.width = width;
    p.height = height;
    return p;
}

// What the kernels need from a camera (kernels do not depend on the render module);
// host side: kernels take its ScreenProjection and eye/toViewer by value.
struct ViewTransform {
    glm::dmat4 viewProjection{1.0}; // world (patient mm) -> GL clip space
    int width = 0;
    int height = 0;
    bool orthographic = false;
    glm::dvec3 eye{0.0};      // perspective: Burns' d = N . (eye - P)
    glm::dvec3 toViewer{0.0}; // orthographic: d = N . toViewer

    ScreenProjection projection() const {
        return makeScreenProjection(viewProjection, width, height);
    }
};

LW_HOST_DEVICE inline std::uint32_t keyBits(float key) {
#if defined(__CUDA_ARCH__)
    return __float_as_uint(key);
#else
    std::uint32_t bits;
    std::memcpy(&bits, &key, sizeof bits);
    return bits;
#endif
}

LW_HOST_DEVICE inline float keyFromBits(std::uint32_t bits) {
#if defined(__CUDA_ARCH__)
    return __uint_as_float(bits);
#else
    float key;
    std::memcpy(&key, &bits, sizeof key);
    return key;
#endif
}

// Continuous pixel coordinates, depth key and 1/w of a world point; false when it lies behind
// the eye plane.
LW_HOST_DEVICE LW_FORCE_INLINE bool projectToScreen(const ScreenProjection& view, double x,
                                                    double y, double z, double& pixelX,
                                                    double& pixelY, float& key, float& invW) {
    const double(*m)[4] = view.m;
    const double cw = m[0][3] * x + m[1][3] * y + m[2][3] * z + m[3][3];
    if (!(cw > 0.0))
        return false;
    const double w = 1.0 / cw;
    const double cx = m[0][0] * x + m[1][0] * y + m[2][0] * z + m[3][0];
    const double cy = m[0][1] * x + m[1][1] * y + m[2][1] * z + m[3][1];
    const double cz = m[0][2] * x + m[1][2] * y + m[2][2] * z + m[3][2];
    pixelX = 0.5 * (cx * w + 1.0) * view.width;
    pixelY = 0.5 * (1.0 - cy * w) * view.height;
    key = float(1.0 - cz * w);
    invW = float(w);
    return true;
}

// Round half away from zero without a libm call (the default x86-64 target has no roundsd).
LW_HOST_DEVICE inline std::int32_t roundToInt(double v) {
    return std::int32_t(v + (v >= 0.0 ? 0.5 : -0.5));
}

// A vertex's fixed-point screen position, or {kInvalidVertex, kInvalidVertex}.
LW_HOST_DEVICE LW_FORCE_INLINE glm::ivec2 snapVertex(bool projected, double pixelX, double pixelY) {
    const bool ok = projected && (pixelX < 0.0 ? -pixelX : pixelX) < kMaxPixelCoordinate &&
                    (pixelY < 0.0 ? -pixelY : pixelY) < kMaxPixelCoordinate;
    return ok ? glm::ivec2(roundToInt(pixelX * double(kSubpixelScale)),
                           roundToInt(pixelY * double(kSubpixelScale)))
              : glm::ivec2(kInvalidVertex);
}

namespace detail {
LW_HOST_DEVICE inline std::int64_t min3(std::int64_t a, std::int64_t b, std::int64_t c) {
    const std::int64_t m = a < b ? a : b;
    return m < c ? m : c;
}
LW_HOST_DEVICE inline std::int64_t max3(std::int64_t a, std::int64_t b, std::int64_t c) {
    const std::int64_t m = a > b ? a : b;
    return m > c ? m : c;
}
// Top-left rule (y down, counter-clockwise on screen after the swap below): an edge is "left"
// when it runs downward (dy > 0), "top" when horizontal and running to the left (dy == 0,
// dx < 0). Centres exactly on such an edge are inside; on the other edges they are outside
// (bias -1 on the integer function).
LW_HOST_DEVICE inline std::int64_t topLeftBias(std::int64_t ax, std::int64_t ay, std::int64_t bx,
                                               std::int64_t by) {
    const std::int64_t dx = bx - ax, dy = by - ay;
    return (dy > 0 || (dy == 0 && dx < 0)) ? 0 : -1;
}
// Whether any pixel of the box [i0, i1] x [j0, j1] is marked in `mask` (width bytes a row).
LW_HOST_DEVICE inline bool boxHoldsMarkedPixel(const std::uint8_t* mask, int width, std::int64_t i0,
                                               std::int64_t i1, std::int64_t j0, std::int64_t j1) {
    for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t i = i0; i <= i1; ++i)
            if (mask[j * width + i])
                return true;
    return false;
}
} // namespace detail

// Calls fn(px, py, key) for every pixel centre covered by the triangle (pa, pb, pc) with depth
// keys (k0, k1, k2) under the top-left rule, key interpolated linearly in screen space. Either
// winding, unless `cullBackFaces`: then triangles that are clockwise on screen (back-facing for a
// mesh wound counter-clockwise seen from outside) cover nothing. Degenerate and invalid triangles
// cover nothing. `pixelFilter` (optional, width * height bytes): skip triangles whose pixel box
// holds no pixel marked there.
template <typename Fn>
LW_HOST_DEVICE LW_FORCE_INLINE void
forEachCoveredPixel(glm::ivec2 pa, glm::ivec2 pb, glm::ivec2 pc, float k0, float k1, float k2,
                    int width, int height, Fn&& fn, bool cullBackFaces = false,
                    const std::uint8_t* pixelFilter = nullptr) {
    std::int64_t x0 = pa.x, y0 = pa.y, x1 = pb.x, y1 = pb.y, x2 = pc.x, y2 = pc.y;
    if (x0 == kInvalidVertex || x1 == kInvalidVertex || x2 == kInvalidVertex)
        return;
    // The pixel-centre grid: centre i sits at i * 256 + 128. Most triangles of a fine mesh hold
    // no centre at all; the bounding box rejects them before any setup.
    const std::int64_t half = kSubpixelScale / 2;
    const std::int64_t minX = detail::min3(x0, x1, x2), maxX = detail::max3(x0, x1, x2);
    const std::int64_t minY = detail::min3(y0, y1, y2), maxY = detail::max3(y0, y1, y2);
    std::int64_t i0 = (minX - half + kSubpixelScale - 1) >> kSubpixelBits; // ceil
    std::int64_t i1 = (maxX - half) >> kSubpixelBits;                      // floor
    std::int64_t j0 = (minY - half + kSubpixelScale - 1) >> kSubpixelBits;
    std::int64_t j1 = (maxY - half) >> kSubpixelBits;
    i0 = i0 > 0 ? i0 : 0;
    j0 = j0 > 0 ? j0 : 0;
    i1 = i1 < width - 1 ? i1 : width - 1;
    j1 = j1 < height - 1 ? j1 : height - 1;
    if (i0 > i1 || j0 > j1)
        return;
    // Only pixels the caller will read matter; most triangles cover one or two pixels, so
    // checking the box is far cheaper than setting the triangle up.
    if (pixelFilter && !detail::boxHoldsMarkedPixel(pixelFilter, width, i0, i1, j0, j1))
        return;
    // Edge function of a -> b at p: (b.y - a.y)(p.x - a.x) - (b.x - a.x)(p.y - a.y); with y down
    // it is positive on the interior of a triangle whose area E_01(v2) is positive.
    std::int64_t area = (y1 - y0) * (x2 - x0) - (x1 - x0) * (y2 - y0);
    if (area == 0 || (area < 0 && cullBackFaces))
        return;
    if (area < 0) {
        std::int64_t t = x1;
        x1 = x2;
        x2 = t;
        t = y1;
        y1 = y2;
        y2 = t;
        const float k = k1;
        k1 = k2;
        k2 = k;
        area = -area;
    }
    using detail::topLeftBias;
    const std::int64_t px = i0 * kSubpixelScale + half, py = j0 * kSubpixelScale + half;
    // w0 belongs to edge 1->2 (weight of vertex 0), w1 to 2->0, w2 to 0->1.
    std::int64_t row0 = (y2 - y1) * (px - x1) - (x2 - x1) * (py - y1) + topLeftBias(x1, y1, x2, y2);
    std::int64_t row1 = (y0 - y2) * (px - x2) - (x0 - x2) * (py - y2) + topLeftBias(x2, y2, x0, y0);
    std::int64_t row2 = (y1 - y0) * (px - x0) - (x1 - x0) * (py - y0) + topLeftBias(x0, y0, x1, y1);
    const std::int64_t stepX0 = (y2 - y1) * kSubpixelScale, stepY0 = -(x2 - x1) * kSubpixelScale;
    const std::int64_t stepX1 = (y0 - y2) * kSubpixelScale, stepY1 = -(x0 - x2) * kSubpixelScale;
    const std::int64_t stepX2 = (y1 - y0) * kSubpixelScale, stepY2 = -(x1 - x0) * kSubpixelScale;
    // Key as a plane over pixel indices: exact barycentric weights at (i0, j0), constant steps.
    const double inv = 1.0 / double(area);
    const double d10 = double(k1) - double(k0), d20 = double(k2) - double(k0);
    const double e1 = double(row1 - topLeftBias(x2, y2, x0, y0)),
                 e2 = double(row2 - topLeftBias(x0, y0, x1, y1));
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

// A silhouette segment on screen: continuous pixel coordinates and depth keys of its ends.
struct ScreenSegment {
    glm::dvec2 a{0.0};
    glm::dvec2 b{0.0};
    float keyA = 0.0f;
    float keyB = 0.0f;
};

// zbuffer2's rule: fn(x, y, key) for each pixel that lw::render::rasterizeLine would set for the
// segment (one pixel per step along the major axis, clipped to the viewport), the key affine
// along the projected line and kept above 0 (keys <= 0 lie beyond the far plane and would read as
// "empty").
template <typename Fn>
LW_HOST_DEVICE LW_FORCE_INLINE void forEachSegmentPixel(const ScreenSegment& segment, int width,
                                                        int height, Fn&& fn) {
    const double dx = segment.b.x - segment.a.x, dy = segment.b.y - segment.a.y;
    const double adx = dx < 0.0 ? -dx : dx, ady = dy < 0.0 ? -dy : dy;
    const double steps = adx > ady ? adx : ady;
    if (!(steps < kMaxPixelCoordinate))
        return;
    const int stepCount = int(std::ceil(steps));
    for (int i = 0; i <= stepCount; ++i) {
        const double t = stepCount == 0 ? 0.0 : double(i) / double(stepCount);
        const double px = segment.a.x + t * dx, py = segment.a.y + t * dy;
        // floor() without a libm call; p is bounded, so the int conversion is exact.
        const int x = int(px) - (px < double(int(px))), y = int(py) - (py < double(int(py)));
        if (x < 0 || y < 0 || x >= width || y >= height)
            continue;
        const float key =
            float(double(segment.keyA) + t * (double(segment.keyB) - double(segment.keyA)));
        fn(x, y, key > 1e-30f ? key : 1e-30f);
    }
}

// The colour pass for one pixel. A pixel holding a segment is drawn when visibility is off, or
// when the segment is not behind the surface:
//   lineKey >= min(surface keys of the 3x3 neighbourhood) - epsilon.
// The neighbourhood is there because at an occluding contour the surface turns edge-on: the
// pixel centre next to the contour point can see the surface far in front of it (depth grows like
// sqrt(2 R s) with the curvature radius R and the screen distance s), whereas across the contour
// a neighbour sees the background or the surface behind the fold. An occluder that covers the
// whole neighbourhood hides the segment. Both buffers hold key bits (0 = empty).
LW_HOST_DEVICE LW_FORCE_INLINE std::uint8_t resolvePixel(const std::uint32_t* surface,
                                                         const std::uint32_t* lines, int x, int y,
                                                         int width, int height, float epsilon,
                                                         bool visibility) {
    const std::size_t index = std::size_t(y) * std::size_t(width) + std::size_t(x);
    const float lineKey = keyFromBits(lines[index]);
    if (!(lineKey > 0.0f))
        return 0;
    if (!visibility)
        return 1;
    float farthest = keyFromBits(surface[index]);
    const int y0 = y > 0 ? y - 1 : 0, y1 = y < height - 1 ? y + 1 : height - 1;
    const int x0 = x > 0 ? x - 1 : 0, x1 = x < width - 1 ? x + 1 : width - 1;
    for (int ny = y0; ny <= y1 && farthest > 0.0f; ++ny)
        for (int nx = x0; nx <= x1; ++nx) {
            const float k = keyFromBits(surface[std::size_t(ny) * std::size_t(width) + nx]);
            farthest = k < farthest ? k : farthest;
        }
    return lineKey >= farthest - epsilon ? 1 : 0;
}

} // namespace lw::kernels
