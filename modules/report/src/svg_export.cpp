#include "lw/report/svg_export.h"

#include "lw/annotation/annotation_projection.h"
#include "lw/report/export_files.h"

#include <QString>
#include <cmath>

namespace lw::report {
namespace {

using annotation::AnnotationKind;
using annotation::ProjectedAnnotation;

QString number(double value) {
    return QString::number(value, 'f', 2);
}

QString line(glm::dvec2 a, glm::dvec2 b) {
    return QString("<line x1=\"%1\" y1=\"%2\" x2=\"%3\" y2=\"%4\"/>\n")
        .arg(number(a.x), number(a.y), number(b.x), number(b.y));
}

QString textAt(glm::dvec2 at, const std::string& caption, double fontSize) {
    if (caption.empty())
        return {};
    return QString("<text x=\"%1\" y=\"%2\" font-size=\"%3\" stroke=\"none\">%4</text>\n")
        .arg(number(at.x), number(at.y), number(fontSize),
             QString::fromStdString(caption).toHtmlEscaped());
}

std::string captionOf(const ProjectedAnnotation& projected) {
    if (projected.text.empty())
        return projected.measurement;
    return projected.measurement.empty() ? projected.text
                                         : projected.text + " " + projected.measurement;
}

glm::dvec2 unitPerpendicular(glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 d = b - a;
    const double length = glm::length(d);
    return length > 0.0 ? glm::dvec2(-d.y, d.x) / length : glm::dvec2(0.0, -1.0);
}

// One annotation's elements, in panel pixels (the caller's group moves them to the panel).
QString annotationElements(const ProjectedAnnotation& p, double scale, double fontSize) {
    const std::string caption = captionOf(p);
    const auto& pts = p.points;
    QString out;
    switch (p.kind) {
    case AnnotationKind::Label: {
        const double r = 4.0 * scale;
        out += line(pts[0] - glm::dvec2(r, 0), pts[0] + glm::dvec2(r, 0));
        out += line(pts[0] - glm::dvec2(0, r), pts[0] + glm::dvec2(0, r));
        out += textAt(pts[0] + glm::dvec2(2.0 * r, -r), caption, fontSize);
        break;
    }
    case AnnotationKind::Arrow: {
        out += line(pts[0], pts[1]);
        const glm::dvec2 side = unitPerpendicular(pts[0], pts[1]);
        const glm::dvec2 back(side.y, -side.x);
        const glm::dvec2 left = pts[1] + back * (14.0 * scale) + side * (5.0 * scale);
        const glm::dvec2 right = pts[1] + back * (14.0 * scale) - side * (5.0 * scale);
        out += QString("<polygon points=\"%1,%2 %3,%4 %5,%6\" stroke=\"none\"/>\n")
                   .arg(number(pts[1].x), number(pts[1].y), number(left.x), number(left.y),
                        number(right.x), number(right.y));
        out += textAt(pts[0] + glm::dvec2(4.0 * scale, -4.0 * scale), caption, fontSize);
        break;
    }
    case AnnotationKind::Ruler: {
        out += line(pts[0], pts[1]);
        const glm::dvec2 tick = unitPerpendicular(pts[0], pts[1]) * (6.0 * scale);
        out += line(pts[0] - tick, pts[0] + tick) + line(pts[1] - tick, pts[1] + tick);
        out += textAt((pts[0] + pts[1]) / 2.0 + glm::dvec2(6.0 * scale, -6.0 * scale), caption,
                      fontSize);
        break;
    }
    case AnnotationKind::Angle:
        out += line(pts[1], pts[0]) + line(pts[1], pts[2]);
        out += textAt(pts[1] + glm::dvec2(22.0 * scale, 4.0 * scale), caption, fontSize);
        break;
    }
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
    const QString colour = style.colour.name();
    int x = 0;
    for (const QImage& panel : images) {
        svg += QString("<g transform=\"translate(%1,0)\" stroke=\"%2\" fill=\"%2\" "
                       "stroke-width=\"%3\" stroke-linecap=\"round\" "
                       "font-family=\"DejaVu Sans, sans-serif\">\n")
                   .arg(x)
                   .arg(colour, number(style.lineWidth * scale));
        for (const annotation::Annotation& item : annotations) {
            const ProjectedAnnotation projected =
                annotation::projectAnnotation(item, panels.camera);
            if (projected.inFront)
                svg += annotationElements(projected, scale, fontSize);
        }
        svg += "</g>\n";
        x += panel.width();
    }
    svg += "</svg>\n";
    return svg.toUtf8();
}

} // namespace lw::report
