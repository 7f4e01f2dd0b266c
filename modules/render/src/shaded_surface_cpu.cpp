#include "lw/render/shaded_surface_cpu.h"

#include "lw/core/parallel.h"
#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"
#include "view_transform.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lw::render {

core::ImageRgba8 shadeSurfaceCpu(const Mesh& mesh, const Camera& camera,
                                 const SurfaceShading& shading) {
    const int width = camera.width(), height = camera.height();
    core::ImageRgba8 image(width, height, shading.background);
    if (mesh.isEmpty() || width == 0 || height == 0)
        return image;
    const kernels::cpu::ViewTransform view = toViewTransform(camera);
    kernels::cpu::ScreenVertices screen;
    kernels::cpu::projectVertices(mesh.positions.data(), mesh.normals.data(), mesh.vertexCount(),
                                  view, screen, shading.threads);
    std::vector<std::uint64_t> nearest(std::size_t(width) * std::size_t(height), 0);
    kernels::cpu::drawTrianglesNearest(screen, mesh.indices.data(), mesh.triangleCount(), 0,
                                       nearest, width, height, shading.threads);

    const double scale = 1.0 / double(kernels::cpu::kSubpixelScale);
    auto channel = [](double base, double lit, double highlight) {
        return std::uint8_t(std::clamp(std::lround(base * lit + 255.0 * highlight), 0L, 255L));
    };
    core::parallelFor(
        std::size_t(height),
        [&](std::size_t row) {
            const int y = int(row);
            core::Rgba8* out = image.row(y);
            for (int x = 0; x < width; ++x) {
                const std::uint64_t packed =
                    nearest[std::size_t(y) * std::size_t(width) + std::size_t(x)];
                if (packed == 0)
                    continue;
                const std::uint32_t triangle = std::uint32_t(packed & 0xffffffffu) - 1;
                const std::uint32_t* tri = mesh.indices.data() + 3 * std::size_t(triangle);
                // Screen-space barycentrics at the pixel centre from the snapped vertices the
                // rasterizer used, then made perspective-correct with 1/w.
                const glm::dvec2 p(x + 0.5, y + 0.5);
                glm::dvec2 v[3];
                for (int i = 0; i < 3; ++i)
                    v[i] = glm::dvec2(screen.xy[tri[i]]) * scale;
                const double area =
                    (v[1].y - v[0].y) * (v[2].x - v[0].x) - (v[1].x - v[0].x) * (v[2].y - v[0].y);
                auto edge = [&](const glm::dvec2& a, const glm::dvec2& b) {
                    return (b.y - a.y) * (p.x - a.x) - (b.x - a.x) * (p.y - a.y);
                };
                double w[3] = {edge(v[1], v[2]) / area, edge(v[2], v[0]) / area,
                               edge(v[0], v[1]) / area};
                double sum = 0.0;
                for (int i = 0; i < 3; ++i) {
                    w[i] = std::max(w[i], 0.0) * double(screen.invW[tri[i]]);
                    sum += w[i];
                }
                if (!(sum > 0.0))
                    sum = 1.0, w[0] = 1.0, w[1] = w[2] = 0.0;
                glm::dvec3 normal(0.0), point(0.0);
                for (int i = 0; i < 3; ++i) {
                    normal += (w[i] / sum) * glm::dvec3(mesh.normals[tri[i]]);
                    point += (w[i] / sum) * glm::dvec3(mesh.positions[tri[i]]);
                }
                const double length = glm::length(normal);
                normal = length > 0.0 ? normal / length : glm::dvec3(0.0);
                // Headlight: light and eye coincide, so the half vector is the view vector.
                const glm::dvec3 toViewer = camera.toViewer(point);
                double facing = glm::dot(normal, toViewer);
                if (facing < 0.0)
                    facing = -facing; // two-sided: inner faces seen through a cut-open surface
                const double lit = shading.ambient + shading.diffuse * facing;
                const double highlight = shading.specular * std::pow(facing, shading.shininess);
                out[x] = {channel(shading.surface.r, lit, highlight),
                          channel(shading.surface.g, lit, highlight),
                          channel(shading.surface.b, lit, highlight), 255};
            }
        },
        shading.threads);
    return image;
}

} // namespace lw::render
