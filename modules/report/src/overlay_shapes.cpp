#include "overlay_shapes.h"

#include <cmath>

namespace lw::report {
namespace {

using annotation::AnnotationKind;
using annotation::ProjectedAnnotation;

// Reference-pixel sizes (multiplied by the scale).
constexpr double kCrossArm = 4.0;
constexpr double kArrowLength = 14.0;
constexpr double kArrowHalfWidth = 5.0;
constexpr double kRulerTick = 6.0;
constexpr double kAngleRadius = 18.0;

std::string captionOf(const ProjectedAnnotation& projected) {
    if (projected.text.empty())
        return projected.measurement;
    return projected.measurement.empty() ? projected.text
                                         : projected.text + " " + projected.measurement;
}

// A unit vector perpendicular to a -> b (screen up when they coincide).
glm::dvec2 perpendicular(glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 d = b - a;
    const double length = glm::length(d);
    return length > 0.0 ? glm::dvec2(-d.y, d.x) / length : glm::dvec2(0.0, -1.0);
}

// Screen angle of the direction from `from` to `to` (counter-clockwise on screen, y down).
double screenAngleDeg(glm::dvec2 from, glm::dvec2 to) {
    return glm::degrees(std::atan2(-(to.y - from.y), to.x - from.x));
}

void addLabel(OverlayShapes& shapes, glm::dvec2 at, double scale) {
    const double r = kCrossArm * scale;
    shapes.segments.push_back({at - glm::dvec2(r, 0), at + glm::dvec2(r, 0)});
    shapes.segments.push_back({at - glm::dvec2(0, r), at + glm::dvec2(0, r)});
}

void addArrow(OverlayShapes& shapes, glm::dvec2 tail, glm::dvec2 head, double scale) {
    shapes.segments.push_back({tail, head});
    const glm::dvec2 side = perpendicular(tail, head);
    const glm::dvec2 back(side.y, -side.x); // unit, from the head toward the tail
    const glm::dvec2 base = head + back * (kArrowLength * scale);
    shapes.triangles.push_back(
        {head, base + side * (kArrowHalfWidth * scale), base - side * (kArrowHalfWidth * scale)});
}

void addRuler(OverlayShapes& shapes, glm::dvec2 a, glm::dvec2 b, double scale) {
    shapes.segments.push_back({a, b});
    const glm::dvec2 tick = perpendicular(a, b) * (kRulerTick * scale);
    shapes.segments.push_back({a - tick, a + tick});
    shapes.segments.push_back({b - tick, b + tick});
}

void addAngle(OverlayShapes& shapes, glm::dvec2 a, glm::dvec2 vertex, glm::dvec2 b, double scale) {
    shapes.segments.push_back({vertex, a});
    shapes.segments.push_back({vertex, b});
    const double start = screenAngleDeg(vertex, a);
    const double span = std::remainder(screenAngleDeg(vertex, b) - start, 360.0);
    shapes.arcs.push_back({vertex, kAngleRadius * scale, start, span});
}

} // namespace

OverlayShapes overlayShapes(const ProjectedAnnotation& projected, double scale) {
    OverlayShapes shapes;
    const auto& p = projected.points;
    glm::dvec2 captionAt{0.0};
    switch (projected.kind) {
    case AnnotationKind::Label:
        addLabel(shapes, p[0], scale);
        captionAt = p[0] + glm::dvec2(2.0 * kCrossArm, -kCrossArm) * scale;
        break;
    case AnnotationKind::Arrow:
        addArrow(shapes, p[0], p[1], scale);
        captionAt = p[0] + glm::dvec2(4.0, -4.0) * scale;
        break;
    case AnnotationKind::Ruler:
        addRuler(shapes, p[0], p[1], scale);
        captionAt = (p[0] + p[1]) / 2.0 + glm::dvec2(6.0, -6.0) * scale;
        break;
    case AnnotationKind::Angle:
        addAngle(shapes, p[0], p[1], p[2], scale);
        captionAt = p[1] + glm::dvec2(kAngleRadius + 4.0, 4.0) * scale;
        break;
    }
    const std::string caption = captionOf(projected);
    if (!caption.empty())
        shapes.captions.push_back({captionAt, caption});
    return shapes;
}

} // namespace lw::report
