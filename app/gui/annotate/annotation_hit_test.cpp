#include "annotate/annotation_hit_test.h"

#include "lw/annotation/annotation_projection.h"

#include <algorithm>
#include <limits>

namespace lw::gui {

double distanceToSegment(glm::dvec2 p, glm::dvec2 a, glm::dvec2 b) {
    const glm::dvec2 d = b - a;
    const double lengthSquared = glm::dot(d, d);
    const double t =
        lengthSquared > 0.0 ? std::clamp(glm::dot(p - a, d) / lengthSquared, 0.0, 1.0) : 0.0;
    return glm::distance(p, a + t * d);
}

namespace {

// The lines that can be grabbed, as pairs of anchor indexes.
std::vector<std::pair<int, int>> linesOf(annotation::AnnotationKind kind) {
    switch (kind) {
    case annotation::AnnotationKind::Label:
        return {};
    case annotation::AnnotationKind::Arrow:
    case annotation::AnnotationKind::Ruler:
        return {{0, 1}};
    case annotation::AnnotationKind::Angle:
        return {{1, 0}, {1, 2}};
    }
    return {};
}

} // namespace

std::optional<AnnotationHit>
hitTestAnnotations(const std::vector<annotation::Annotation>& annotations,
                   const render::Camera& camera, glm::dvec2 pixel, double anchorRadius,
                   double lineRadius) {
    std::optional<AnnotationHit> nearestAnchor, nearestLine;
    double anchorDistance = std::numeric_limits<double>::infinity();
    double lineDistance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < int(annotations.size()); ++i) {
        const annotation::ProjectedAnnotation projected =
            annotation::projectAnnotation(annotations[std::size_t(i)], camera);
        if (!projected.inFront)
            continue;
        const auto& points = projected.points;
        for (int a = 0; a < int(points.size()); ++a) {
            const double distance = glm::distance(pixel, points[std::size_t(a)]);
            if (distance <= anchorRadius && distance < anchorDistance) {
                anchorDistance = distance;
                nearestAnchor = AnnotationHit{i, a};
            }
        }
        for (const auto& [from, to] : linesOf(projected.kind)) {
            const double distance =
                distanceToSegment(pixel, points[std::size_t(from)], points[std::size_t(to)]);
            if (distance <= lineRadius && distance < lineDistance) {
                lineDistance = distance;
                nearestLine = AnnotationHit{i, -1};
            }
        }
    }
    return nearestAnchor ? nearestAnchor : nearestLine;
}

} // namespace lw::gui
