#include "lw/render/camera.h"

#include "lw/core/error.h"
#include "lw/volume/bricks.h"
#include "lw/volume/volume.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <numbers>
#include <optional>
#include <string>

namespace lw::render {

namespace {

double radians(double degrees) {
    return degrees * std::numbers::pi / 180.0;
}

} // namespace

Aabb volumeBounds(const volume::Volume& volume) {
    if (volume.isEmpty())
        throw core::Error("volume bounds", "the volume is empty");
    const glm::dvec3 last = glm::dvec3(volume.dims() - 1);
    const auto& geometry = volume.geometry();
    Aabb box = Aabb::around(geometry.indexToPatient({0, 0, 0}));
    for (int i = 1; i < 8; ++i)
        box.extend(geometry.indexToPatient(
            {(i & 1) ? last.x : 0.0, (i & 2) ? last.y : 0.0, (i & 4) ? last.z : 0.0}));
    return box;
}

Aabb surfaceBounds(const volume::Volume& volume, double isoReal) {
    const auto grid = volume::BrickGrid::build(volume, glm::ivec3(16));
    const auto& geometry = volume.geometry();
    const double storedIso = volume.valueMapping().toStored(isoReal);
    std::optional<Aabb> box;
    for (const int index : grid.activeBricks(storedIso)) {
        const volume::Brick& brick = grid.bricks()[std::size_t(index)];
        for (int i = 0; i < 8; ++i) {
            const glm::ivec3 corner{(i & 1) ? brick.cellEnd.x : brick.cellBegin.x,
                                    (i & 2) ? brick.cellEnd.y : brick.cellBegin.y,
                                    (i & 4) ? brick.cellEnd.z : brick.cellBegin.z};
            const glm::dvec3 p = geometry.indexToPatient(glm::dvec3(corner));
            if (box)
                box->extend(p);
            else
                box = Aabb::around(p);
        }
    }
    return box ? *box : volumeBounds(volume);
}

Camera::Camera() {
    update();
}

Camera::Camera(const CameraSetup& setup, int width, int height)
    : m_setup(setup), m_width(width), m_height(height) {
    update();
}

void Camera::setSetup(const CameraSetup& setup) {
    m_setup = setup;
    update();
}

void Camera::setView(double azimuthDeg, double elevationDeg) {
    m_setup.azimuthDeg = azimuthDeg;
    m_setup.elevationDeg = elevationDeg;
    update();
}

void Camera::setViewport(int width, int height) {
    m_width = width;
    m_height = height;
    update();
}

void Camera::update() {
    if (m_width <= 0 || m_height <= 0)
        throw core::Error("camera", "invalid viewport " + std::to_string(m_width) + "x" +
                                        std::to_string(m_height));
    if (!m_setup.bounds.isValid())
        throw core::Error("camera", "invalid bounding box (min > max)");
    if (m_setup.projection == Projection::Perspective &&
        !(m_setup.fovYDeg > 0.0 && m_setup.fovYDeg < 179.0))
        throw core::Error("camera", "field of view must lie in (0, 179) degrees");
    if (!(m_setup.margin >= 0.0))
        throw core::Error("camera", "margin must not be negative");
    if (!(m_setup.zoom > 0.0) || !std::isfinite(m_setup.zoom))
        throw core::Error("camera", "zoom must be a positive number");

    m_target = m_setup.bounds.center();
    // A degenerate (point or flat) box still needs a finite view.
    const double radius = std::max(m_setup.bounds.radius(), 1e-6);
    const double az = radians(m_setup.azimuthDeg);
    const double el = radians(m_setup.elevationDeg);
    const glm::dvec3 toEye{std::sin(az) * std::cos(el), -std::cos(az) * std::cos(el), std::sin(el)};
    m_forward = -toEye;
    m_up = glm::dvec3{-std::sin(az) * std::sin(el), std::cos(az) * std::sin(el), std::cos(el)};
    m_right = glm::cross(m_forward, m_up);
    if (m_setup.rollDeg != 0.0) {
        // Turning the screen counter-clockwise turns its axes the same way about the view axis.
        const double roll = radians(m_setup.rollDeg);
        const glm::dvec3 up = std::cos(roll) * m_up - std::sin(roll) * m_right;
        m_right = std::cos(roll) * m_right + std::sin(roll) * m_up;
        m_up = up;
    }

    const double aspect = double(m_width) / double(m_height);
    const double grow = 1.0 + m_setup.margin;
    if (m_setup.projection == Projection::Orthographic) {
        double halfH = 0.0;
        if (m_setup.fit == FitMode::Sphere) {
            halfH = aspect >= 1.0 ? radius * grow : radius * grow / aspect;
        } else {
            double u = 0.0, v = 0.0;
            for (int i = 0; i < 8; ++i) {
                const glm::dvec3 d = m_setup.bounds.corner(i) - m_target;
                u = std::max(u, std::abs(glm::dot(d, m_right)));
                v = std::max(v, std::abs(glm::dot(d, m_up)));
            }
            halfH = std::max({v, u / aspect, radius * 1e-6}) * grow;
        }
        m_halfHeight = halfH / m_setup.zoom;
        m_halfWidth = halfH * aspect / m_setup.zoom;
        m_distance = 2.0 * radius;
        m_near = 0.5 * radius;
        m_far = 3.5 * radius;
    } else {
        const double tanY = std::tan(0.5 * radians(m_setup.fovYDeg));
        const double tanX = tanY * aspect;
        double distance = 0.0;
        if (m_setup.fit == FitMode::Sphere) {
            distance = radius * grow / std::sin(std::atan(std::min(tanX, tanY)));
        } else {
            for (int i = 0; i < 8; ++i) {
                const glm::dvec3 d = m_setup.bounds.corner(i) - m_target;
                const double w = glm::dot(d, m_forward);
                distance = std::max({distance, std::abs(glm::dot(d, m_right)) * grow / tanX - w,
                                     std::abs(glm::dot(d, m_up)) * grow / tanY - w});
            }
            distance = std::max(distance, 1.05 * radius);
        }
        m_halfWidth = tanX / m_setup.zoom;
        m_halfHeight = tanY / m_setup.zoom;
        m_distance = distance;
        m_near = std::max(distance - 1.01 * radius, 1e-3 * radius);
        m_far = distance + 1.01 * radius;
    }
    // Pan in units of the fitted half-height at the target (zoom applied: a drag across the
    // screen moves the surface by the same share of the screen at any zoom).
    const double halfHeightAtTarget = isOrthographic() ? m_halfHeight : m_distance * m_halfHeight;
    m_target += (m_right * m_setup.pan.x + m_up * m_setup.pan.y) * halfHeightAtTarget;
    m_eye = m_target - m_forward * m_distance;
}

glm::dvec3 Camera::toViewer(glm::dvec3 point) const {
    return isOrthographic() ? -m_forward : glm::normalize(m_eye - point);
}

glm::dmat4 Camera::viewMatrix() const {
    return glm::lookAt(m_eye, m_target, m_up);
}

glm::dmat4 Camera::projectionMatrix() const {
    if (isOrthographic())
        return glm::ortho(-m_halfWidth, m_halfWidth, -m_halfHeight, m_halfHeight, m_near, m_far);
    return glm::frustum(-m_halfWidth * m_near, m_halfWidth * m_near, -m_halfHeight * m_near,
                        m_halfHeight * m_near, m_near, m_far);
}

ProjectedPoint Camera::project(glm::dvec3 world) const {
    const glm::dvec3 v = world - m_eye;
    const double x = glm::dot(v, m_right);
    const double y = glm::dot(v, m_up);
    const double z = glm::dot(v, m_forward);
    ProjectedPoint out;
    out.depth = z;
    double ndcX = 0.0, ndcY = 0.0;
    if (isOrthographic()) {
        ndcX = x / m_halfWidth;
        ndcY = y / m_halfHeight;
        out.ndcDepth = (2.0 * z - m_far - m_near) / (m_far - m_near);
    } else {
        ndcX = x / (z * m_halfWidth);
        ndcY = y / (z * m_halfHeight);
        out.ndcDepth =
            (m_far + m_near) / (m_far - m_near) - 2.0 * m_far * m_near / ((m_far - m_near) * z);
    }
    out.pixel = {0.5 * (ndcX + 1.0) * m_width, 0.5 * (1.0 - ndcY) * m_height};
    return out;
}

Ray Camera::rayThroughPoint(glm::dvec2 pixel) const {
    const double ndcX = 2.0 * pixel.x / m_width - 1.0;
    const double ndcY = 1.0 - 2.0 * pixel.y / m_height;
    if (isOrthographic())
        return {m_eye + m_right * (ndcX * m_halfWidth) + m_up * (ndcY * m_halfHeight), m_forward};
    return {m_eye, glm::normalize(m_forward + m_right * (ndcX * m_halfWidth) +
                                  m_up * (ndcY * m_halfHeight))};
}

glm::dvec3 Camera::unproject(glm::dvec2 pixel, double ndcDepth) const {
    const Ray ray = rayThroughPoint(pixel);
    // Invert project()'s ndcDepth(z) for the eye-space depth z along the view axis.
    double z = 0.0;
    if (isOrthographic())
        z = 0.5 * (ndcDepth * (m_far - m_near) + m_far + m_near);
    else
        z = 2.0 * m_far * m_near / ((m_far + m_near) - ndcDepth * (m_far - m_near));
    // The ray reaches view depth z after z / cos(angle to the view axis).
    return ray.at(z / glm::dot(ray.direction, m_forward));
}

glm::dvec3 Camera::panelLightDirection() const {
    return glm::normalize(-m_forward + 0.45 * m_up - 0.30 * m_right);
}

double Camera::pixelFootprint(double depth) const {
    return isOrthographic() ? 2.0 * m_halfHeight / m_height : 2.0 * depth * m_halfHeight / m_height;
}

double Camera::visibleHeightAtTarget() const {
    return isOrthographic() ? 2.0 * m_halfHeight : 2.0 * m_distance * m_halfHeight;
}

int Camera::squareSizeForVoxelCoverage(const CameraSetup& setup, double voxelSize,
                                       double pixelsPerVoxel) {
    if (!(voxelSize > 0.0) || !(pixelsPerVoxel > 0.0))
        throw core::Error("camera", "voxel size and pixels per voxel must be positive");
    const Camera square(setup, 1, 1);
    return std::max(1,
                    int(std::lround(pixelsPerVoxel * square.visibleHeightAtTarget() / voxelSize)));
}

} // namespace lw::render
