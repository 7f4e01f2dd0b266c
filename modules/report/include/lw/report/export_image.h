#pragma once

// The exported picture: the two panels (rendered again at the export size by the caller, not
// scaled) with the annotations burned into each, laid out side by side or one alone.

#include "lw/annotation/annotation.h"
#include "lw/render/camera.h"
#include "lw/report/annotation_overlay.h"

#include <QColor>
#include <QImage>
#include <vector>

namespace lw::report {

enum class PanelLayout { SideBySide, IsoPanel, SilhouettePanel };

// Both panels of one view, rendered with `camera` (each camera.width() x camera.height()).
struct RenderedPanels {
    QImage iso;
    QImage silhouette;
    render::Camera camera;
};

// The panels `layout` shows, left to right (one or two).
std::vector<QImage> panelsOf(const RenderedPanels& panels, PanelLayout layout);

// The panels of `layout` with `annotations` burned into each, side by side on `background`.
QImage composeExportImage(const RenderedPanels& panels,
                          const std::vector<annotation::Annotation>& annotations,
                          PanelLayout layout, QColor background = Qt::white,
                          const OverlayStyle& style = {});

// Images side by side, top-aligned, on `background`.
QImage sideBySide(const std::vector<QImage>& images, QColor background);

} // namespace lw::report
