#include "lw/report/export_image.h"

#include "lw/core/parallel.h"
#include "lw/render/svg_lines.h"

#include <QPainter>
#include <QPainterPath>
#include <algorithm>
#include <limits>

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

// The rows a polyline's points span.
struct RowSpan {
    float top = -std::numeric_limits<float>::infinity();
    float bottom = std::numeric_limits<float>::infinity();
    bool meets(const RowSpan& other) const { return top <= other.bottom && other.top <= bottom; }
};

// Each polyline's rows; a polyline without points meets none (top above bottom).
std::vector<RowSpan> rowSpansOf(const std::vector<render::Polyline>& lines) {
    constexpr float kInfinity = std::numeric_limits<float>::infinity();
    std::vector<RowSpan> spans(lines.size(), RowSpan{kInfinity, -kInfinity});
    for (std::size_t i = 0; i < lines.size(); ++i)
        for (const glm::vec2& p : lines[i].points) {
            spans[i].top = std::min(spans[i].top, p.y);
            spans[i].bottom = std::max(spans[i].bottom, p.y);
        }
    return spans;
}

// Each polyline as one antialiased path in `pen`; with `spans`, only those that meet `rows`.
void strokePaths(QPainter& painter, const std::vector<render::Polyline>& lines, const QPen& pen,
                 const std::vector<RowSpan>* spans = nullptr, RowSpan rows = {}) {
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing, true);
    painter.setPen(pen);
    painter.setBrush(Qt::NoBrush);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        const render::Polyline& line = lines[i];
        if (line.points.size() < 2 || (spans && !(*spans)[i].meets(rows)))
            continue;
        QPainterPath path(QPointF(line.points[0].x, line.points[0].y));
        for (std::size_t k = 1; k < line.points.size(); ++k)
            path.lineTo(line.points[k].x, line.points[k].y);
        if (line.closed)
            path.closeSubpath();
        painter.drawPath(path);
    }
    painter.restore();
}

QPen visiblePen(double width, QColor colour) {
    QPen pen(colour, width);
    pen.setCapStyle(Qt::RoundCap);
    pen.setJoinStyle(Qt::RoundJoin);
    return pen;
}

QPen hiddenPen(double visibleWidth) {
    QPen pen(QColor(render::kHiddenLineColour), visibleWidth * render::kHiddenLineWidthFactor);
    pen.setCapStyle(Qt::FlatCap);
    // Qt measures a dash pattern in pen widths; the style measures it in visible widths.
    pen.setDashPattern({render::kHiddenDashWidths / render::kHiddenLineWidthFactor,
                        render::kHiddenGapWidths / render::kHiddenLineWidthFactor});
    return pen;
}

// The silhouette's strokes (hidden ones under the visible) in horizontal bands painted in
// parallel. Each band paints, in the same order, the lines that reach its rows (a margin covers
// the pen's half width, its caps and the antialiasing), into those rows only: QPainter's
// coverage of a pixel depends on the path and the pixel alone, so the picture is the one a
// single painter makes, in a fraction of the time (a 512-cube CT's export strokes hundreds of
// thousands of segments).
void strokeInBands(QImage& image, const RenderedPanels& panels) {
    const int height = image.height();
    const std::size_t bytesPerLine = std::size_t(image.bytesPerLine());
    uchar* const rows = image.bits(); // detached once, before the threads share it
    const std::vector<RowSpan> visibleSpans = rowSpansOf(panels.silhouetteLines);
    const std::vector<RowSpan> hiddenSpans = rowSpansOf(panels.hiddenLines);
    const float margin = float(panels.silhouetteLineWidth) + 2.0f;
    const int bands = std::clamp(height / 64, 1, 64);
    core::parallelFor(std::size_t(bands), [&](std::size_t band) {
        const int top = int(band) * height / bands, bottom = int(band + 1) * height / bands;
        QImage part(rows + std::size_t(top) * bytesPerLine, image.width(), bottom - top,
                    qsizetype(bytesPerLine), image.format());
        QPainter painter(&part);
        painter.translate(0.0, -double(top));
        const RowSpan reach{float(top) - margin, float(bottom) + margin};
        strokePaths(painter, panels.hiddenLines, hiddenPen(panels.silhouetteLineWidth),
                    &hiddenSpans, reach);
        strokePaths(painter, panels.silhouetteLines,
                    visiblePen(panels.silhouetteLineWidth, panels.silhouetteLineColour),
                    &visibleSpans, reach);
    });
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
    strokePaths(painter, lines, visiblePen(width, colour));
}

void strokeHiddenLines(QPainter& painter, const std::vector<render::Polyline>& lines,
                       double visibleWidth) {
    strokePaths(painter, lines, hiddenPen(visibleWidth));
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
        strokeInBands(silhouette, panels);
    }
    for (QImage& panel : annotated) {
        panel = panel.convertToFormat(QImage::Format_ARGB32_Premultiplied);
        burnInAnnotations(panel, annotations, panels.camera, style);
    }
    return sideBySide(annotated, background);
}

} // namespace lw::report
