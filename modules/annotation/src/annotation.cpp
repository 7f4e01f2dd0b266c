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

std::string measurementText(const Annotation& annotation) {
    char text[64] = "";
    if (annotation.kind == AnnotationKind::Ruler)
        std::snprintf(text, sizeof text, "%.1f mm", rulerLengthMm(annotation));
    else if (annotation.kind == AnnotationKind::Angle)
        std::snprintf(text, sizeof text, "%.1f\u00b0", angleDegrees(annotation));
    return text;
}

} // namespace lw::annotation
