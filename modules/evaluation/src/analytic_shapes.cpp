#include "lw/evaluation/analytic_shapes.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lw::evaluation {

using render::Aabb;

namespace {

// Any unit vector not parallel to `axis`, made orthogonal to it.
glm::dvec3 perpendicularTo(glm::dvec3 axis) {
    const glm::dvec3 helper = std::abs(axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    return glm::normalize(glm::cross(axis, helper));
}

double signOf(double v) {
    return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0);
}

} // namespace

// ---- sphere ----------------------------------------------------------------------------------

SphereShape::SphereShape(glm::dvec3 center, double radius) : m_center(center), m_radius(radius) {
    if (!(radius > 0.0))
        throw core::Error("sphere shape", "radius must be positive");
}

double SphereShape::value(glm::dvec3 p) const {
    return m_radius - glm::length(p - m_center);
}

glm::dvec3 SphereShape::gradient(glm::dvec3 p) const {
    const glm::dvec3 d = p - m_center;
    const double length = glm::length(d);
    return length > 0.0 ? -d / length : glm::dvec3(0.0);
}

Aabb SphereShape::bounds() const {
    return {m_center - m_radius, m_center + m_radius};
}

// ---- torus -----------------------------------------------------------------------------------

TorusShape::TorusShape(glm::dvec3 center, glm::dvec3 axis, double ringRadius, double tubeRadius)
    : m_center(center), m_ringRadius(ringRadius), m_tubeRadius(tubeRadius) {
    if (!(tubeRadius > 0.0) || !(ringRadius > tubeRadius))
        throw core::Error("torus shape", "needs 0 < tube radius < ring radius");
    if (!(glm::length(axis) > 0.0))
        throw core::Error("torus shape", "axis must not be zero");
    m_axis = glm::normalize(axis);
    m_axisU = perpendicularTo(m_axis);
    m_axisV = glm::cross(m_axis, m_axisU);
}

double TorusShape::value(glm::dvec3 p) const {
    const glm::dvec3 q = p - m_center;
    const double x = glm::dot(q, m_axisU), y = glm::dot(q, m_axisV), z = glm::dot(q, m_axis);
    const double rho = std::sqrt(x * x + y * y);
    return m_tubeRadius - std::sqrt((rho - m_ringRadius) * (rho - m_ringRadius) + z * z);
}

glm::dvec3 TorusShape::gradient(glm::dvec3 p) const {
    const glm::dvec3 q = p - m_center;
    const double x = glm::dot(q, m_axisU), y = glm::dot(q, m_axisV), z = glm::dot(q, m_axis);
    const double rho = std::sqrt(x * x + y * y);
    const double d = std::sqrt((rho - m_ringRadius) * (rho - m_ringRadius) + z * z);
    if (d == 0.0 || rho == 0.0)
        return glm::dvec3(0.0); // on the core circle or the axis: no unique direction
    const glm::dvec3 radial = (x / rho) * m_axisU + (y / rho) * m_axisV;
    return -((rho - m_ringRadius) / d * radial + (z / d) * m_axis);
}

Aabb TorusShape::bounds() const {
    // Extent of the ring (radius R in the plane) per world axis, plus the tube in every direction.
    glm::dvec3 half;
    for (int i = 0; i < 3; ++i)
        half[i] =
            m_ringRadius * std::sqrt(std::max(0.0, 1.0 - m_axis[i] * m_axis[i])) + m_tubeRadius;
    return {m_center - half, m_center + half};
}

// ---- two linked tori -------------------------------------------------------------------------

LinkedToriShape::LinkedToriShape(double ringRadius, double tubeRadius)
    : m_first({0, 0, 0}, {0, 0, 1}, ringRadius, tubeRadius),
      m_second({ringRadius, 0, 0}, {0, 1, 0}, ringRadius, tubeRadius) {
    if (!(tubeRadius < 0.5 * ringRadius))
        throw core::Error(
            "linked tori shape",
            "tube radius must be below half the ring radius so the rings do not touch");
}

double LinkedToriShape::value(glm::dvec3 p) const {
    return std::max(m_first.value(p), m_second.value(p));
}

glm::dvec3 LinkedToriShape::gradient(glm::dvec3 p) const {
    return m_first.value(p) >= m_second.value(p) ? m_first.gradient(p) : m_second.gradient(p);
}

Aabb LinkedToriShape::bounds() const {
    return Aabb::unite(m_first.bounds(), m_second.bounds());
}

