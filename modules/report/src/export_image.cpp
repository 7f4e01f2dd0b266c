#include "lw/report/export_image.h"

#include "lw/render/svg_lines.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>

namespace lw::report {

namespace {

// The silhouette panel as the picture starts from: its raster, or, when its lines come as
// vectors, an empty panel of the same size and background for them to be drawn on.
QImage silhouetteBase(const RenderedPanels& panels) {
    if (panels.silhouetteLines.empty() || panels.silhouette.isNull())
        return panels.silhouette;
    QImage blank(panels.silhouette.size(), QImage::Format_RGB32);
    blank.fill(panels.silhouette.pixelColor(0, 0)); // the background: a corner holds no line
    return blank;
}

// `lines` (silhouette panel pixels) placed in the picture of `layout`: shifted past the iso
// panel side by side, none without a silhouette panel.
std::vector<render::Polyline> placedLines(std::vector<render::Polyline> lines,
                                          const RenderedPanels& panels, PanelLayout layout) {
    if (layout == PanelLayout::IsoPanel)
        return {};
    const float shift = layout == PanelLayout::SideBySide ? float(panels.iso.width()) : 0.0f;
    for (render::Polyline& line : lines)
        for (glm::vec2& p : line.points)
            p.x += shift;
    return lines;
}

// Each polyline as one antialiased path in `pen`.
void strokePaths(QPainter& painter, const std::vector<render::Polyline>& lines, const QPen& pen) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setPen(pen);
    painter.setBrush(Qt::NoBrush);
    for (const render::Polyline& line : lines) {
        if (line.points.size() < 2)
            continue;
        QPainterPath path(QPointF(line.points[0].x, line.points[0].y));
        for (std::size_t i = 1; i < line.points.size(); ++i)
            path.lineTo(line.points[i].x, line.points[i].y);
        if (line.closed)
            path.closeSubpath();
        painter.drawPath(path);
    }
    painter.restore();
}

} // namespace

std::vector<QImage> panelsOf(const RenderedPanels& panels, PanelLayout layout) {
    switch (layout) {
    case PanelLayout::SideBySide:
        return {panels.iso, silhouetteBase(panels)};
    case PanelLayout::IsoPanel:
        return {panels.iso};
    case PanelLayout::SilhouettePanel:
        return {silhouetteBase(panels)};
    }
    return {};
}

std::vector<render::Polyline> pictureLines(const RenderedPanels& panels, PanelLayout layout) {
    return placedLines(panels.silhouetteLines, panels, layout);
}

std::vector<render::Polyline> pictureHiddenLines(const RenderedPanels& panels, PanelLayout layout) {
    return placedLines(panels.hiddenLines, panels, layout);
}

void strokeLines(QPainter& painter, const std::vector<render::Polyline>& lines, double width,
                 QColor colour) {
    QPen pen(colour, width);
    pen.setCapStyle(Qt::RoundCap);
    pen.setJoinStyle(Qt::RoundJoin);
    strokePaths(painter, lines, pen);
}

void strokeHiddenLines(QPainter& painter, const std::vector<render::Polyline>& lines,
                       double visibleWidth) {
    const double width = visibleWidth * render::kHiddenLineWidthFactor;
    QPen pen(QColor(render::kHiddenLineColour), width);
    pen.setCapStyle(Qt::FlatCap);
    // Qt measures a dash pattern in pen widths; the style measures it in visible widths.
    pen.setDashPattern({render::kHiddenDashWidths / render::kHiddenLineWidthFactor,
                        render::kHiddenGapWidths / render::kHiddenLineWidthFactor});
    strokePaths(painter, lines, pen);
}

QImage sideBySide(const std::vector<QImage>& images, QColor background) {
    int width = 0, height = 0;
    for (const QImage& image : images) {
        width += image.width();
        height = std::max(height, image.height());
    }
    QImage result(width, height, QImage::Format_RGB32);
    result.fill(background);
    QPainter painter(&result);
    int x = 0;
    for (const QImage& image : images) {
        painter.drawImage(x, 0, image);
        x += image.width();
    }
    return result;
}

QImage composeExportImage(const RenderedPanels& panels,
                          const std::vector<annotation::Annotation>& annotations,
                          PanelLayout layout, QColor background, const OverlayStyle& style,
                          SilhouetteLines lines) {
    std::vector<QImage> annotated = panelsOf(panels, layout);
    if (lines == SilhouetteLines::Stroked && layout != PanelLayout::IsoPanel &&
        !panels.silhouetteLines.empty()) {
        // The silhouette panel (the last one) is blank: its lines go on as antialiased strokes.
        QImage& silhouette = annotated.back();
        silhouette = silhouette.convertToFormat(QImage::Format_ARGB32_Premultiplied);
        QPainter painter(&silhouette);
        strokeHiddenLines(painter, panels.hiddenLines, panels.silhouetteLineWidth);
        strokeLines(painter, panels.silhouetteLines, panels.silhouetteLineWidth,
                    panels.silhouetteLineColour);
    }
    for (QImage& panel : annotated) {
        panel = panel.convertToFormat(QImage::Format_ARGB32_Premultiplied);
        burnInAnnotations(panel, annotations, panels.camera, style);
    }
    return sideBySide(annotated, background);
}

} // namespace lw::report
