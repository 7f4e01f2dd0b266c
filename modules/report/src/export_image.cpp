#include "lw/report/export_image.h"

#include <QPainter>
#include <algorithm>

namespace lw::report {

std::vector<QImage> panelsOf(const RenderedPanels& panels, PanelLayout layout) {
    switch (layout) {
    case PanelLayout::SideBySide:
        return {panels.iso, panels.silhouette};
    case PanelLayout::IsoPanel:
        return {panels.iso};
    case PanelLayout::SilhouettePanel:
        return {panels.silhouette};
    }
    return {};
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
                          PanelLayout layout, QColor background, const OverlayStyle& style) {
    std::vector<QImage> annotated = panelsOf(panels, layout);
    for (QImage& panel : annotated) {
        panel = panel.convertToFormat(QImage::Format_ARGB32_Premultiplied);
        burnInAnnotations(panel, annotations, panels.camera, style);
    }
    return sideBySide(annotated, background);
}

} // namespace lw::report
