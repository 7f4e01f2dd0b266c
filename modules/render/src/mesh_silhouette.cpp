#include "mesh_silhouette.h"

namespace lw::render {

void appendMeshSilhouette(const Mesh& mesh, glm::vec3 eyeOrDirection, bool orthographic,
                          std::vector<kernels::SegmentEndpoints>& out) {
    std::vector<float> distance(mesh.vertexCount());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        distance[v] = kernels::silhouetteDistance(mesh.positions[v], mesh.normals[v],
                                                  eyeOrDirection, orthographic);
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* v = &mesh.indices[3 * t];
        const glm::vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
        const float d[3] = {distance[v[0]], distance[v[1]], distance[v[2]]};
        kernels::SegmentEndpoints ends;
        if (kernels::silhouetteSegment(p, d, ends))
            out.push_back(ends);
    }
}

} // namespace lw::render
