#pragma once

// Where an annotation falls in a panel: its anchors projected through the panel's render
// Camera, so it can be drawn over (burned into) an image rendered with that camera.

#include "lw/annotation/annotation.h"
#include "lw/render/camera.h"

#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lw::annotation {

struct ProjectedAnnotation {
    AnnotationKind kind = AnnotationKind::Label;
    // The anchors in continuous pixel coordinates of the camera's viewport (x right, y down).
    std::vector<glm::dvec2> points;
    // False when an anchor lies behind the eye (perspective): its pixel position means nothing
    // and the annotation is not drawn.
    bool inFront = true;
    std::string text;        // the label or caption
    std::string measurement; // measurementText(): "42.3 mm", "87.5°" or empty
};

ProjectedAnnotation projectAnnotation(const Annotation& annotation, const render::Camera& camera);

} // namespace lw::annotation
