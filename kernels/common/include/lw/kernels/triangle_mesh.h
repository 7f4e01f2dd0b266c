#pragma once

// The one host mesh type of the engine: what marching cubes writes (CPU, whole volume or one
// brick; the CUDA back-end's download), what the renderers draw and the shaded panel shows
// (render::Mesh is this type). An indexed triangle mesh with shared vertices in patient
// coordinates (mm); the CUDA back-end's device meshes are views of the same three arrays
// (cuda::DeviceMeshView).

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace lw::kernels {

struct TriangleMesh {
    std::vector<glm::vec3> positions;
    // Unit, pointing outward (from value >= iso towards lower values).
    std::vector<glm::vec3> normals;
    // Three per triangle, counter-clockwise seen from outside.
    std::vector<std::uint32_t> indices;

    std::size_t triangleCount() const { return indices.size() / 3; }
    std::size_t vertexCount() const { return positions.size(); }
    bool isEmpty() const { return indices.empty(); }
};

// The host bytes of a mesh of `vertices` vertices (position and normal) and `triangles`
// triangles (three 32-bit indices): what marching cubes checks against its budget before it
// allocates. Saturates instead of wrapping.
constexpr std::uint64_t meshBytes(std::uint64_t vertices, std::uint64_t triangles) {
    constexpr std::uint64_t kPerVertex = 2 * sizeof(glm::vec3);
    constexpr std::uint64_t kPerTriangle = 3 * sizeof(std::uint32_t);
    constexpr std::uint64_t kMax = ~std::uint64_t(0);
    if (vertices > kMax / (2 * kPerVertex) || triangles > kMax / (2 * kPerTriangle))
        return kMax;
    return vertices * kPerVertex + triangles * kPerTriangle;
}

} // namespace lw::kernels
