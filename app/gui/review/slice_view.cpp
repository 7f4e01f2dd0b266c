#include "review/slice_view.h"

#include <QApplication>
#include <QElapsedTimer>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>

namespace lw::gui {
namespace {

// The linked cursor's cross-hair, the same colour as in the 3D panels (review_panel.cpp).
const QColor kMarkerColour(0, 200, 255);
constexpr int kWheelNotch = 120; // angleDelta units of one wheel notch

void drawShadowedText(QPainter& painter, const QRectF& rect, int flags, const QString& text) {
    painter.setPen(QColor(0, 0, 0, 200));
    painter.drawText(rect.translated(1, 1), flags, text);
    painter.setPen(QColor(230, 230, 230));
    painter.drawText(rect, flags, text);
}

} // namespace

SliceView::SliceView(volume::SliceGeometry geometry, QWidget* parent)
    : QWidget(parent), m_geometry(std::move(geometry)) {
    setObjectName(QString::fromLatin1(volume::sliceOrientationName(m_geometry.orientation).data()) +
                  QStringLiteral("Slice"));
    m_position = m_geometry.middlePosition();
    setMouseTracking(true); // the value readout follows the mouse
    setFocusPolicy(Qt::StrongFocus);
    setAttribute(Qt::WA_OpaquePaintEvent);
    setMinimumSize(120, 120);
}

std::optional<double> SliceView::shownPosition() const {
    return m_slice && m_slice->image ? std::optional(m_slice->image->position) : std::nullopt;
}

void SliceView::setPosition(double position) {
    const double low = std::min(m_geometry.firstPosition, m_geometry.lastPosition);
    const double high = std::max(m_geometry.firstPosition, m_geometry.lastPosition);
    position = std::clamp(position, low, high);
    if (position == m_position)
        return;
    m_position = position;
    update();
    emit positionChanged(m_position);
}

void SliceView::stepBy(int steps) {
    setPosition(m_position + steps * m_geometry.step);
}

QString SliceView::positionText() const {
    return tr("%1 %2").arg(sliceOrientationTitle(orientation()),
                           slicePositionText(orientation(), m_position));
}

void SliceView::setSlice(std::shared_ptr<const SliceResult> result) {
    m_slice = std::move(result);
    m_windowed = m_slice->image ? windowedImage(*m_slice->image, m_window) : QImage();
    update();
    emit sliceShown();
}

void SliceView::setWindowLevel(WindowLevel window) {
    if (window == m_window)
        return;
    m_window = window;
    if (m_slice && m_slice->image)
        m_windowed = windowedImage(*m_slice->image, m_window);
    update();
}

void SliceView::setContourColour(const QColor& colour) {
    m_contourColour = colour;
    update();
}

void SliceView::setMarker(std::optional<glm::dvec3> patient) {
    m_marker = patient;
    update();
}

void SliceView::setOverlayPainter(OverlayPainter painter) {
    m_overlayPainter = std::move(painter);
    update();
}

void SliceView::setValueReader(std::function<QString(glm::dvec3)> reader) {
    m_valueReader = std::move(reader);
}

SliceView::Placement SliceView::placement() const {
    const glm::dvec2 size(m_geometry.size);
    const double fit = std::min(width() / std::max(size.x, 1.0), height() / std::max(size.y, 1.0));
    Placement placed;
    placed.scale = fit * m_zoom;
    const QPointF centre = QPointF(width(), height()) / 2.0 + m_pan;
    placed.origin = centre - QPointF(size.x, size.y) * placed.scale / 2.0;
    return placed;
}

QPointF SliceView::widgetPointOfPixel(glm::dvec2 pixel) const {
    const Placement placed = placement();
    return placed.origin + QPointF(pixel.x + 0.5, pixel.y + 0.5) * placed.scale;
}

std::optional<glm::dvec3> SliceView::patientAt(QPointF widgetPoint) const {
    const Placement placed = placement();
    const QPointF inImage = (widgetPoint - placed.origin) / placed.scale;
    const glm::dvec2 pixel(inImage.x() - 0.5, inImage.y() - 0.5);
    const glm::dvec2 size(m_geometry.size);
    if (pixel.x < -0.5 || pixel.y < -0.5 || pixel.x > size.x - 0.5 || pixel.y > size.y - 0.5)
        return std::nullopt;
    return m_geometry.patientPoint(pixel, m_position);
}

QPointF SliceView::widgetPointOf(glm::dvec3 patient) const {
    return widgetPointOfPixel(m_geometry.pixelOf(patient));
}

void SliceView::paintEvent(QPaintEvent*) {
    QElapsedTimer timer;
    timer.start();
    QPainter painter(this);
    painter.fillRect(rect(), Qt::black);
    if (!m_windowed.isNull()) {
        const Placement placed = placement();
        const QRectF target(placed.origin,
                            QSizeF(m_geometry.size.x, m_geometry.size.y) * placed.scale);
        // Smoothed when shrunk (no aliasing); magnified pixels stay visible as voxels.
        painter.setRenderHint(QPainter::SmoothPixmapTransform, placed.scale < 1.0);
        painter.drawImage(target, m_windowed);
    }
    drawContour(painter);
    drawMarker(painter);
    if (m_overlayPainter) {
        painter.save();
        m_overlayPainter(painter);
        painter.restore();
    }
    drawLabels(painter);
    painter.end();
    m_lastPaintMs = double(timer.nsecsElapsed()) / 1e6;
    emit painted(m_lastPaintMs);
}

void SliceView::drawContour(QPainter& painter) const {
    if (!m_slice || m_slice->contour.empty())
        return;
    QVector<QLineF> lines;
    lines.reserve(qsizetype(m_slice->contour.size()));
    for (const volume::ContourSegment& segment : m_slice->contour)
        lines.append(QLineF(widgetPointOfPixel(segment.a), widgetPointOfPixel(segment.b)));
    // Thin and aliased: a 512 x 512 CT slice's bone contour has thousands of segments, which
    // antialiased 1.5-pixel lines took 5 ms to draw on the UI thread (linework-review-bench).
    painter.save();
    painter.setPen(QPen(m_contourColour, 1.0));
    painter.drawLines(lines);
    painter.restore();
}

void SliceView::drawMarker(QPainter& painter) const {
    if (!m_marker)
        return;
    const QPointF at = widgetPointOf(*m_marker);
    // Solid on the slice through the point, dashed on a slice away from it.
    const bool onSlice =
        std::abs(m_geometry.positionOf(*m_marker) - m_position) <= 0.5 * m_geometry.step;
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(kMarkerColour, 1.5, onSlice ? Qt::SolidLine : Qt::DashLine));
    constexpr double kGap = 4.0, kArm = 14.0;
    painter.drawLine(at + QPointF(-kArm, 0), at + QPointF(-kGap, 0));
    painter.drawLine(at + QPointF(kGap, 0), at + QPointF(kArm, 0));
    painter.drawLine(at + QPointF(0, -kArm), at + QPointF(0, -kGap));
    painter.drawLine(at + QPointF(0, kGap), at + QPointF(0, kArm));
    painter.restore();
}

