#include "annotate/overlay_painter.h"

#include "lw/annotation/annotation_projection.h"

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

void drawHandles(QPainter& painter, const annotation::ProjectedAnnotation& projected,
                 double scale) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(selectedStyle().colour, 1.5 * scale));
    painter.setBrush(Qt::white);
    const double radius = 4.5 * scale;
    for (const glm::dvec2& point : projected.points)
        painter.drawEllipse(toPoint(point), radius, radius);
    painter.restore();
}

void drawRubberBand(QPainter& painter, const annotation::ProjectedAnnotation& band, double scale) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(selectedStyle().colour, 1.5 * scale, Qt::DashLine));
    painter.drawLine(toPoint(band.points.at(0)), toPoint(band.points.at(1)));
    painter.restore();
}

void drawShown(QPainter& painter, const std::optional<annotation::ProjectedAnnotation>& shown,
               bool selected, double scale) {
    if (!shown)
        return;
    report::drawProjectedAnnotation(painter, *shown, scale,
                                    selected ? selectedStyle() : normalStyle());
    if (selected)
        drawHandles(painter, *shown, scale);
}

// The scene through any panel's projection: the 3D panels' camera or a slice's pixels.
void paintScene(QPainter& painter, const PanelProjector& project, const OverlayScene& scene,
                double scale) {
    const auto& annotations = *scene.annotations;
    for (int i = 0; i < int(annotations.size()); ++i)
        if (i != scene.previewReplaces)
            drawShown(painter, project(annotations[std::size_t(i)]), i == scene.selected, scale);
    if (scene.preview)
        drawShown(painter, project(*scene.preview), true, scale);
    if (scene.rubberBand) {
        // Projected as a two-point annotation, so a slice shows it only within its slab.
        const annotation::Annotation band{annotation::AnnotationKind::Ruler,
                                          {scene.rubberBand->first, scene.rubberBand->second},
                                          {}};
        if (const std::optional<annotation::ProjectedAnnotation> shown = project(band))
            drawRubberBand(painter, *shown, scale);
    }
}

} // namespace

void paintOverlay(QPainter& painter, const render::Camera& camera, const OverlayScene& scene,
                  double scale) {
    paintScene(painter, cameraProjector(camera), scene, scale);
}

PanelProjector sliceProjector(const report::SlicePanelFrame& slice) {
    return [slice](const annotation::Annotation& item)
               -> std::optional<annotation::ProjectedAnnotation> {
        if (!annotation::showsOnSlice(item, slice.orientation, slice.positionMm, slice.spacingMm))
            return std::nullopt;
        return annotation::projectAnnotation(item, slice.toPixel);
    };
}

void paintOverlay(QPainter& painter, const report::SlicePanelFrame& slice,
                  const OverlayScene& scene, double scale) {
    paintScene(painter, sliceProjector(slice), scene, scale);
}

} // namespace lw::gui