// ---- superquadric ----------------------------------------------------------------------------

SuperquadricShape::SuperquadricShape(glm::dvec3 center, glm::dvec3 halfAxes, double e1, double e2)
    : m_center(center), m_halfAxes(halfAxes), m_e1(e1), m_e2(e2) {
    if (!(halfAxes.x > 0.0 && halfAxes.y > 0.0 && halfAxes.z > 0.0))
        throw core::Error("superquadric shape", "half axes must be positive");
    if (!(e1 > 0.0 && e1 <= 1.0 && e2 > 0.0 && e2 <= 1.0))
        throw core::Error("superquadric shape",
                          "exponents must lie in (0, 1] (convex shapes only)");
    m_scale = std::min({halfAxes.x, halfAxes.y, halfAxes.z});
}

double SuperquadricShape::value(glm::dvec3 p) const {
    const glm::dvec3 q = glm::abs(p - m_center) / m_halfAxes;
    const double u = std::pow(q.x, 2.0 / m_e2) + std::pow(q.y, 2.0 / m_e2);
    const double w = std::pow(u, m_e2 / m_e1) + std::pow(q.z, 2.0 / m_e1);
    return m_scale * (1.0 - std::pow(w, 0.5 * m_e1));
}

glm::dvec3 SuperquadricShape::gradient(glm::dvec3 p) const {
    const glm::dvec3 d = p - m_center;
    const glm::dvec3 q = glm::abs(d) / m_halfAxes;
    const double u = std::pow(q.x, 2.0 / m_e2) + std::pow(q.y, 2.0 / m_e2);
    const double w = std::pow(u, m_e2 / m_e1) + std::pow(q.z, 2.0 / m_e1);
    if (w <= 0.0)
        return glm::dvec3(0.0); // the centre: G has no gradient there
    // Chain rule through G = w^(e1/2), w = u^(e2/e1) + Z^(2/e1), u = X^(2/e2) + Y^(2/e2); the
    // exponent factors cancel to the form below.
    const double outer = std::pow(w, 0.5 * m_e1 - 1.0);
    const double inner = u > 0.0 ? std::pow(u, m_e2 / m_e1 - 1.0) : 0.0;
    glm::dvec3 gradG;
    gradG.x = outer * inner * std::pow(q.x, 2.0 / m_e2 - 1.0) * signOf(d.x) / m_halfAxes.x;
    gradG.y = outer * inner * std::pow(q.y, 2.0 / m_e2 - 1.0) * signOf(d.y) / m_halfAxes.y;
    gradG.z = outer * std::pow(q.z, 2.0 / m_e1 - 1.0) * signOf(d.z) / m_halfAxes.z;
    return -m_scale * gradG;
}

Aabb SuperquadricShape::bounds() const {
    return {m_center - m_halfAxes, m_center + m_halfAxes};
}

// ---- metaballs -------------------------------------------------------------------------------

MetaballsShape::MetaballsShape()
    : MetaballsShape({{{0, 0, 0}, 1.0, 18.0},
                      {{26, 4, 6}, 0.8, 13.0},
                      {{-20, 10, -12}, 0.9, 14.0},
                      {{4, -8, 24}, 0.7, 11.0},
                      {{-6, 22, 16}, 0.6, 10.0}},
                     0.35) {}

MetaballsShape::MetaballsShape(std::vector<Metaball> balls, double threshold)
    : m_balls(std::move(balls)), m_threshold(threshold) {
    if (m_balls.empty() || !(threshold > 0.0))
        throw core::Error("metaballs shape", "needs at least one ball and a positive threshold");
    double lipschitzRaw = 0.0;
    for (const auto& ball : m_balls) {
        if (!(ball.weight > 0.0 && ball.width > 0.0))
            throw core::Error("metaballs shape", "weights and widths must be positive");
        // max |grad w exp(-r^2/s^2)| = w sqrt(2/e) / s, reached at r = s / sqrt(2).
        lipschitzRaw += ball.weight * std::sqrt(2.0 / std::numbers::e) / ball.width;
    }
    m_scale = 1.0 / lipschitzRaw;
    m_bounds = computeBounds();
}

double MetaballsShape::value(glm::dvec3 p) const {
    double sum = 0.0;
    for (const auto& ball : m_balls) {
        const glm::dvec3 d = p - ball.center;
        sum += ball.weight * std::exp(-glm::dot(d, d) / (ball.width * ball.width));
    }
    return m_scale * (sum - m_threshold);
}

