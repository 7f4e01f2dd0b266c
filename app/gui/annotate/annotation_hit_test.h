#pragma once

// Which annotation lies under the mouse in a panel: the anchors and lines projected through the
// panel's camera and measured in its pixels. Plain geometry, no widgets.

#include "lw/annotation/annotation.h"
#include "lw/render/camera.h"

#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace lw::gui {

struct AnnotationHit {
    int annotation = -1;
    int anchor = -1; // -1: one of the annotation's lines, not an anchor
};

// The nearest anchor within `anchorRadius` pixels of `pixel` (anchors win over lines, so the ends
// of a short ruler stay draggable), else the nearest line (arrow, ruler, the arms of an angle)
// within `lineRadius`. Annotations with an anchor behind the eye are not hit.
std::optional<AnnotationHit>
hitTestAnnotations(const std::vector<annotation::Annotation>& annotations,
                   const render::Camera& camera, glm::dvec2 pixel, double anchorRadius,
                   double lineRadius);

// Distance in pixels from `p` to the segment a-b.
double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b);

} // namespace lw::gui
