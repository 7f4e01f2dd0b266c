#pragma once

// Radial curvature of an iso-surface from the field's derivatives, for suggestive contours
// (DeCarlo et al. 2003; from volumes: Burns et al. 2005). Host+device, so a CUDA pass can
// follow the CPU one with the same rule.
//
// With the field f (inside = f >= iso), its gradient g (pointing inside) and Hessian H, the
// outward normal is n = -g / |g|. For a unit vector v from the surface point toward the viewer,
// w = v - (n.v) n is v projected onto the tangent plane, and the normal curvature in w's
// direction is
//     kappa_r = -(w^T H w) / (|g| |w|^2)        (convex > 0: a sphere of radius R gives 1/R)
// because the second fundamental form of {f = iso} is -H / |g| restricted to the tangent plane
// with this normal. Suggestive contours are where kappa_r = 0 and the derivative of kappa_r
// along w is positive (there n.v has a local minimum along w: an "almost contour").
//
// The Hessian of the voxel field is the derivative of the voxel gradient marching cubes uses
// (voxel_grid.h): central differences of the gradient at the neighbouring grid points over the
// same real distances (uneven gaps, one-sided at the faces), in the oblique frame (axisI, axisJ,
// stackAxis), then taken to patient coordinates with the normal matrix A = M^-T of that frame:
// H_patient = A H_frame A^T (a gantry tilt shears the frame; this undoes it).

#include "lw/kernels/host_device.h"
#include "lw/kernels/silhouette_segment.h" // isolineCrossing
#include "lw/kernels/voxel_grid.h"

#include <cmath>
#include <glm/glm.hpp>

