#pragma once

// The drawing of an annotation as plain shapes in panel pixels: segments, filled triangles (arrow
// heads), arcs (angles) and captions. One geometry for both outputs: QPainter burns it into the
// rasters (annotation_overlay.cpp), the SVG writes it as vector elements (svg_export.cpp).

#include "lw/annotation/annotation_projection.h"

#include <array>
#include <glm/glm.hpp>
#include <string>
#include <vector>

namespace lw::report {

struct OverlayShapes {
    struct Segment {
        glm::dvec2 a, b;
    };
    // Angles in degrees counter-clockwise as seen on the screen, 0 at three o'clock (Qt's
    // drawArc convention); the point at angle t is centre + radius * (cos t, -sin t).
    struct Arc {
        glm::dvec2 centre;
        double radius = 0.0;
        double startDeg = 0.0;
        double spanDeg = 0.0;
    };
    // Text whose left baseline is at `baseline`.
    struct Caption {
        glm::dvec2 baseline;
        std::string text;
    };
    std::vector<Segment> segments;
    std::vector<std::array<glm::dvec2, 3>> triangles;
    std::vector<Arc> arcs;
    std::vector<Caption> captions;
};

// The shapes of one projected annotation; `scale` multiplies every size (overlayScale()).
OverlayShapes overlayShapes(const annotation::ProjectedAnnotation& projected, double scale);

} // namespace lw::report
