#include "lw/render/surface_picking.h"

#include <cmath>
#include <limits>

namespace lw::render {

std::optional<glm::dvec3> pickFromDepthBuffer(const std::vector<float>& depth, const Camera& camera,
                                              glm::dvec2 pixel) {
    const int width = camera.width(), height = camera.height();
    if (depth.size() != std::size_t(width) * std::size_t(height))
        return std::nullopt;
    const double x = std::floor(pixel.x), y = std::floor(pixel.y);
    if (x < 0 || y < 0 || x >= width || y >= height)
        return std::nullopt;
    const float windowDepth = depth[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    if (!(windowDepth < 1.0f)) // the cleared value: no surface here
        return std::nullopt;
    return camera.unproject({x + 0.5, y + 0.5}, 2.0 * double(windowDepth) - 1.0);
}

namespace {

// Distance along the ray to the triangle (a, b, c), or a negative value for a miss.
double rayTriangleDistance(const Ray& ray, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    const glm::dvec3 edge1 = b - a, edge2 = c - a;
    const glm::dvec3 p = glm::cross(ray.direction, edge2);
    const double determinant = glm::dot(edge1, p);
    if (std::abs(determinant) < 1e-14)
        return -1.0; // parallel to the triangle's plane
    const double inverse = 1.0 / determinant;
    const glm::dvec3 s = ray.origin - a;
    const double u = glm::dot(s, p) * inverse;
    if (u < 0.0 || u > 1.0)
        return -1.0;
    const glm::dvec3 q = glm::cross(s, edge1);
    const double v = glm::dot(ray.direction, q) * inverse;
    if (v < 0.0 || u + v > 1.0)
        return -1.0;
    return glm::dot(edge2, q) * inverse;
}

} // namespace

std::optional<glm::dvec3> pickMeshSurface(const Mesh& mesh, const Camera& camera,
                                          glm::dvec2 pixel) {
    const Ray ray = camera.rayThroughPoint(pixel);
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        const double distance = rayTriangleDistance(ray, mesh.positions[mesh.indices[t]],
                                                    mesh.positions[mesh.indices[t + 1]],
                                                    mesh.positions[mesh.indices[t + 2]]);
        if (distance > 0.0 && distance < nearest)
            nearest = distance;
    }
    if (!std::isfinite(nearest))
        return std::nullopt;
    return ray.at(nearest);
}

} // namespace lw::render
