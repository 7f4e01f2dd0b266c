#pragma once

// Method 3's kernels (dispatch in zbuffer_cuda.cu). The rules -- projection, snapping, top-left
// coverage, segment stepping, the colour pass -- are kernels/common's zbuffer_rules.h, the same
// functions the CPU rasterizer calls.

#include "lw/kernels/silhouette_segment.h"
#include "lw/kernels/zbuffer_rules.h"

#include <cstdint>

namespace lw::kernels::cuda::zb {

struct ScreenVertex {
    glm::ivec2 xy; // fixed point, kInvalidVertex when not projected
    float key;
    float facing; // Burns' d
};

__global__ void projectVertices(const glm::vec3* positions, const glm::vec3* normals,
                                std::uint32_t count, ScreenProjection view,
                                glm::vec3 eyeOrDirection, bool orthographic, ScreenVertex* out) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count)
        return;
    const glm::vec3 p = positions[i];
    double px = 0.0, py = 0.0;
    float key = 0.0f, invW = 0.0f;
    const bool ok = projectToScreen(view, double(p.x), double(p.y), double(p.z), px, py, key, invW);
    ScreenVertex v;
    v.xy = snapVertex(ok, px, py);
    v.key = key;
    v.facing = silhouetteDistance(p, normals[i], eyeOrDirection, orthographic);
    out[i] = v;
}

// Burns' segment of a triangle whose vertices' d differ in sign, projected and stepped into
// zbuffer2 right away.
__device__ inline void drawSilhouetteOf(const glm::vec3* positions, std::uint32_t a,
                                        std::uint32_t b, std::uint32_t c, const float d[3],
                                        const ScreenProjection& view, std::uint32_t* lines,
                                        unsigned long long* segmentCount) {
    const int sides = int(d[0] >= 0.0f) + int(d[1] >= 0.0f) + int(d[2] >= 0.0f);
    if (sides == 0 || sides == 3)
        return;
    const glm::vec3 p[3] = {positions[a], positions[b], positions[c]};
    SegmentEndpoints ends;
    if (!silhouetteSegment(p, d, ends))
        return;
    ScreenSegment segment;
    float invW = 0.0f;
    if (!projectToScreen(view, double(ends.a.x), double(ends.a.y), double(ends.a.z), segment.a.x,
                         segment.a.y, segment.keyA, invW) ||
        !projectToScreen(view, double(ends.b.x), double(ends.b.y), double(ends.b.z), segment.b.x,
                         segment.b.y, segment.keyB, invW))
        return;
    atomicAdd(segmentCount, 1ull);
    const int width = view.width;
    forEachSegmentPixel(segment, width, view.height, [&](int x, int y, float key) {
        atomicMax(lines + std::size_t(y) * std::size_t(width) + std::size_t(x), keyBits(key));
    });
}

// A triangle's covered pixels into zbuffer1 (the surface's depth).
__device__ inline void drawCoverageOf(const ScreenVertex& a, const ScreenVertex& b,
                                      const ScreenVertex& c, int width, int height,
                                      bool cullBackFaces, std::uint32_t* surface) {
    forEachCoveredPixel(
        a.xy, b.xy, c.xy, a.key, b.key, c.key, width, height,
        [&](int x, int y, float key) {
            atomicMax(surface + std::size_t(y) * std::size_t(width) + std::size_t(x), keyBits(key));
        },
        cullBackFaces);
}

// A triangle's silhouette segment and, with Depth (visibility on), its coverage, in one thread:
// its indices and screen vertices are read once for both passes. The passes write different
// z-buffers by atomicMax, so their order does not change the image. Without Depth only the
// vertices' d is read.
template <bool Depth>
__global__ void drawTriangles(const glm::vec3* positions, const std::uint32_t* indices,
                              std::uint32_t triangleCount, const ScreenVertex* screen,
                              ScreenProjection view, bool cullBackFaces, std::uint32_t* lines,
                              std::uint32_t* surface, unsigned long long* segmentCount) {
    const std::uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
    if (t >= triangleCount)
        return;
    const std::uint32_t a = indices[3 * std::size_t(t)], b = indices[3 * std::size_t(t) + 1],
                        c = indices[3 * std::size_t(t) + 2];
    if constexpr (Depth) {
        const ScreenVertex va = screen[a], vb = screen[b], vc = screen[c];
        const float d[3] = {va.facing, vb.facing, vc.facing};
        drawSilhouetteOf(positions, a, b, c, d, view, lines, segmentCount);
        drawCoverageOf(va, vb, vc, view.width, view.height, cullBackFaces, surface);
    } else {
        const float d[3] = {screen[a].facing, screen[b].facing, screen[c].facing};
        drawSilhouetteOf(positions, a, b, c, d, view, lines, segmentCount);
    }
}

__global__ void resolve(const std::uint32_t* surface, const std::uint32_t* lines, int width,
                        int height, float epsilon, bool visibility, std::uint8_t* mask) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height)
        return;
    mask[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
        resolvePixel(surface, lines, x, y, width, height, epsilon, visibility);
}

// The same colour pass into a GL texture's array (GL_R8: one byte a texel, row y = mask row y).
__global__ void resolveToSurface(const std::uint32_t* surface, const std::uint32_t* lines,
                                 int width, int height, float epsilon, bool visibility,
                                 cudaSurfaceObject_t target) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height)
        return;
    const std::uint8_t value =
        resolvePixel(surface, lines, x, y, width, height, epsilon, visibility);
    surf2Dwrite(value, target, x * int(sizeof(std::uint8_t)), y);
}

} // namespace lw::kernels::cuda::zb
