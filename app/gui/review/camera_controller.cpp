#include "review/camera_controller.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace lw::gui {
namespace {

constexpr double kDegrees = 180.0 / std::numbers::pi;
// A drag across the whole viewport height turns the surface half a turn.
constexpr double kRadiansPerViewport = std::numbers::pi;

// The camera frame at identity is the anterior view (Camera's az 0, el 0, roll 0):
//   screen right = +x (patient's left), screen up = +z (superior), toward the viewer = -y.
constexpr glm::dvec3 kRight0{1.0, 0.0, 0.0};
constexpr glm::dvec3 kUp0{0.0, 0.0, 1.0};
constexpr glm::dvec3 kToEye0{0.0, -1.0, 0.0};

glm::dquat orientationFor(double azimuthDeg, double elevationDeg, double rollDeg) {
    // Camera: toEye = (sin az cos el, -cos az cos el, sin el): turn about +z by az (toward +x
    // means a rotation of -az about z), then tilt up about the new screen right by el, then roll
    // about the view axis.
    const glm::dquat az = glm::angleAxis(azimuthDeg / kDegrees, glm::dvec3(0, 0, 1));
    const glm::dquat el = glm::angleAxis(-elevationDeg / kDegrees, az * kRight0);
    const glm::dquat base = el * az;
    const glm::dquat roll = glm::angleAxis(rollDeg / kDegrees, base * kToEye0);
    return glm::normalize(roll * base);
}

} // namespace

CameraController::CameraController(QObject* parent) : QObject(parent) {}

void CameraController::setBounds(const render::Aabb& bounds) {
    m_bounds = bounds;
    emit changed();
}

void CameraController::setProjection(render::Projection projection) {
    if (projection == m_projection)
        return;
    m_projection = projection;
    emit changed();
}

render::CameraSetup CameraController::cameraSetup() const {
    const glm::dvec3 toEye = m_orientation * kToEye0;
    const glm::dvec3 up = m_orientation * kUp0;
    const double el = std::asin(std::clamp(toEye.z, -1.0, 1.0));
    // At the poles the azimuth is free: take the one whose elevation tangent is the screen up,
    // so the roll is 0 there.
    const double horizontal = std::hypot(toEye.x, toEye.y);
    const double az = horizontal > 1e-9 ? std::atan2(toEye.x, -toEye.y)
                                        : std::atan2(-up.x * toEye.z, up.y * toEye.z);
    const glm::dvec3 up0{-std::sin(az) * std::sin(el), std::cos(az) * std::sin(el), std::cos(el)};
    const glm::dvec3 right0 = glm::cross(-toEye, up0);
    render::CameraSetup setup;
    setup.bounds = m_bounds;
    setup.projection = m_projection;
    setup.azimuthDeg = az * kDegrees;
    setup.elevationDeg = el * kDegrees;
    // Camera::update turns up0 by roll: up = cos r up0 - sin r right0.
    setup.rollDeg = std::atan2(-glm::dot(up, right0), glm::dot(up, up0)) * kDegrees;
    setup.zoom = m_zoom;
    setup.pan = m_pan;
    return setup;
}

render::Camera CameraController::camera(int width, int height) const {
    return render::Camera(cameraSetup(), std::max(1, width), std::max(1, height));
}

void CameraController::rotateByDrag(QPointF delta, QSize viewport) {
    const double length = std::hypot(delta.x(), delta.y());
    if (length == 0.0 || viewport.height() <= 0)
        return;
    // Dragging right turns the front of the surface to the right (about screen up), dragging
    // down turns it down (about screen right); the camera turns the opposite way.
    const glm::dvec3 right = m_orientation * kRight0;
    const glm::dvec3 up = m_orientation * kUp0;
    const glm::dvec3 axis = glm::normalize(up * delta.x() + right * delta.y());
    const double angle = kRadiansPerViewport * length / viewport.height();
    m_orientation = glm::normalize(glm::angleAxis(-angle, axis) * m_orientation);
    emit changed();
}

void CameraController::panByDrag(QPointF delta, QSize viewport) {
    if (viewport.height() <= 0)
        return;
    // Pan is in units of the half-height at the target: half the viewport's height in pixels.
    const double unit = 0.5 * viewport.height();
    m_pan += glm::dvec2(-delta.x() / unit, delta.y() / unit);
    m_pan = glm::clamp(m_pan, glm::dvec2(-4.0), glm::dvec2(4.0));
    emit changed();
}

void CameraController::zoomBy(double factor) {
    if (!(factor > 0.0))
        return;
    m_zoom = std::clamp(m_zoom * factor, 0.1, 50.0);
    emit changed();
}

void CameraController::rollBy(double degrees) {
    const glm::dvec3 toEye = m_orientation * kToEye0;
    m_orientation = glm::normalize(glm::angleAxis(degrees / kDegrees, toEye) * m_orientation);
    emit changed();
}

void CameraController::setView(double azimuthDeg, double elevationDeg, double rollDeg) {
    m_orientation = orientationFor(azimuthDeg, elevationDeg, rollDeg);
    emit changed();
}

void CameraController::setStandardView(StandardView view) {
    switch (view) {
    case StandardView::Anterior:
        return setView(0.0, 0.0);
    case StandardView::Posterior:
        return setView(180.0, 0.0);
    case StandardView::Left:
        return setView(90.0, 0.0);
    case StandardView::Right:
        return setView(-90.0, 0.0);
    case StandardView::Superior:
        return setView(0.0, 90.0);
    case StandardView::Inferior:
        return setView(0.0, -90.0);
    }
}

void CameraController::reset() {
    m_zoom = 1.0;
    m_pan = glm::dvec2(0.0);
    setView(0.0, 0.0);
}

} // namespace lw::gui
