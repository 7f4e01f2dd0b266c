#include "shell/slice_export.h"

#include "lw/report/annotation_overlay.h"
#include "lw/report/export_image.h"
#include "review/review_widget.h"
#include "review/slice_view.h"
#include "review/slice_views.h"

#include <QPainter>
#include <algorithm>
#include <cmath>

namespace lw::gui {
namespace {

// Image pixels to panel pixels: fitted and centred, pixel centres at (pixel + 0.5) * scale.
struct Fit {
    double scale = 1.0;
    QPointF origin;
    QPointF map(glm::dvec2 pixel) const {
        return origin + QPointF(pixel.x + 0.5, pixel.y + 0.5) * scale;
    }
};

Fit fitInto(glm::ivec2 imageSize, QSize size) {
    Fit fit;
    fit.scale = std::min(size.width() / double(std::max(imageSize.x, 1)),
                         size.height() / double(std::max(imageSize.y, 1)));
    fit.origin = QPointF(size.width(), size.height()) / 2.0 -
                 QPointF(imageSize.x, imageSize.y) * fit.scale / 2.0;
    return fit;
}

void drawContour(QPainter& painter, const SliceResult& slice, const Fit& fit, QColor colour,
                 double width) {
    QVector<QLineF> lines;
    lines.reserve(qsizetype(slice.contour.size()));
    for (const volume::ContourSegment& segment : slice.contour)
        lines.append(QLineF(fit.map(segment.a), fit.map(segment.b)));
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(colour, width));
    painter.drawLines(lines);
}

} // namespace

QImage renderSlicePanel(const SliceView& view, QSize size,
                        const std::vector<annotation::Annotation>& annotations) {
    QImage panel(size, QImage::Format_RGB32);
    panel.fill(Qt::black);
    const SliceResult* slice = view.slice();
    if (!slice || !slice->image)
        return panel;
    const volume::SliceGeometry& geometry = slice->image->geometry;
    const Fit fit = fitInto(geometry.size, size);
    {
        QPainter painter(&panel);
        const QRectF target(fit.origin, QSizeF(geometry.size.x, geometry.size.y) * fit.scale);
        painter.setRenderHint(QPainter::SmoothPixmapTransform, fit.scale < 1.0);
        painter.drawImage(target, windowedImage(*slice->image, view.windowLevel()));
        drawContour(painter, *slice, fit, view.contourColour(),
                    std::max(1.0, report::overlayScale(size.height()) * 0.75));
    }
    report::SlicePanelFrame frame;
    frame.orientation = view.orientation();
    frame.positionMm = slice->image->position;
    frame.spacingMm = std::abs(view.geometry().step);
    frame.toPixel = [&geometry, fit](const glm::dvec3& patient) {
        const QPointF at = fit.map(geometry.pixelOf(patient));
        return glm::dvec2(at.x(), at.y());
    };
    report::burnInSliceAnnotations(panel, annotations, frame);
    return panel;
}

SlicePanels slicePanelsOf(ReviewWidget& review, QSize panelSize, QSize pictureSize,
                          const std::vector<annotation::Annotation>& annotations) {
    SlicePanels panels;
    const ReviewLayoutChoice choice = review.layoutChoice();
    if (choice.layout == ReviewLayout::SurfacesAndSlices) {
        const int side = std::max(1, pictureSize.width() / 3);
        for (const volume::SliceOrientation orientation :
             {volume::SliceOrientation::Axial, volume::SliceOrientation::Coronal,
              volume::SliceOrientation::Sagittal})
            panels.images.push_back(renderSlicePanel(review.slices().view(orientation),
                                                     QSize(side, side), annotations));
        panels.below = true;
    } else if (choice.layout == ReviewLayout::SilhouetteAndSlice) {
        panels.images.push_back(
            renderSlicePanel(review.slices().view(choice.largeSlice), panelSize, annotations));
    }
    return panels;
}

QImage withSlicePanels(const QImage& picture, const SlicePanels& slices, QColor background) {
    if (slices.images.empty())
        return picture;
    const QImage row = report::sideBySide(slices.images, background);
    if (!slices.below)
        return report::sideBySide({picture, row}, background);
    QImage joined(std::max(picture.width(), row.width()), picture.height() + row.height(),
                  QImage::Format_RGB32);
    joined.fill(background);
    QPainter painter(&joined);
    painter.drawImage(0, 0, picture);
    painter.drawImage(0, picture.height(), row);
    return joined;
}

} // namespace lw::gui