glm::dvec3 MetaballsShape::gradient(glm::dvec3 p) const {
    glm::dvec3 g(0.0);
    for (const auto& ball : m_balls) {
        const glm::dvec3 d = p - ball.center;
        const double s2 = ball.width * ball.width;
        g += ball.weight * std::exp(-glm::dot(d, d) / s2) * (-2.0 / s2) * d;
    }
    return m_scale * g;
}

Aabb MetaballsShape::computeBounds() const {
    // value > 0 needs some ball with w exp(-d^2/s^2) > threshold / count: a conservative box, which
    // a Lipschitz-safe grid search then tightens (an inside point is within h*sqrt(3)/2 of a grid
    // point whose value is >= -h*sqrt(3)/2, since |grad value| <= 1).
    const double count = double(m_balls.size());
    bool any = false;
    Aabb loose;
    for (const auto& ball : m_balls) {
        const double ratio = count * ball.weight / m_threshold;
        if (ratio <= 1.0)
            continue;
        const double reach = ball.width * std::sqrt(std::log(ratio));
        const Aabb box{ball.center - reach, ball.center + reach};
        loose = any ? Aabb::unite(loose, box) : box;
        any = true;
    }
    if (!any)
        throw core::Error("metaballs shape", "threshold too high: the shape is empty");
    constexpr int kSteps = 96;
    const glm::dvec3 size = loose.size();
    const double h = std::max({size.x, size.y, size.z}) / kSteps;
    const double reachOfSample = h * std::sqrt(3.0) / 2.0;
    bool found = false;
    Aabb tight;
    for (double z = loose.min.z; z <= loose.max.z + h; z += h)
        for (double y = loose.min.y; y <= loose.max.y + h; y += h)
            for (double x = loose.min.x; x <= loose.max.x + h; x += h) {
                const glm::dvec3 p{x, y, z};
                if (value(p) < -reachOfSample)
                    continue;
                tight = found ? Aabb::unite(tight, Aabb::around(p)) : Aabb::around(p);
                found = true;
            }
    if (!found)
        throw core::Error("metaballs shape", "the shape is empty");
    return {glm::max(tight.min - reachOfSample, loose.min),
            glm::min(tight.max + reachOfSample, loose.max)};
}

// ---- registry and sampling -------------------------------------------------------------------

std::vector<std::string> analyticShapeNames() {
    return {"sphere", "torus", "tori", "superquadric", "metaballs"};
}

std::unique_ptr<AnalyticShape> makeAnalyticShape(std::string_view name) {
    if (name == "sphere")
        return std::make_unique<SphereShape>();
    if (name == "torus")
        return std::make_unique<TorusShape>();
    if (name == "tori")
        return std::make_unique<LinkedToriShape>();
    if (name == "superquadric")
        return std::make_unique<SuperquadricShape>();
    if (name == "metaballs")
        return std::make_unique<MetaballsShape>();
    throw core::Error(std::string(name),
                      "unknown analytic shape (sphere, torus, tori, superquadric, metaballs)");
}

volume::Volume sampleShape(const AnalyticShape& shape, int n) {
    if (n < 8)
        throw core::Error("analytic shape " + shape.name(),
                          "sampling needs at least 8 voxels per axis");
    const Aabb box = shape.bounds();
    const glm::dvec3 size = box.size();
    const double extent = std::max({size.x, size.y, size.z});
    // Isotropic spacing; at least 5% and 2 voxels of outside on each side so the surface closes.
    const double spacing = std::max(extent * 1.1 / (n - 1), extent / (n - 5));
    const glm::dvec3 origin = box.center() - 0.5 * spacing * (n - 1);
    volume::Volume out({n, n, n}, volume::VoxelType::Float32,
                       volume::VolumeGeometry::regular(origin, glm::dvec3(spacing)));
    out.setDescription("analytic " + shape.name() + " " + std::to_string(n) + "^3, iso 0");
    float* voxels = out.dataAs<float>();
    core::parallelFor(std::size_t(n), [&](std::size_t z) {
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const glm::dvec3 p = origin + spacing * glm::dvec3(x, y, double(z));
                voxels[out.index(x, y, int(z))] = static_cast<float>(shape.value(p));
            }
    });
    return out;
}

} // namespace lw::evaluation
