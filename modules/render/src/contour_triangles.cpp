#include "lw/render/contour_triangles.h"

#include "lw/kernels/silhouette_segment.h"

#include <numeric>

namespace lw::render {

void appendContourTriangles(const Mesh& mesh, glm::vec4 viewer, Mesh& part) {
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* v = &mesh.indices[3 * t];
        const glm::vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
        const glm::vec3 n[3] = {mesh.normals[v[0]], mesh.normals[v[1]], mesh.normals[v[2]]};
        if (!kernels::mayHoldContour(p, n, viewer))
            continue;
        part.positions.insert(part.positions.end(), p, p + 3);
        part.normals.insert(part.normals.end(), n, n + 3);
    }
}

void numberCorners(Mesh& part) {
    part.indices.resize(part.positions.size());
    std::iota(part.indices.begin(), part.indices.end(), std::uint32_t(0));
}

Mesh contourTriangles(const Mesh& mesh, const Camera& camera) {
    Mesh part;
    appendContourTriangles(mesh, camera.viewerHomogeneous(), part);
    numberCorners(part);
    return part;
}

} // namespace lw::render
