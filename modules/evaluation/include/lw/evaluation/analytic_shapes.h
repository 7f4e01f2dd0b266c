#pragma once

#include "lw/render/aabb.h"
#include "lw/volume/volume.h"

#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace lw::evaluation {

// Every shape is inside where value(p) >= kShapeIso. The values are in mm and, except for the
// metaballs, are signed distances or distance-like (lipschitz() <= 1), so marching cubes on a
// sampled grid interpolates them well and ray casting can step by |value| / lipschitz().
inline constexpr double kShapeIso = 0.0;

// An implicit solid for accuracy tests: exact value, analytic gradient (pointing inward, i.e.
// toward larger values; the outward normal is -gradient / |gradient|), and a box enclosing the
// surface {value = kShapeIso}.
class AnalyticShape {
public:
    virtual ~AnalyticShape() = default;
    virtual std::string name() const = 0;
    virtual double value(glm::dvec3 p) const = 0;
    virtual glm::dvec3 gradient(glm::dvec3 p) const = 0;
    virtual render::Aabb bounds() const = 0;
    // Upper bound of |gradient| over space: outside, the surface is at least -value / lipschitz()
    // away.
    virtual double lipschitz() const = 0;
};

// R - |p - c|.
class SphereShape final : public AnalyticShape {
public:
    explicit SphereShape(glm::dvec3 center = {0, 0, 0}, double radius = 40.0);
    std::string name() const override { return "sphere"; }
    double value(glm::dvec3 p) const override;
    glm::dvec3 gradient(glm::dvec3 p) const override;
    render::Aabb bounds() const override;
    double lipschitz() const override { return 1.0; }

private:
    glm::dvec3 m_center;
    double m_radius;
};

// Tube radius r around a ring of radius R: r - |(|q_xy| - R, q_z)| in the torus frame, where q is
// p relative to the centre in the basis (axisU, axisV, axis).
class TorusShape final : public AnalyticShape {
public:
    TorusShape(glm::dvec3 center = {0, 0, 0}, glm::dvec3 axis = {0, 0, 1}, double ringRadius = 40.0,
               double tubeRadius = 14.0);
    std::string name() const override { return "torus"; }
    double value(glm::dvec3 p) const override;
    glm::dvec3 gradient(glm::dvec3 p) const override;
    render::Aabb bounds() const override;
    double lipschitz() const override { return 1.0; }

private:
    glm::dvec3 m_center;
    glm::dvec3 m_axisU, m_axisV, m_axis;
    double m_ringRadius;
    double m_tubeRadius;
};

// Two linked rings (like chain links): one in the xy-plane at the origin, the other in the
// xz-plane centred on the first one's ring. The tubes never touch (their core circles are at
// least ringRadius apart), so the union max(f1, f2) is smooth near the surface.
class LinkedToriShape final : public AnalyticShape {
public:
    explicit LinkedToriShape(double ringRadius = 30.0, double tubeRadius = 9.0);
    std::string name() const override { return "tori"; }
    double value(glm::dvec3 p) const override;
    glm::dvec3 gradient(glm::dvec3 p) const override;
    render::Aabb bounds() const override;
    double lipschitz() const override { return 1.0; }

private:
    TorusShape m_first;
    TorusShape m_second;
};

// A superellipsoid with half axes (a, b, c) and shape exponents e1 (north-south) and e2
// (east-west), both in (0, 1] so the solid is convex (1 = ellipsoid, small = rounded box):
//   G(p) = ((|x/a|^(2/e2) + |y/b|^(2/e2))^(e2/e1) + |z/c|^(2/e1))^(e1/2),
//   value = m (1 - G),  m = min(a, b, c).
// G is a norm (homogeneous of degree 1), so value is linear along rays from the centre and
// m |grad G| <= 1: distance-like without being a distance.
class SuperquadricShape final : public AnalyticShape {
public:
    SuperquadricShape(glm::dvec3 center = {0, 0, 0}, glm::dvec3 halfAxes = {40.0, 32.0, 26.0},
                      double e1 = 0.45, double e2 = 0.6);
    std::string name() const override { return "superquadric"; }
    double value(glm::dvec3 p) const override;
    glm::dvec3 gradient(glm::dvec3 p) const override;
    render::Aabb bounds() const override;
    double lipschitz() const override { return 1.0; }

private:
    glm::dvec3 m_center;
    glm::dvec3 m_halfAxes;
    double m_e1;
    double m_e2;
    double m_scale;
};

struct Metaball {
    glm::dvec3 center{0.0};
    double weight = 1.0; // > 0
    double width = 10.0; // Gaussian width s in exp(-|p - c|^2 / s^2), mm
};

// Blobby union: value = scale * (sum_i w_i exp(-|p - c_i|^2 / s_i^2) - threshold), scaled so the
// Lipschitz bound sum_i w_i sqrt(2/e) / s_i becomes 1. Where blobs merge the surface has saddles,
// so some views show interior occluding contours.
class MetaballsShape final : public AnalyticShape {
public:
    MetaballsShape(); // five blobs of different sizes, asymmetric so no view is degenerate
    MetaballsShape(std::vector<Metaball> balls, double threshold);
    std::string name() const override { return "metaballs"; }
    double value(glm::dvec3 p) const override;
    glm::dvec3 gradient(glm::dvec3 p) const override;
    render::Aabb bounds() const override { return m_bounds; }
    double lipschitz() const override { return 1.0; }

private:
    render::Aabb computeBounds() const;

    std::vector<Metaball> m_balls;
    double m_threshold;
    double m_scale;
    render::Aabb m_bounds;
};

// "sphere", "torus", "tori", "superquadric", "metaballs" (the paper's Table 5 set).
std::vector<std::string> analyticShapeNames();
// Throws core::Error for an unknown name.
std::unique_ptr<AnalyticShape> makeAnalyticShape(std::string_view name);

// Samples value() at the voxel centres of an n x n x n float32 volume with isotropic spacing
// covering the shape's bounding box (centred) with a margin of at least 2 voxels and 5% on every
// side, so the surface is closed inside the grid. Extract the surface at kShapeIso. n >= 8.
volume::Volume sampleShape(const AnalyticShape& shape, int n);

} // namespace lw::evaluation