namespace lw::kernels {

// A symmetric 3x3 matrix (a Hessian).
template <typename Real> struct Sym3T { Real xx = 0, yy = 0, zz = 0, xy = 0, xz = 0, yz = 0; };
using Sym3 = Sym3T<float>;

// The symmetric part of the matrix whose rows are row[0..2] (each with .x, .y, .z): a Hessian
// from differences of the gradient, whose mixed terms agree only up to the stencil's error.
template <typename Real, typename Row>
LW_HOST_DEVICE inline Sym3T<Real> symmetrised(const Row (&row)[3]) {
    Sym3T<Real> h;
    h.xx = row[0].x;
    h.yy = row[1].y;
    h.zz = row[2].z;
    h.xy = Real(0.5) * (row[0].y + row[1].x);
    h.xz = Real(0.5) * (row[0].z + row[2].x);
    h.yz = Real(0.5) * (row[1].z + row[2].y);
    return h;
}

template <typename Real>
LW_HOST_DEVICE inline Real quadraticForm(const Sym3T<Real>& h, glm::vec<3, Real> w) {
    return h.xx * w.x * w.x + h.yy * w.y * w.y + h.zz * w.z * w.z +
           Real(2) * (h.xy * w.x * w.y + h.xz * w.x * w.z + h.yz * w.y * w.z);
}

template <typename Real> struct RadialCurvatureT {
    Real kr = 0;            // radial curvature (1/mm, convex > 0); 0 where w or g vanishes
    Real nDotV = 0;         // cos of the angle between the outward normal and the view vector
    glm::vec<3, Real> w{0}; // unit direction of v projected onto the tangent plane (0: head-on)
};
using RadialCurvature = RadialCurvatureT<float>;

// kappa_r at `position` from the field's gradient and Hessian there (patient coordinates).
// `eyeOrDirection` is the eye (perspective) or the unit vector toward the viewer (orthographic),
// as for silhouetteDistance().
template <typename Real>
LW_HOST_DEVICE inline RadialCurvatureT<Real>
radialCurvature(glm::vec<3, Real> position, glm::vec<3, Real> gradient, const Sym3T<Real>& hessian,
                glm::vec<3, Real> eyeOrDirection, bool orthographic) {
    using V = glm::vec<3, Real>;
    RadialCurvatureT<Real> out;
    const Real g2 = glm::dot(gradient, gradient);
    V v = orthographic ? eyeOrDirection : eyeOrDirection - position;
    const Real v2 = glm::dot(v, v);
    if (!(g2 > Real(0)) || !(v2 > Real(0)))
        return out;
    const Real gLength = std::sqrt(g2);
    const V n = gradient * (Real(-1) / gLength);
    v = v * (Real(1) / std::sqrt(v2));
    out.nDotV = glm::dot(n, v);
    const V w = v - out.nDotV * n;
    const Real w2 = glm::dot(w, w);
    // Head-on (w -> 0) the direction of w, and with it kappa_r, is undefined.
    if (!(w2 > Real(1e-12)))
        return out;
    out.kr = -quadraticForm(hessian, w) / (gLength * w2);
    out.w = w * (Real(1) / std::sqrt(w2));
    return out;
}

// A = M^-T (row-major, McGridFrame::normalMatrix): H_patient = A H_frame A^T.
LW_HOST_DEVICE inline Sym3 hessianToPatient(const float a[9], const Sym3& h) {
    const float m[3][3] = {{h.xx, h.xy, h.xz}, {h.xy, h.yy, h.yz}, {h.xz, h.yz, h.zz}};
    float ah[3][3]; // A H
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            ah[r][c] = a[r * 3 + 0] * m[0][c] + a[r * 3 + 1] * m[1][c] + a[r * 3 + 2] * m[2][c];
    const auto entry = [&](int r, int c) {
        return ah[r][0] * a[c * 3 + 0] + ah[r][1] * a[c * 3 + 1] + ah[r][2] * a[c * 3 + 2];
    };
    Sym3 out;
    out.xx = entry(0, 0);
    out.yy = entry(1, 1);
    out.zz = entry(2, 2);
    out.xy = entry(0, 1);
    out.xz = entry(0, 2);
    out.yz = entry(1, 2);
    return out;
}

namespace detail {
LW_HOST_DEVICE inline McVec3 gradientDifference(const McVec3& lo, const McVec3& hi, float span) {
    return {mcDerivative(lo.x, hi.x, span), mcDerivative(lo.y, hi.y, span),
            mcDerivative(lo.z, hi.z, span)};
}
} // namespace detail

// Hessian of the voxel field at grid point (x, y, z) in the oblique frame, per mm^2: each row
// the derivative of sampler.gradient() along one axis, central inside and one-sided at the
// faces like the gradient itself, symmetrised (the two mixed differences agree only up to the
// stencil's error).
template <typename T>
LW_HOST_DEVICE inline Sym3 frameHessian(const VoxelGradientSampler<T>& sampler, int x, int y,
                                        int z) {
    const GridSpans& s = sampler.spans;
    const GridDims& d = s.dims;
    McVec3 row[3];
    {
        const int lo = x > 0 ? x - 1 : x, hi = x < d.cx ? x + 1 : x;
        const float span = (hi - lo) == 2 ? s.spanI : ((hi - lo) == 1 ? s.edgeSpanI : 0.0f);
        row[0] = detail::gradientDifference(sampler.gradient(lo, y, z), sampler.gradient(hi, y, z),
                                            span);
    }
    {
        const int lo = y > 0 ? y - 1 : y, hi = y < d.cy ? y + 1 : y;
        const float span = (hi - lo) == 2 ? s.spanJ : ((hi - lo) == 1 ? s.edgeSpanJ : 0.0f);
        row[1] = detail::gradientDifference(sampler.gradient(x, lo, z), sampler.gradient(x, hi, z),
                                            span);
    }
    {
        // spanK[z] is already the distance between the neighbours used (one gap at the ends).
        const int lo = z > 0 ? z - 1 : z, hi = z < d.cz ? z + 1 : z;
        row[2] = detail::gradientDifference(sampler.gradient(x, y, lo), sampler.gradient(x, y, hi),
                                            s.spanK[std::size_t(z)]);
    }
    return symmetrised<float>(row);
}

} // namespace lw::kernels
