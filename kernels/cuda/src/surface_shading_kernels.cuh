#pragma once

// The shaded iso panel's kernels (dispatch in surface_shading_cuda.cu). Coverage, snapping and
// the depth key are zbuffer_rules.h's, as on the CPU (render/shaded_surface_cpu.cpp, whose
// lighting these kernels repeat in double precision).

#include "lw/kernels/cuda/surface_shading_cuda.h"
#include "lw/kernels/zbuffer_rules.h"

#include <cstdint>

namespace lw::kernels::cuda::shade {

struct ScreenPoint {
    glm::ivec2 xy; // fixed point, kInvalidVertex when not projected
    float key;
    float invW;
};

// One mesh of the frame as the kernels read it; its triangles are numbered from `first`.
struct MeshSlot {
    const glm::vec3* positions = nullptr;
    const glm::vec3* normals = nullptr;
    const std::uint32_t* indices = nullptr;
    const ScreenPoint* screen = nullptr;
    std::uint32_t first = 0;
};

struct Slots {
    MeshSlot mesh[SurfaceShadingCuda::kMaxMeshes];
    int count = 0;
};

__global__ void projectVertices(const glm::vec3* positions, std::uint32_t count,
                                ScreenProjection view, ScreenPoint* out) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count)
        return;
    const glm::vec3 p = positions[i];
    double px = 0.0, py = 0.0;
    float key = 0.0f, invW = 0.0f;
    const bool ok = projectToScreen(view, double(p.x), double(p.y), double(p.z), px, py, key, invW);
    out[i] = ScreenPoint{snapVertex(ok, px, py), key, invW};
}

// Every covered pixel centre keeps the nearest triangle: (key bits << 32) | (number + 1), by
// atomicMax (keys of points in front of the eye are positive floats, which order as their bits).
__global__ void drawNearest(MeshSlot mesh, std::uint32_t triangleCount, int width, int height,
                            unsigned long long* nearest) {
    const std::uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
    if (t >= triangleCount)
        return;
    const std::uint32_t* tri = mesh.indices + 3 * std::size_t(t);
    const ScreenPoint a = mesh.screen[tri[0]], b = mesh.screen[tri[1]], c = mesh.screen[tri[2]];
    const unsigned long long id = (unsigned long long)(mesh.first) + t + 1ull;
    forEachCoveredPixel(
        a.xy, b.xy, c.xy, a.key, b.key, c.key, width, height, [&](int x, int y, float key) {
            if (!(key > 0.0f))
                return; // outside the near/far range
            const unsigned long long packed = ((unsigned long long)(keyBits(key)) << 32) | id;
            atomicMax(nearest + std::size_t(y) * std::size_t(width) + std::size_t(x), packed);
        });
}

__device__ inline std::uint8_t channel(double base, double lit, double highlight) {
    const long long v = llround(base * lit + 255.0 * highlight);
    return std::uint8_t(v < 0 ? 0 : (v > 255 ? 255 : v));
}

__device__ inline glm::dvec3 unit(glm::dvec3 v) {
    const double length = sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    return length > 0.0 ? v / length : glm::dvec3(0.0);
}

