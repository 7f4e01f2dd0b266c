#pragma once

// Which annotation lies under the mouse in a panel: the anchors and lines projected through the
// panel's camera and measured in its pixels. Plain geometry, no widgets.

#include "lw/annotation/annotation.h"
#include "lw/annotation/annotation_projection.h"
#include "lw/render/camera.h"

#include <functional>
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

// An annotation in the panel's pixels, or nothing when the panel does not show it.
using PanelProjector =
    std::function<std::optional<annotation::ProjectedAnnotation>(const annotation::Annotation&)>;

// A 3D panel's: through its camera, nothing when an anchor lies behind the eye.
PanelProjector cameraProjector(const render::Camera& camera);

// The same for any panel: a slice panel projects the annotations its slice shows.
std::optional<AnnotationHit>
hitTestAnnotations(const std::vector<annotation::Annotation>& annotations,
                   const PanelProjector& project, glm::dvec2 pixel, double anchorRadius,
                   double lineRadius);

// Distance in pixels from `p` to the segment a-b.
double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b);

} // namespace lw::gui
