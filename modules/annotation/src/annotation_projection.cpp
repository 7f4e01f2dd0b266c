#include "lw/annotation/annotation_projection.h"

namespace lw::annotation {

namespace {

ProjectedAnnotation withoutPoints(const Annotation& annotation) {
    ProjectedAnnotation projected;
    projected.kind = annotation.kind;
    projected.text = annotation.text;
    projected.measurement = measurementText(annotation);
    return projected;
}

} // namespace

ProjectedAnnotation projectAnnotation(const Annotation& annotation, const render::Camera& camera) {
    ProjectedAnnotation projected = withoutPoints(annotation);
    for (const glm::dvec3& anchor : annotation.anchors) {
        const render::ProjectedPoint point = camera.project(anchor);
        projected.points.push_back(point.pixel);
        if (!camera.isOrthographic() && point.depth <= 0.0)
            projected.inFront = false;
    }
    return projected;
}

ProjectedAnnotation projectAnnotation(const Annotation& annotation, const PatientToPixel& toPixel) {
    ProjectedAnnotation projected = withoutPoints(annotation);
    for (const glm::dvec3& anchor : annotation.anchors)
        projected.points.push_back(toPixel(anchor));
    return projected;
}

} // namespace lw::annotation
