#include "lw/report/annotation_overlay.h"

#include "lw/annotation/annotation_projection.h"
#include "overlay_shapes.h"

#include <QFont>
#include <QFontMetricsF>
#include <QPainter>
#include <QPainterPath>
#include <QString>
#include <cmath>

namespace lw::report {
namespace {

QPointF toPoint(glm::dvec2 pixel) {
    return {pixel.x, pixel.y};
}

// A caption over a halo box, so it stays legible over lines and the shaded surface.
void drawCaption(QPainter& painter, const OverlayShapes::Caption& caption,
                 const OverlayStyle& style) {
    const QString text = QString::fromStdString(caption.text);
    const QFontMetricsF metrics(painter.font());
    QRectF box = metrics.boundingRect(text).translated(toPoint(caption.baseline));
    const double pad = metrics.height() * 0.15;
    box.adjust(-pad, -pad, pad, pad);
    painter.fillRect(box, style.halo);
    painter.drawText(toPoint(caption.baseline), text);
}

void drawShapes(QPainter& painter, const OverlayShapes& shapes, const OverlayStyle& style) {
    for (const OverlayShapes::Segment& segment : shapes.segments)
        painter.drawLine(toPoint(segment.a), toPoint(segment.b));
    for (const auto& triangle : shapes.triangles) {
        QPainterPath path;
        path.moveTo(toPoint(triangle[0]));
        path.lineTo(toPoint(triangle[1]));
        path.lineTo(toPoint(triangle[2]));
        path.closeSubpath();
        painter.fillPath(path, style.colour);
    }
    for (const OverlayShapes::Arc& arc : shapes.arcs) {
        const QPointF r(arc.radius, arc.radius);
        painter.drawArc(QRectF(toPoint(arc.centre) - r, toPoint(arc.centre) + r),
                        int(std::lround(arc.startDeg * 16.0)),
                        int(std::lround(arc.spanDeg * 16.0)));
    }
    for (const OverlayShapes::Caption& caption : shapes.captions)
        drawCaption(painter, caption, style);
}

} // namespace

double overlayScale(int height, const OverlayStyle& style) {
    return std::max(0.5, height / style.referenceHeight);
}

void drawAnnotation(QPainter& painter, const annotation::Annotation& annotation,
                    const render::Camera& camera, double scale, const OverlayStyle& style) {
    const annotation::ProjectedAnnotation projected =
        annotation::projectAnnotation(annotation, camera);
    if (projected.inFront)
        drawProjectedAnnotation(painter, projected, scale, style);
}

void drawProjectedAnnotation(QPainter& painter, const annotation::ProjectedAnnotation& projected,
                             double scale, const OverlayStyle& style) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setRenderHint(QPainter::TextAntialiasing);
    painter.setPen(QPen(style.colour, style.lineWidth * scale, Qt::SolidLine, Qt::RoundCap));
    QFont font = painter.font();
    font.setPixelSize(std::max(6, int(std::lround(style.fontPixelSize * scale))));
    painter.setFont(font);
    drawShapes(painter, overlayShapes(projected, scale), style);
    painter.restore();
}

void burnInAnnotations(QImage& panel, const std::vector<annotation::Annotation>& annotations,
                       const render::Camera& camera, const OverlayStyle& style) {
    if (annotations.empty() || panel.isNull())
        return;
    const double scale = overlayScale(panel.height(), style);
    QPainter painter(&panel);
    for (const annotation::Annotation& item : annotations)
        drawAnnotation(painter, item, camera, scale, style);
}

void burnInSliceAnnotations(QImage& panel, const std::vector<annotation::Annotation>& annotations,
                            const SlicePanelFrame& slice, const OverlayStyle& style) {
    if (annotations.empty() || panel.isNull())
        return;
    const double scale = overlayScale(panel.height(), style);
    QPainter painter(&panel);
    for (const annotation::Annotation& item : annotations)
        if (annotation::showsOnSlice(item, slice.orientation, slice.positionMm, slice.spacingMm))
            drawProjectedAnnotation(painter, annotation::projectAnnotation(item, slice.toPixel),
                                    scale, style);
}

} // namespace lw::report
