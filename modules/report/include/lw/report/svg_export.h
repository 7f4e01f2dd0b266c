#pragma once

// SVG export. The iso panel goes in as an embedded PNG raster; the silhouette as vector paths
// when the panels carry its visible polylines (RenderedPanels::silhouetteLines), otherwise as
// part of the raster; the annotations are real vector elements over it (lines, arrow heads,
// arcs, text), editable in a drawing program.

#include "lw/annotation/annotation.h"
#include "lw/report/export_image.h"

#include <QByteArray>
#include <vector>

namespace lw::report {

QByteArray renderSvg(const RenderedPanels& panels,
                     const std::vector<annotation::Annotation>& annotations, PanelLayout layout,
                     QColor background = Qt::white, const OverlayStyle& style = {});

} // namespace lw::report
