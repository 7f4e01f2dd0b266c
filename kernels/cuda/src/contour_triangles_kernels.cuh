#pragma once

// The contour triangles' kernels (dispatch in contour_triangles_cuda.cu).

#include "lw/kernels/silhouette_segment.h"

#include <cstdint>
#include <glm/glm.hpp>

namespace lw::kernels::cuda::contour {

// flags[t] = 1 where triangle t may hold the contour seen from `viewer`.
__global__ void flagTriangles(const glm::vec3* positions, const glm::vec3* normals,
                              const std::uint32_t* indices, std::uint32_t triangles,
                              glm::vec4 viewer, std::uint8_t* flags) {
    const std::uint32_t t = blockIdx.x * blockDim.x + threadIdx.x;
    if (t >= triangles)
        return;
    glm::vec3 p[3], n[3];
    for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = indices[3 * std::size_t(t) + k];
        p[k] = positions[v];
        n[k] = normals[v];
    }
    flags[t] = mayHoldContour(p, n, viewer) ? 1 : 0;
}

// Corner k of the i-th selected triangle into vertex 3 i + k of the output: one thread a corner.
__global__ void gatherCorners(const glm::vec3* positions, const glm::vec3* normals,
                              const std::uint32_t* indices, const std::uint32_t* selected,
                              const std::uint32_t* selectedCount, glm::vec3* outPositions,
                              glm::vec3* outNormals) {
    const std::uint32_t corner = blockIdx.x * blockDim.x + threadIdx.x;
    if (corner >= 3 * *selectedCount)
        return;
    const std::uint32_t t = selected[corner / 3];
    const std::uint32_t v = indices[3 * std::size_t(t) + corner % 3];
    outPositions[corner] = positions[v];
    outNormals[corner] = normals[v];
}

} // namespace lw::kernels::cuda::contour
