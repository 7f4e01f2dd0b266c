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
    return hitTestAnnotations(annotations, cameraProjector(camera), pixel, anchorRadius,
                              lineRadius);
}

PanelProjector cameraProjector(const render::Camera& camera) {
    return
        [camera](
            const annotation::Annotation& item) -> std::optional<annotation::ProjectedAnnotation> {
            annotation::ProjectedAnnotation projected = annotation::projectAnnotation(item, camera);
            return projected.inFront ? std::optional(std::move(projected)) : std::nullopt;
        };
}

std::optional<AnnotationHit>
hitTestAnnotations(const std::vector<annotation::Annotation>& annotations,
                   const PanelProjector& project, glm::dvec2 pixel, double anchorRadius,
                   double lineRadius) {
    std::optional<AnnotationHit> nearestAnchor, nearestLine;
    double anchorDistance = std::numeric_limits<double>::infinity();
    double lineDistance = std::numeric_limits<double>::infinity();
    for (int i = 0; i < int(annotations.size()); ++i) {
        const std::optional<annotation::ProjectedAnnotation> shown =
            project(annotations[std::size_t(i)]);
        if (!shown)
            continue;
        const annotation::ProjectedAnnotation& projected = *shown;
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
