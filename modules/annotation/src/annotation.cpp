#include "lw/annotation/annotation.h"

#include "lw/core/error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lw::annotation {

int anchorCount(AnnotationKind kind) {
    switch (kind) {
    case AnnotationKind::Label:
        return 1;
    case AnnotationKind::Arrow:
        return 2;
    case AnnotationKind::Ruler:
        return 2;
    case AnnotationKind::Angle:
        return 3;
    }
    return 0;
}

const char* kindName(AnnotationKind kind) {
    switch (kind) {
    case AnnotationKind::Label:
        return "label";
    case AnnotationKind::Arrow:
        return "arrow";
    case AnnotationKind::Ruler:
        return "ruler";
    case AnnotationKind::Angle:
        return "angle";
    }
    return "?";
}

std::optional<AnnotationKind> parseKind(std::string_view name) {
    for (AnnotationKind kind : {AnnotationKind::Label, AnnotationKind::Arrow, AnnotationKind::Ruler,
                                AnnotationKind::Angle})
        if (name == kindName(kind))
            return kind;
    return std::nullopt;
}

double slicePositionOf(SliceOrientation orientation, const glm::dvec3& patient) {
    return glm::dot(volume::sliceAxes(orientation).normal, patient);
}

glm::dvec3 pointOnSlice(const SlicePlacement& slice, glm::dvec3 patient) {
    switch (slice.orientation) {
    case SliceOrientation::Axial:
        patient.z = slice.positionMm;
        break;
    case SliceOrientation::Coronal:
        patient.y = slice.positionMm;
        break;
    case SliceOrientation::Sagittal:
        patient.x = slice.positionMm;
        break;
    }
    return patient;
}

namespace {

void validatePlacement(const Annotation& annotation, const std::string& subject) {
    const SlicePlacement& slice = *annotation.slice;
    if (!std::isfinite(slice.positionMm))
        throw core::Error(subject, "the slice's position is not a finite number");
    if (!(slice.spacingMm > 0.0) || !std::isfinite(slice.spacingMm))
        throw core::Error(subject, "the slice's spacing is not a positive number");
    for (const glm::dvec3& anchor : annotation.anchors) {
        const double offset =
            std::abs(slicePositionOf(slice.orientation, anchor) - slice.positionMm);
        if (offset > 0.5 * slice.spacingMm) {
            char reason[160];
            std::snprintf(reason, sizeof reason,
                          "a point lies %g mm from its %s slice, more than half the spacing",
                          offset, std::string(sliceOrientationName(slice.orientation)).c_str());
            throw core::Error(subject, reason);
        }
    }
}

} // namespace

void validate(const Annotation& annotation, const std::string& subject) {
    const int expected = anchorCount(annotation.kind);
    if (int(annotation.anchors.size()) != expected)
        throw core::Error(subject, std::string("a ") + kindName(annotation.kind) + " needs " +
                                       std::to_string(expected) + " point" +
                                       (expected == 1 ? "" : "s") + ", not " +
                                       std::to_string(annotation.anchors.size()));
    for (const glm::dvec3& anchor : annotation.anchors)
        if (!std::isfinite(anchor.x) || !std::isfinite(anchor.y) || !std::isfinite(anchor.z))
            throw core::Error(subject, "a point is not a finite number");
    if (annotation.kind == AnnotationKind::Label && annotation.text.empty())
        throw core::Error(subject, "a label needs a text");
    if (annotation.slice)
        validatePlacement(annotation, subject);
}

bool showsOnSlice(const Annotation& annotation, SliceOrientation orientation, double positionMm,
                  double spacingMm) {
    if (annotation.slice && annotation.slice->orientation != orientation)
        return false;
    const double low = positionMm - 0.5 * spacingMm;
    const double high = positionMm + 0.5 * spacingMm;
    return std::all_of(annotation.anchors.begin(), annotation.anchors.end(),
                       [&](const glm::dvec3& anchor) {
                           const double position = slicePositionOf(orientation, anchor);
                           return position >= low && position < high;
                       });
}

double rulerLengthMm(const Annotation& ruler) {
    return glm::distance(ruler.anchors.at(0), ruler.anchors.at(1));
}

double angleDegrees(const Annotation& angle) {
    const glm::dvec3 a = angle.anchors.at(0) - angle.anchors.at(1);
    const glm::dvec3 b = angle.anchors.at(2) - angle.anchors.at(1);
    const double lengths = glm::length(a) * glm::length(b);
    if (!(lengths > 0.0))
        return 0.0;
    // atan2 of |a x b| and a . b stays accurate near 0 and 180 degrees, where acos does not.
    return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

std::string placementText(const Annotation& annotation) {
    if (!annotation.slice)
        return {};
    char text[64];
    std::snprintf(text, sizeof text, "%s %.1f mm",
                  std::string(sliceOrientationName(annotation.slice->orientation)).c_str(),
                  annotation.slice->positionMm);
    return text;
}

std::string measurementText(const Annotation& annotation) {
    char text[64] = "";
    if (annotation.kind == AnnotationKind::Ruler)
        std::snprintf(text, sizeof text, "%.1f mm", rulerLengthMm(annotation));
    else if (annotation.kind == AnnotationKind::Angle)
        std::snprintf(text, sizeof text, "%.1f\u00b0", angleDegrees(annotation));
    const std::string measurement = text;
    const std::string placement = placementText(annotation);
    if (placement.empty() || measurement.empty())
        return measurement + placement;
    return measurement + " \u00b7 " + placement; // a middle dot between value and plane
}

} // namespace lw::annotation
