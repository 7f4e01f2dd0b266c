#include "lw/report/svg_export.h"

#include "lw/annotation/annotation_projection.h"
#include "lw/render/svg_lines.h"
#include "lw/report/export_files.h"
#include "overlay_shapes.h"

#include <QString>
#include <cmath>

namespace lw::report {
namespace {

QString number(double value) {
    return QString::number(value, 'f', 2);
}

QString point(glm::dvec2 p) {
    return number(p.x) + "," + number(p.y);
}

// An arc as an SVG path: screen angles counter-clockwise (OverlayShapes::Arc), which is SVG's
// negative sweep direction since its y axis points down.
QString arcPath(const OverlayShapes::Arc& arc) {
    const auto at = [&](double deg) {
        const double t = glm::radians(deg);
        return arc.centre + arc.radius * glm::dvec2(std::cos(t), -std::sin(t));
    };
    return QString("<path fill=\"none\" d=\"M %1 A %2 %2 0 %3 %4 %5\"/>\n")
        .arg(point(at(arc.startDeg)), number(arc.radius))
        .arg(std::abs(arc.spanDeg) > 180.0 ? 1 : 0)
        .arg(arc.spanDeg > 0.0 ? 0 : 1)
        .arg(point(at(arc.startDeg + arc.spanDeg)));
}

// One annotation's elements, in panel pixels (the caller's group moves them to the panel).
QString svgElements(const OverlayShapes& shapes, double fontSize, const OverlayStyle& style) {
    QString out;
    for (const OverlayShapes::Segment& s : shapes.segments)
        out += QString("<line x1=\"%1\" y1=\"%2\" x2=\"%3\" y2=\"%4\"/>\n")
                   .arg(number(s.a.x), number(s.a.y), number(s.b.x), number(s.b.y));
    for (const auto& t : shapes.triangles)
        out += QString("<polygon stroke=\"none\" points=\"%1 %2 %3\"/>\n")
                   .arg(point(t[0]), point(t[1]), point(t[2]));
    for (const OverlayShapes::Arc& arc : shapes.arcs)
        out += arcPath(arc);
    // The halo as a wide stroke painted under the glyphs, like the raster's halo box.
    for (const OverlayShapes::Caption& c : shapes.captions)
        out += QString("<text x=\"%1\" y=\"%2\" font-size=\"%3\" stroke=\"%4\" "
                       "stroke-width=\"%5\" paint-order=\"stroke\">%6</text>\n")
                   .arg(number(c.baseline.x), number(c.baseline.y), number(fontSize),
                        style.halo.name(), number(fontSize * 0.25),
                        QString::fromStdString(c.text).toHtmlEscaped());
    return out;
}

} // namespace

QByteArray renderSvg(const RenderedPanels& panels,
                     const std::vector<annotation::Annotation>& annotations, PanelLayout layout,
                     QColor background, const OverlayStyle& style) {
    const std::vector<QImage> images = panelsOf(panels, layout);
    const QImage raster = sideBySide(images, background);
    const double scale = overlayScale(panels.camera.height(), style);
    const double fontSize = style.fontPixelSize * scale;
    QString svg = QString("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                          "<svg xmlns=\"http://www.w3.org/2000/svg\" "
                          "xmlns:xlink=\"http://www.w3.org/1999/xlink\" "
                          "width=\"%1\" height=\"%2\" viewBox=\"0 0 %1 %2\">\n"
                          "<title>Linework review</title>\n")
                      .arg(raster.width())
                      .arg(raster.height());
    const QByteArray png = encodePngBytes(raster, "SVG raster");
    svg += QString("<image x=\"0\" y=\"0\" width=\"%1\" height=\"%2\" "
                   "xlink:href=\"data:image/png;base64,%3\"/>\n")
               .arg(raster.width())
               .arg(raster.height())
               .arg(QString::fromLatin1(png.toBase64()));
    // The silhouette's vector lines (when the panels carry them) over the embedded raster, whose
    // silhouette panel is then blank (panelsOf).
    const std::vector<render::Polyline> lines = pictureLines(panels, layout);
    if (!lines.empty()) {
        render::SvgLineStyle lineStyle;
        lineStyle.colour = panels.silhouetteLineColour.name().toStdString();
        lineStyle.widthPx = panels.silhouetteLineWidth;
        svg += QString::fromStdString(
            render::silhouettePaths(lines, lineStyle, pictureHiddenLines(panels, layout)));
    }
    const QString colour = style.colour.name();
    int x = 0;
    for (const QImage& panel : images) {
        svg += QString("<g transform=\"translate(%1,0)\" stroke=\"%2\" fill=\"%2\" "
                       "stroke-width=\"%3\" stroke-linecap=\"round\" "
                       "font-family=\"DejaVu Sans, sans-serif\">\n")
                   .arg(x)
                   .arg(colour, number(style.lineWidth * scale));
        for (const annotation::Annotation& item : annotations) {
            const annotation::ProjectedAnnotation projected =
                annotation::projectAnnotation(item, panels.camera);
            if (projected.inFront)
                svg += svgElements(overlayShapes(projected, scale), fontSize, style);
        }
        svg += "</g>\n";
        x += panel.width();
    }
    svg += "</svg>\n";
    return svg.toUtf8();
}

} // namespace lw::report
