#pragma once

// SVG export. The engine does not hand out the visible silhouette as polylines yet (the line
// quality issue adds them), so the panels go in as one embedded PNG raster; the annotations are
// real vector elements over it (lines, arrow heads, arcs, text), editable in a drawing program.

#include "lw/annotation/annotation.h"
#include "lw/report/export_image.h"

#include <QByteArray>
#include <vector>

namespace lw::report {

QByteArray renderSvg(const RenderedPanels& panels,
                     const std::vector<annotation::Annotation>& annotations, PanelLayout layout,
                     QColor background = Qt::white, const OverlayStyle& style = {});

} // namespace lw::report
