#pragma once

// Annotations of a review, anchored in patient coordinates (LPS, mm) so they follow the camera
// and mean the same in every panel, export and session. Measurements are computed from the
// anchors, never stored: moving an anchor cannot leave a stale number behind.

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lw::annotation {

enum class AnnotationKind {
    Label, // one anchor: the text is drawn there
    Arrow, // two anchors: tail, head (the head points at the finding); optional text at the tail
    Ruler, // two anchors: the distance between them in mm
    Angle, // three anchors: arm end, vertex, arm end; the angle at the vertex in degrees
};

struct Annotation {
    AnnotationKind kind = AnnotationKind::Label;
    std::vector<glm::dvec3> anchors; // patient coordinates (LPS, mm), anchorCount(kind) of them
    std::string text;                // the label's text; a caption for the other kinds (UTF-8)
};

// How many anchors each kind has.
int anchorCount(AnnotationKind kind);
// "label", "arrow", "ruler", "angle": the names in the JSON files and the report.
const char* kindName(AnnotationKind kind);
std::optional<AnnotationKind> parseKind(std::string_view name);

// Throws core::Error(subject, reason) when the anchors do not fit the kind, an anchor is not
// finite, or a label has no text.
void validate(const Annotation& annotation, const std::string& subject);

// The ruler's length in mm (distance between its two anchors).
double rulerLengthMm(const Annotation& ruler);
// The angle at the vertex (the second anchor) in degrees, 0..180; 0 when an arm has no length.
double angleDegrees(const Annotation& angle);

// The measurement as a report shows it: "42.3 mm" for a ruler, "87.5°" for an angle (one
// decimal, UTF-8 degree sign), empty for labels and arrows.
std::string measurementText(const Annotation& annotation);

} // namespace lw::annotation