void SliceView::drawLabels(QPainter& painter) const {
    const volume::SliceEdgeLabels edges = volume::sliceEdgeLabels(orientation());
    const QRectF inner = QRectF(rect()).adjusted(6, 4, -6, -4);
    QFont bold = painter.font();
    bold.setBold(true);
    painter.setFont(bold);
    drawShadowedText(painter, inner, Qt::AlignTop | Qt::AlignHCenter, QString(QChar(edges.top)));
    drawShadowedText(painter, inner, Qt::AlignBottom | Qt::AlignHCenter,
                     QString(QChar(edges.bottom)));
    drawShadowedText(painter, inner, Qt::AlignVCenter | Qt::AlignLeft, QString(QChar(edges.left)));
    drawShadowedText(painter, inner, Qt::AlignVCenter | Qt::AlignRight,
                     QString(QChar(edges.right)));
    painter.setFont(font());
    drawShadowedText(painter, inner, Qt::AlignTop | Qt::AlignLeft, positionText());
    drawShadowedText(painter, inner, Qt::AlignTop | Qt::AlignRight,
                     tr("W %1 · L %2").arg(m_window.width).arg(m_window.level));
    drawShadowedText(painter, inner, Qt::AlignBottom | Qt::AlignLeft, m_readout);
    if (m_slice && !m_slice->error.isEmpty())
        drawShadowedText(painter, inner, Qt::AlignCenter | Qt::TextWordWrap, m_slice->error);
}

