#include "annotate/overlay_painter.h"

#include "lw/report/annotation_overlay.h"

namespace lw::gui {
namespace {

report::OverlayStyle normalStyle() {
    return {};
}

// The selected annotation stands out from the burnt-in orange without hiding what it measures.
report::OverlayStyle selectedStyle() {
    report::OverlayStyle style;
    style.colour = QColor(0, 140, 255);
    style.lineWidth = 2.5;
    return style;
}

QPointF toPoint(glm::dvec2 pixel) {
    return {pixel.x, pixel.y};
}

void drawHandles(QPainter& painter, const render::Camera& camera,
                 const annotation::Annotation& annotation, double scale) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(selectedStyle().colour, 1.5 * scale));
    painter.setBrush(Qt::white);
    const double radius = 4.5 * scale;
    for (const glm::dvec3& anchor : annotation.anchors) {
        const render::ProjectedPoint point = camera.project(anchor);
        if (camera.isOrthographic() || point.depth > 0.0)
            painter.drawEllipse(toPoint(point.pixel), radius, radius);
    }
    painter.restore();
}

void drawRubberBand(QPainter& painter, const render::Camera& camera,
                    const std::pair<glm::dvec3, glm::dvec3>& band, double scale) {
    const render::ProjectedPoint a = camera.project(band.first);
    const render::ProjectedPoint b = camera.project(band.second);
    if (!camera.isOrthographic() && (a.depth <= 0.0 || b.depth <= 0.0))
        return;
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(selectedStyle().colour, 1.5 * scale, Qt::DashLine));
    painter.drawLine(toPoint(a.pixel), toPoint(b.pixel));
    painter.restore();
}

} // namespace

void paintOverlay(QPainter& painter, const render::Camera& camera, const OverlayScene& scene,
                  double scale) {
    const auto& annotations = *scene.annotations;
    for (int i = 0; i < int(annotations.size()); ++i) {
        if (i == scene.previewReplaces)
            continue;
        const bool selected = i == scene.selected;
        report::drawAnnotation(painter, annotations[std::size_t(i)], camera, scale,
                               selected ? selectedStyle() : normalStyle());
        if (selected)
            drawHandles(painter, camera, annotations[std::size_t(i)], scale);
    }
    if (scene.preview) {
        report::drawAnnotation(painter, *scene.preview, camera, scale, selectedStyle());
        drawHandles(painter, camera, *scene.preview, scale);
    }
    if (scene.rubberBand)
        drawRubberBand(painter, camera, *scene.rubberBand, scale);
}

} // namespace lw::gui
