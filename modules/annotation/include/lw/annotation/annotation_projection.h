#pragma once

// Where an annotation falls in a panel: its anchors projected through the panel's render
// Camera, so it can be drawn over (burned into) an image rendered with that camera, or through a
// slice panel's mapping of patient points to its pixels.

#include "lw/annotation/annotation.h"
#include "lw/render/camera.h"

#include <functional>
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

// A panel's pixel (continuous, x right, y down) for a patient point (LPS, mm).
using PatientToPixel = std::function<glm::dvec2(const glm::dvec3& patient)>;

// The anchors through `toPixel`: a slice panel's lw::volume::SliceGeometry::pixelOf followed by
// its zoom and pan. Nothing is behind an eye there (inFront is true); which annotations a slice
// shows is showsOnSlice's to say, before projecting.
ProjectedAnnotation projectAnnotation(const Annotation& annotation, const PatientToPixel& toPixel);

} // namespace lw::annotation
