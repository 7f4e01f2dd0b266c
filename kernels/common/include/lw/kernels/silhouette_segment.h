#pragma once

// The silhouette segment of one triangle (Burns et al. 2005), shared by the CPU and CUDA
// back-ends of methods 2 and 3 (method 1 does the same in its geometry shader).
//
// At each vertex B with normal N, d = N . (eye - B) for a perspective camera, or d = N . toViewer
// for an orthographic one (toViewer = -forward, the same for every vertex). The contour passes
// where d = 0: on each edge whose end values differ in sign, at t = d_a / (d_a - d_b). A vertex
// with d == 0 counts as front-facing (d >= 0) so that every edge is classified the same way by
// both triangles that share it, and neighbouring segments meet end to end.

#include "lw/kernels/host_device.h"

#include <glm/glm.hpp>

namespace lw::kernels {

struct SegmentEndpoints {
    glm::vec3 a;
    glm::vec3 b;
};

// d at a vertex; `eyeOrDirection` is the eye position (perspective) or the unit vector toward the
// viewer (orthographic).
LW_HOST_DEVICE inline float silhouetteDistance(glm::vec3 position, glm::vec3 normal,
                                               glm::vec3 eyeOrDirection, bool orthographic) {
    const glm::vec3 toEye = orthographic ? eyeOrDirection : eyeOrDirection - position;
    return glm::dot(normal, toEye);
}

// Returns true and the segment when the triangle (p[i], d[i]) holds a piece of the contour.
LW_HOST_DEVICE inline bool silhouetteSegment(const glm::vec3 p[3], const float d[3],
                                             SegmentEndpoints& out) {
    const bool front0 = d[0] >= 0.0f, front1 = d[1] >= 0.0f, front2 = d[2] >= 0.0f;
    if (front0 == front1 && front1 == front2)
        return false;
    // The lone vertex is the one whose side differs from the other two; the contour crosses
    // the two edges that touch it.
    const int lone = (front0 == front1) ? 2 : (front0 == front2 ? 1 : 0);
    const int other1 = (lone + 1) % 3, other2 = (lone + 2) % 3;
    const float t1 = d[lone] / (d[lone] - d[other1]);
    const float t2 = d[lone] / (d[lone] - d[other2]);
    out.a = p[lone] + t1 * (p[other1] - p[lone]);
    out.b = p[lone] + t2 * (p[other2] - p[lone]);
    return true;
}

} // namespace lw::kernels
