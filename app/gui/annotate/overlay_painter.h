#pragma once

// What the review's panels draw over their picture for the annotations: each annotation as the
// export burns it in (report::drawAnnotation, the same shapes, at screen size), the selected
// one in the highlight colour with its anchors as handles to drag, and the annotation being
// placed or dragged as it would come out.

#include "annotate/annotation_hit_test.h"
#include "lw/annotation/annotation.h"
#include "lw/render/camera.h"
#include "lw/report/annotation_overlay.h"

#include <QPainter>
#include <optional>
#include <vector>

namespace lw::gui {

struct OverlayScene {
    const std::vector<annotation::Annotation>* annotations = nullptr;
    int selected = -1;
    // Drawn instead of annotation `previewReplaces` (-1: in addition to the rest): an anchor being
    // dragged, or the annotation being placed with its last anchor under the mouse.
    std::optional<annotation::Annotation> preview;
    int previewReplaces = -1;
    // A placement with more anchors to come: a dashed line from the last one to the mouse.
    std::optional<std::pair<glm::dvec3, glm::dvec3>> rubberBand;
};

// `scale`: device pixels per reference pixel (the screen's pixel ratio).
void paintOverlay(QPainter& painter, const render::Camera& camera, const OverlayScene& scene,
                  double scale);

// The same over a slice panel, in its widget's pixels: the annotations its slice shows
// (annotation::showsOnSlice), drawn as the slice export burns them in.
void paintOverlay(QPainter& painter, const report::SlicePanelFrame& slice,
                  const OverlayScene& scene, double scale);

// The annotations a slice panel shows, in its pixels (for drawing and hit testing there).
PanelProjector sliceProjector(const report::SlicePanelFrame& slice);

} // namespace lw::gui
