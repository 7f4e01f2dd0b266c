#pragma once

// One slice panel: a resampled axial, coronal or sagittal slice under a window/level, its iso
// contour, the linked cursor's cross-hair, the patient direction letters at its edges, the
// plane's name and position, and the value under the mouse. Raster painting (no OpenGL): the
// image comes from a SliceSampler; the view only maps it to the widget.
//
// Widget pixels and patient points map both ways (patientAt, widgetPointOf), through the
// image's pixels:
//
//   widget = origin + (pixel + 0.5) * scale     pixel centres at integers (slice_plane.h),
//   origin: the image's top-left corner in the widget, fitted and centred, then zoomed and
//   panned; the patient point of a pixel lies on the plane at position().
//
// Mouse and keys: wheel / Page Up / Page Down one slice step; Ctrl+wheel, + and - zoom; middle
// drag pans; Home resets zoom and pan; right drag sets window (left-right) and level (up-down);
// Shift+click asks for the linked cursor at the point. The left button without Shift is the
// annotation tools' (AnnotationToolController filters it, as on the 3D panels).

#include "lw/volume/slice_plane.h"
#include "review/slice_image.h"
#include "review/slice_sampler.h"

#include <QColor>
#include <QImage>
#include <QPainter>
#include <QPointF>
#include <QWidget>
#include <functional>
#include <memory>
#include <optional>

namespace lw::gui {

class SliceView : public QWidget {
    Q_OBJECT
public:
    explicit SliceView(volume::SliceGeometry geometry, QWidget* parent = nullptr);

    volume::SliceOrientation orientation() const { return m_geometry.orientation; }
    const volume::SliceGeometry& geometry() const { return m_geometry; }
    // The position asked for (mm along the plane's normal); the image follows when sampled.
    double position() const { return m_position; }
    // The position of the slice on screen, or nothing before the first one arrives.
    std::optional<double> shownPosition() const;
    void setPosition(double position); // clamped to the volume's slices
    void stepBy(int steps);            // SliceGeometry::step each
    // The plane and its position as the view shows them ("Axial S 12.5 mm").
    QString positionText() const;

    void setSlice(std::shared_ptr<const SliceResult> result);
    const SliceResult* slice() const { return m_slice.get(); }
    void setWindowLevel(WindowLevel window);
    WindowLevel windowLevel() const { return m_window; }
    void setContourColour(const QColor& colour);
    QColor contourColour() const { return m_contourColour; }
    void setMarker(std::optional<glm::dvec3> patient);
    std::optional<glm::dvec3> marker() const { return m_marker; }
    // The text of the value at a patient point (nothing outside the volume), for the readout.
    void setValueReader(std::function<QString(glm::dvec3)> reader);
    QString readout() const { return m_readout; }

    // Drawn over the slice (in widget pixels) after the contour and the cursor: the annotations.
    using OverlayPainter = std::function<void(QPainter& painter)>;
    void setOverlayPainter(OverlayPainter painter);

    std::optional<glm::dvec3> patientAt(QPointF widgetPoint) const;
    QPointF widgetPointOf(glm::dvec3 patient) const;
    double zoom() const { return m_zoom; }
    double lastPaintMs() const { return m_lastPaintMs; }

signals:
    void positionChanged(double position);
    void windowLevelDragged(lw::gui::WindowLevel window);
    void linkRequested(glm::dvec3 patient); // Shift+click on the slice
    void sliceShown();                      // a new result taken (painted at the next paint)
    void painted(double milliseconds);

protected:
    void paintEvent(QPaintEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void mouseReleaseEvent(QMouseEvent* event) override;
    void leaveEvent(QEvent* event) override;

private:
    struct Placement {
        double scale = 1.0; // widget pixels per image pixel
        QPointF origin;     // the image's top-left corner
    };
    Placement placement() const;
    QPointF widgetPointOfPixel(glm::dvec2 pixel) const;
    void zoomBy(double factor);
    void dragWindow(QPointF delta);
    void updateReadout(QPointF widgetPoint);
    void drawContour(QPainter& painter) const;
    void drawMarker(QPainter& painter) const;
    void drawLabels(QPainter& painter) const;

    volume::SliceGeometry m_geometry;
    double m_position = 0.0;
    std::shared_ptr<const SliceResult> m_slice;
    QImage m_windowed; // m_slice's image under m_window
    WindowLevel m_window;
    QColor m_contourColour = QColor(255, 255, 0);
    std::optional<glm::dvec3> m_marker;
    std::function<QString(glm::dvec3)> m_valueReader;
    QString m_readout;
    OverlayPainter m_overlayPainter;
    double m_zoom = 1.0;
    QPointF m_pan; // widget pixels
    QPointF m_lastMouse;
    QPointF m_shiftPress;
    bool m_shiftPressed = false;
    int m_wheelRemainder = 0; // eighths of a degree not yet a whole step (touchpads)
    double m_lastPaintMs = 0.0;
};

} // namespace lw::gui
