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

// Method 1's pass-2 candidates: whether the geometry shader may emit a segment for a triangle
// (vertex positions p, normals n) seen from `viewer` -- the eye (w = 1) or the unit vector toward
// the viewer (w = 0). False only when all three d lie beyond a margin on one side: GLSL evaluates
// d in float too, perhaps with fused multiply-adds, and a relative margin of 1e-4 of
// |N| |eye - B| covers any such rounding, so the candidates are a superset of what it emits.
LW_HOST_DEVICE inline bool mayHoldContour(const glm::vec3 p[3], const glm::vec3 n[3],
                                          glm::vec4 viewer) {
    int front = 0, back = 0;
    for (int k = 0; k < 3; ++k) {
        const glm::vec3 toEye = glm::vec3(viewer) - p[k] * viewer.w;
        const float d = glm::dot(n[k], toEye);
        const float margin = 1e-4f * glm::length(n[k]) * glm::length(toEye) + 1e-30f;
        front += d > margin;
        back += d < -margin;
    }
    return front != 3 && back != 3;
}

// Where the per-vertex scalar `value` crosses zero inside a triangle: a vertex at 0 counts as
// positive, so neighbouring triangles agree on every edge. The lone vertex is the one whose
// side differs from the other two; the crossing runs over the two edges that touch it, named so
// that attributes can be interpolated at the endpoints: endpoint a lies on edge (lone, other1)
// at parameter ta, b on (lone, other2) at tb. Burns' silhouette (value = d) and the suggestive
// contours (value = kappa_r) both take it.
struct IsolineCrossing {
    int lone = 0, other1 = 1, other2 = 2;
    float ta = 0.0f, tb = 0.0f;
};

LW_HOST_DEVICE inline bool isolineCrossing(const float value[3], IsolineCrossing& out) {
    const bool s0 = value[0] >= 0.0f, s1 = value[1] >= 0.0f, s2 = value[2] >= 0.0f;
    if (s0 == s1 && s1 == s2)
        return false;
    out.lone = (s0 == s1) ? 2 : (s0 == s2 ? 1 : 0);
    out.other1 = (out.lone + 1) % 3;
    out.other2 = (out.lone + 2) % 3;
    out.ta = value[out.lone] / (value[out.lone] - value[out.other1]);
    out.tb = value[out.lone] / (value[out.lone] - value[out.other2]);
    return true;
}

// The zero of d on the edge (p0, p1) whose ends differ in sign, always interpolated from the
// end with d >= 0 toward the other: the two triangles that share the edge see it from
// different lone vertices, and this way both compute the same point bit for bit (neighbouring
// segments meet exactly, and method 2 on CUDA tests a shared endpoint's ray once).
LW_HOST_DEVICE inline glm::vec3 edgeZeroCrossing(glm::vec3 p0, float d0, glm::vec3 p1, float d1) {
    if (!(d0 >= 0.0f)) {
        const glm::vec3 p = p0;
        p0 = p1;
        p1 = p;
        const float d = d0;
        d0 = d1;
        d1 = d;
    }
    return p0 + (d0 / (d0 - d1)) * (p1 - p0);
}

// Returns true and the segment when the triangle (p[i], d[i]) holds a piece of the contour;
// `crossing` (optional) receives which edges its ends lie on.
LW_HOST_DEVICE inline bool silhouetteSegment(const glm::vec3 p[3], const float d[3],
                                             SegmentEndpoints& out,
                                             IsolineCrossing* crossing = nullptr) {
    IsolineCrossing c;
    if (!isolineCrossing(d, c))
        return false;
    out.a = edgeZeroCrossing(p[c.lone], d[c.lone], p[c.other1], d[c.other1]);
    out.b = edgeZeroCrossing(p[c.lone], d[c.lone], p[c.other2], d[c.other2]);
    if (crossing)
        *crossing = c;
    return true;
}

} // namespace lw::kernels
