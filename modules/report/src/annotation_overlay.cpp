#include "lw/report/annotation_overlay.h"

#include "lw/annotation/annotation_projection.h"

#include <QFont>
#include <QFontMetricsF>
#include <QPainter>
#include <QPainterPath>
#include <QString>
#include <cmath>

namespace lw::report {
namespace {

using annotation::AnnotationKind;
using annotation::ProjectedAnnotation;

QPointF toPoint(glm::dvec2 pixel) {
    return {pixel.x, pixel.y};
}

// Text at `anchor` (its left baseline moved by `offset`), over a halo box so it stays legible.
void drawText(QPainter& painter, const QString& text, QPointF anchor, QPointF offset,
              const OverlayStyle& style) {
    if (text.isEmpty())
        return;
    const QFontMetricsF metrics(painter.font());
    const QPointF baseline = anchor + offset;
    QRectF box = metrics.boundingRect(text).translated(baseline);
    const double pad = metrics.height() * 0.15;
    box.adjust(-pad, -pad, pad, pad);
    painter.fillRect(box, style.halo);
    painter.drawText(baseline, text);
}

QString caption(const ProjectedAnnotation& projected) {
    const QString text = QString::fromStdString(projected.text);
    const QString measurement = QString::fromStdString(projected.measurement);
    if (text.isEmpty())
        return measurement;
    return measurement.isEmpty() ? text : text + QStringLiteral(" ") + measurement;
}

// A unit vector perpendicular to a -> b (or up when they coincide).
QPointF perpendicular(QPointF a, QPointF b) {
    const QPointF d = b - a;
    const double length = std::hypot(d.x(), d.y());
    return length > 0.0 ? QPointF(-d.y() / length, d.x() / length) : QPointF(0.0, -1.0);
}

void drawLabel(QPainter& painter, const ProjectedAnnotation& projected, double scale,
               const OverlayStyle& style) {
    const QPointF at = toPoint(projected.points[0]);
    const double r = 4.0 * scale;
    painter.drawLine(at - QPointF(r, 0), at + QPointF(r, 0));
    painter.drawLine(at - QPointF(0, r), at + QPointF(0, r));
    drawText(painter, caption(projected), at, QPointF(2.0 * r, -r), style);
}

void drawArrow(QPainter& painter, const ProjectedAnnotation& projected, double scale,
               const OverlayStyle& style) {
    const QPointF tail = toPoint(projected.points[0]), head = toPoint(projected.points[1]);
    painter.drawLine(tail, head);
    const QPointF side = perpendicular(tail, head);
    const QPointF back(side.y(), -side.x()); // unit, from the head toward the tail
    const double length = 14.0 * scale, half = 5.0 * scale;
    QPainterPath tip;
    tip.moveTo(head);
    tip.lineTo(head + back * length + side * half);
    tip.lineTo(head + back * length - side * half);
    tip.closeSubpath();
    painter.fillPath(tip, style.colour);
    drawText(painter, caption(projected), tail, QPointF(4.0 * scale, -4.0 * scale), style);
}

void drawRuler(QPainter& painter, const ProjectedAnnotation& projected, double scale,
               const OverlayStyle& style) {
    const QPointF a = toPoint(projected.points[0]), b = toPoint(projected.points[1]);
    painter.drawLine(a, b);
    const QPointF tick = perpendicular(a, b) * (6.0 * scale);
    painter.drawLine(a - tick, a + tick);
    painter.drawLine(b - tick, b + tick);
    const QPointF middle = (a + b) / 2.0;
    drawText(painter, caption(projected), middle, QPointF(6.0 * scale, -6.0 * scale), style);
}

void drawAngle(QPainter& painter, const ProjectedAnnotation& projected, double scale,
               const OverlayStyle& style) {
    const QPointF a = toPoint(projected.points[0]), vertex = toPoint(projected.points[1]),
                  b = toPoint(projected.points[2]);
    painter.drawLine(vertex, a);
    painter.drawLine(vertex, b);
    // The arc between the arms, in screen angles (y down: Qt's angles run counter-clockwise
    // on screen, hence the minus signs).
    const double startDeg = -std::atan2(a.y() - vertex.y(), a.x() - vertex.x()) * 180.0 / M_PI;
    const double endDeg = -std::atan2(b.y() - vertex.y(), b.x() - vertex.x()) * 180.0 / M_PI;
    double span = std::remainder(endDeg - startDeg, 360.0);
    const double radius = 18.0 * scale;
    painter.drawArc(QRectF(vertex - QPointF(radius, radius), vertex + QPointF(radius, radius)),
                    int(std::lround(startDeg * 16.0)), int(std::lround(span * 16.0)));
    drawText(painter, caption(projected), vertex, QPointF(radius + 4.0 * scale, 4.0 * scale),
             style);
}

} // namespace

double overlayScale(int height, const OverlayStyle& style) {
    return std::max(0.5, height / style.referenceHeight);
}

void burnInAnnotations(QImage& panel, const std::vector<annotation::Annotation>& annotations,
                       const render::Camera& camera, const OverlayStyle& style) {
    if (annotations.empty() || panel.isNull())
        return;
    const double scale = overlayScale(panel.height(), style);
    QPainter painter(&panel);
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setRenderHint(QPainter::TextAntialiasing);
    painter.setPen(QPen(style.colour, style.lineWidth * scale, Qt::SolidLine, Qt::RoundCap));
    QFont font = painter.font();
    font.setPixelSize(std::max(6, int(std::lround(style.fontPixelSize * scale))));
    painter.setFont(font);
    for (const annotation::Annotation& item : annotations) {
        const ProjectedAnnotation projected = annotation::projectAnnotation(item, camera);
        if (!projected.inFront)
            continue;
        switch (projected.kind) {
        case AnnotationKind::Label:
            drawLabel(painter, projected, scale, style);
            break;
        case AnnotationKind::Arrow:
            drawArrow(painter, projected, scale, style);
            break;
        case AnnotationKind::Ruler:
            drawRuler(painter, projected, scale, style);
            break;
        case AnnotationKind::Angle:
            drawAngle(painter, projected, scale, style);
            break;
        }
    }
}

} // namespace lw::report