__device__ inline double dot3(glm::dvec3 a, glm::dvec3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

// One lit pixel, as shadePixel in render/shaded_surface_cpu.cpp.
__device__ inline uchar4 lightPixel(glm::dvec3 normal, glm::dvec3 toViewer,
                                    const SurfaceLighting& light) {
    glm::dvec3 base = light.front;
    double facing = dot3(normal, toViewer);
    if (facing < 0.0) { // inner faces seen through a cut-open surface
        normal = -normal;
        facing = -facing;
        base = light.back;
    }
    double lit = 0.0, highlight = 0.0;
    if (light.lightDirection == glm::dvec3(0.0)) {
        lit = light.ambient + light.diffuse * facing;
        highlight = light.specular * pow(facing, light.shininess);
    } else {
        const double diffuse = fmax(dot3(normal, light.lightDirection), 0.0);
        const glm::dvec3 half = unit(light.lightDirection + toViewer);
        lit = light.ambient + light.diffuse * diffuse;
        highlight = diffuse > 0.0
                        ? light.specular * pow(fmax(dot3(normal, half), 0.0), light.shininess)
                        : 0.0;
    }
    return make_uchar4(channel(base.x, lit, highlight), channel(base.y, lit, highlight),
                       channel(base.z, lit, highlight), 255);
}

struct ShadeView {
    ScreenProjection projection;
    bool orthographic;
    glm::dvec3 eye, toViewer;
};

// The pixel's triangle, its perspective-correct barycentric weights at the pixel centre (from
// the snapped vertices the rasterizer used), the interpolated normal and point, lit; the depth
// from the point, as a GL depth buffer holds it.
__global__ void shadePixels(const unsigned long long* nearest, Slots slots, ShadeView view,
                            SurfaceLighting light, uchar4* rgba, float* depth) {
    const int width = view.projection.width, height = view.projection.height;
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x >= width || y >= height)
        return;
    const std::size_t pixel = std::size_t(y) * std::size_t(width) + std::size_t(x);
    const unsigned long long packed = nearest[pixel];
    if (packed == 0) {
        rgba[pixel] = make_uchar4(channel(light.background.x, 1.0, 0.0),
                                  channel(light.background.y, 1.0, 0.0),
                                  channel(light.background.z, 1.0, 0.0), 255);
        depth[pixel] = 1.0f;
        return;
    }
    const std::uint32_t number = std::uint32_t(packed & 0xffffffffull) - 1u;
    const MeshSlot& mesh =
        slots.count > 1 && number >= slots.mesh[1].first ? slots.mesh[1] : slots.mesh[0];
    const std::uint32_t* tri = mesh.indices + 3 * std::size_t(number - mesh.first);
    const double scale = 1.0 / double(kSubpixelScale);
    const double px = x + 0.5, py = y + 0.5;
    glm::dvec2 v[3];
    for (int i = 0; i < 3; ++i)
        v[i] = glm::dvec2(double(mesh.screen[tri[i]].xy.x) * scale,
                          double(mesh.screen[tri[i]].xy.y) * scale);
    const double area =
        (v[1].y - v[0].y) * (v[2].x - v[0].x) - (v[1].x - v[0].x) * (v[2].y - v[0].y);
    auto edge = [&](const glm::dvec2& a, const glm::dvec2& b) {
        return (b.y - a.y) * (px - a.x) - (b.x - a.x) * (py - a.y);
    };
    double w[3] = {edge(v[1], v[2]) / area, edge(v[2], v[0]) / area, edge(v[0], v[1]) / area};
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
        w[i] = fmax(w[i], 0.0) * double(mesh.screen[tri[i]].invW);
        sum += w[i];
    }
    if (!(sum > 0.0)) {
        sum = 1.0;
        w[0] = 1.0;
        w[1] = w[2] = 0.0;
    }
    glm::dvec3 normal(0.0), point(0.0);
    for (int i = 0; i < 3; ++i) {
        normal += (w[i] / sum) * glm::dvec3(mesh.normals[tri[i]]);
        point += (w[i] / sum) * glm::dvec3(mesh.positions[tri[i]]);
    }
    normal = unit(normal);
    const glm::dvec3 toViewer = view.orthographic ? view.toViewer : unit(view.eye - point);
    rgba[pixel] = lightPixel(normal, toViewer, light);
    const double(*m)[4] = view.projection.m;
    const double cw = m[0][3] * point.x + m[1][3] * point.y + m[2][3] * point.z + m[3][3];
    const double cz = m[0][2] * point.x + m[1][2] * point.y + m[2][2] * point.z + m[3][2];
    depth[pixel] = float(0.5 * (cz / cw + 1.0));
}

} // namespace lw::kernels::cuda::shade
