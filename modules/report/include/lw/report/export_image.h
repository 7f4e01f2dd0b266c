#pragma once

// The exported picture: the two panels (rendered again at the export size by the caller, not
// scaled) with the annotations burned into each, laid out side by side or one alone.

#include "lw/annotation/annotation.h"
#include "lw/render/camera.h"
#include "lw/render/visible_polylines.h"
#include "lw/report/annotation_overlay.h"

#include <QColor>
#include <QImage>
#include <QPainter>
#include <vector>

namespace lw::report {

enum class PanelLayout { SideBySide, IsoPanel, SilhouettePanel };

// Both panels of one view, rendered with `camera` (each camera.width() x camera.height()).
struct RenderedPanels {
    QImage iso;
    QImage silhouette;
    render::Camera camera;
    // The silhouette panel's visible lines as vectors (render/visible_polylines.h, panel
    // pixels). When there are any, the exports draw them as paths (SVG, PDF) or antialiased
    // strokes (PNG) of silhouetteLineWidth pixels in silhouetteLineColour instead of the raster
    // panel's lines; empty: the raster panel as it is.
    std::vector<render::Polyline> silhouetteLines;
    double silhouetteLineWidth = 1.0;
    QColor silhouetteLineColour = Qt::black;
    // The silhouette's hidden parts (render::splitPolylines), drawn under the visible lines thin,
    // dashed and grey (render/svg_lines.h's hidden style); empty: none drawn.
    std::vector<render::Polyline> hiddenLines;
};

// The silhouette lines placed in the picture of `layout` (shifted onto the silhouette panel);
// empty when the layout has no silhouette panel or the panels carry no lines.
std::vector<render::Polyline> pictureLines(const RenderedPanels& panels, PanelLayout layout);
// The same for the hidden lines.
std::vector<render::Polyline> pictureHiddenLines(const RenderedPanels& panels, PanelLayout layout);

// Strokes `lines` (picture pixels) onto `painter`, antialiased, `width` pixels wide.
void strokeLines(QPainter& painter, const std::vector<render::Polyline>& lines, double width,
                 QColor colour);
// Strokes hidden lines in the hidden style for visible lines `visibleWidth` pixels wide.
void strokeHiddenLines(QPainter& painter, const std::vector<render::Polyline>& lines,
                       double visibleWidth);

// The panels `layout` shows, left to right (one or two).
std::vector<QImage> panelsOf(const RenderedPanels& panels, PanelLayout layout);

// Whether the silhouette's vector lines go into the picture as pixels (PNG) or are left for the
// caller to draw as vectors over it (PDF: pictureLines()).
enum class SilhouetteLines { Stroked, LeftOut };

// The panels of `layout` with `annotations` burned into each, side by side on `background`.
QImage composeExportImage(const RenderedPanels& panels,
                          const std::vector<annotation::Annotation>& annotations,
                          PanelLayout layout, QColor background = Qt::white,
                          const OverlayStyle& style = {},
                          SilhouetteLines lines = SilhouetteLines::Stroked);

// Images side by side, top-aligned, on `background`.
QImage sideBySide(const std::vector<QImage>& images, QColor background);

} // namespace lw::report
