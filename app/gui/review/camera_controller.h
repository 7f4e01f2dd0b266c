#pragma once

// One camera for both review panels (linked cameras): a trackball orientation, pan, zoom and
// the projection, in patient coordinates (LPS). The engine's Camera is built from it for any
// viewport size, so both panels and an export at another resolution show the same view.
//
// The orientation is a rotation of the camera frame; the engine's Camera wants azimuth,
// elevation and roll, so cameraSetup() converts (exactly, poles included).

#include "lw/render/camera.h"

#include <QObject>
#include <QPointF>
#include <QSize>
#include <glm/gtc/quaternion.hpp>

namespace lw::gui {

enum class StandardView { Anterior, Posterior, Left, Right, Superior, Inferior };

class CameraController : public QObject {
    Q_OBJECT
public:
    explicit CameraController(QObject* parent = nullptr);

    void setBounds(const render::Aabb& bounds);
    const render::Aabb& bounds() const { return m_bounds; }
    void setProjection(render::Projection projection);
    render::Projection projection() const { return m_projection; }

    render::CameraSetup cameraSetup() const;
    render::Camera camera(int width, int height) const;

    // Mouse: a drag of `delta` pixels on a viewport of `viewport` pixels.
    void rotateByDrag(QPointF delta, QSize viewport);
    void panByDrag(QPointF delta, QSize viewport);
    void zoomBy(double factor);
    void rollBy(double degrees);
    void setView(double azimuthDeg, double elevationDeg, double rollDeg = 0.0);
    void setStandardView(StandardView view);
    void reset();

    double zoom() const { return m_zoom; }
    glm::dvec2 pan() const { return m_pan; }

signals:
    void changed();

private:
    render::Aabb m_bounds{{-1, -1, -1}, {1, 1, 1}};
    render::Projection m_projection = render::Projection::Perspective;
    glm::dquat m_orientation{1.0, 0.0, 0.0, 0.0}; // camera frame: anterior view at identity
    double m_zoom = 1.0;
    glm::dvec2 m_pan{0.0};
};

} // namespace lw::gui