void SliceView::wheelEvent(QWheelEvent* event) {
    const QPoint delta = event->angleDelta();
    const int amount = delta.y() != 0 ? delta.y() : delta.x();
    if (event->modifiers() & Qt::ControlModifier) {
        zoomBy(std::pow(1.1, amount / double(kWheelNotch)));
    } else {
        m_wheelRemainder += amount;
        const int steps = m_wheelRemainder / kWheelNotch;
        m_wheelRemainder -= steps * kWheelNotch;
        if (steps != 0)
            stepBy(steps);
    }
    updateReadout(event->position()); // the value under the mouse on the new slice
    event->accept();
}

void SliceView::keyPressEvent(QKeyEvent* event) {
    switch (event->key()) {
    case Qt::Key_PageUp:
        return stepBy(1);
    case Qt::Key_PageDown:
        return stepBy(-1);
    case Qt::Key_Plus:
    case Qt::Key_Equal:
        return zoomBy(1.1);
    case Qt::Key_Minus:
        return zoomBy(1.0 / 1.1);
    case Qt::Key_Home:
        m_zoom = 1.0;
        m_pan = QPointF();
        update();
        return;
    default:
        QWidget::keyPressEvent(event);
    }
}

void SliceView::zoomBy(double factor) {
    m_zoom = std::clamp(m_zoom * factor, 0.25, 32.0);
    update();
}

void SliceView::mousePressEvent(QMouseEvent* event) {
    setFocus();
    m_lastMouse = event->position();
    m_shiftPressed = event->button() == Qt::LeftButton && (event->modifiers() & Qt::ShiftModifier);
    m_shiftPress = event->position();
}

void SliceView::mouseMoveEvent(QMouseEvent* event) {
    const QPointF delta = event->position() - m_lastMouse;
    m_lastMouse = event->position();
    if (event->buttons() & Qt::RightButton) {
        dragWindow(delta);
    } else if (event->buttons() & Qt::MiddleButton) {
        m_pan += delta;
        update();
    }
    updateReadout(event->position());
}

void SliceView::mouseReleaseEvent(QMouseEvent* event) {
    const bool click =
        (event->position() - m_shiftPress).manhattanLength() < QApplication::startDragDistance();
    if (event->button() == Qt::LeftButton && m_shiftPressed && click)
        if (const std::optional<glm::dvec3> point = patientAt(event->position()))
            emit linkRequested(*point);
    m_shiftPressed = false;
}

void SliceView::leaveEvent(QEvent*) {
    m_readout.clear();
    update();
}

// Right drag: to the right widens the window, down raises the level (the image darkens), as in
// Horos and Weasis; faster for wide windows so bone and brain both take a short drag.
void SliceView::dragWindow(QPointF delta) {
    const double perPixel = std::max(1.0, m_window.width / 200.0);
    WindowLevel window = m_window;
    window.width = std::max(1.0, window.width + delta.x() * perPixel);
    window.level += delta.y() * perPixel;
    setWindowLevel(window);
    emit windowLevelDragged(m_window);
}

void SliceView::updateReadout(QPointF widgetPoint) {
    const std::optional<glm::dvec3> point = patientAt(widgetPoint);
    const QString text = point && m_valueReader ? m_valueReader(*point) : QString();
    if (text != m_readout) {
        m_readout = text;
        update();
    }
}

} // namespace lw::gui
