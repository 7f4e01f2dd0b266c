#include "lw/render/shaded_surface_cpu.h"

#include "lw/core/parallel.h"
#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"
#include "view_transform.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace lw::render {

namespace {

core::Rgba8 toRgba8(glm::vec3 colour) {
    auto channel = [](float c) {
        return std::uint8_t(std::clamp(std::lround(c * 255.0f), 0L, 255L));
    };
    return {channel(colour.r), channel(colour.g), channel(colour.b), 255};
}

// One lit pixel: headlight (two-sided, as before) or Blinn-Phong with a light, as surface.frag.
core::Rgba8 shadePixel(glm::dvec3 normal, glm::dvec3 toViewer, const SurfaceShading& shading) {
    auto channel = [](double base, double lit, double highlight) {
        return std::uint8_t(std::clamp(std::lround(base * lit + 255.0 * highlight), 0L, 255L));
    };
    core::Rgba8 base = shading.surface;
    double facing = glm::dot(normal, toViewer);
    if (facing < 0.0) { // inner faces seen through a cut-open surface
        normal = -normal;
        facing = -facing;
        base = shading.backSurface.value_or(shading.surface);
    }
    double lit = 0.0, highlight = 0.0;
    if (shading.lightDirection == glm::dvec3(0.0)) {
        // Headlight: light and eye coincide, so the half vector is the view vector.
        lit = shading.ambient + shading.diffuse * facing;
        highlight = shading.specular * std::pow(facing, shading.shininess);
    } else {
        const double diffuse = std::max(glm::dot(normal, shading.lightDirection), 0.0);
        const glm::dvec3 half = glm::normalize(shading.lightDirection + toViewer);
        lit = shading.ambient + shading.diffuse * diffuse;
        highlight = diffuse > 0.0
                        ? shading.specular *
                              std::pow(std::max(glm::dot(normal, half), 0.0), shading.shininess)
                        : 0.0;
    }
    return {channel(base.r, lit, highlight), channel(base.g, lit, highlight),
            channel(base.b, lit, highlight), 255};
}

} // namespace

SurfaceShading glPanelShading(const Camera& camera, const SilhouetteGlOptions& options) {
    SurfaceShading shading;
    shading.background = toRgba8(glm::vec3(options.background));
    shading.surface = toRgba8(options.frontColour);
    shading.backSurface = toRgba8(options.backColour);
    shading.ambient = options.material.x;
    shading.diffuse = options.material.y;
    shading.specular = options.material.z;
    shading.shininess = options.material.w;
    shading.lightDirection = camera.panelLightDirection(); // the GL renderer's light
    return shading;
}

core::ImageRgba8 shadeSurfaceCpu(const Mesh& mesh, const Camera& camera,
                                 const SurfaceShading& shading, std::vector<float>* depth) {
    const int width = camera.width(), height = camera.height();
    core::ImageRgba8 image(width, height, shading.background);
    if (depth)
        depth->assign(std::size_t(width) * std::size_t(height), 1.0f);
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
                out[x] = shadePixel(normal, camera.toViewer(point), shading);
                if (depth)
                    (*depth)[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
                        float(0.5 * (camera.project(point).ndcDepth + 1.0));
            }
        },
        shading.threads);
    return image;
}

} // namespace lw::render
