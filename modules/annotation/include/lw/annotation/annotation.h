#pragma once

// Annotations of a review, anchored in patient coordinates (LPS, mm) so they follow the camera
// and mean the same in every panel, export and session. Measurements are computed from the
// anchors, never stored: moving an anchor cannot leave a stale number behind.
//
// An annotation is placed either in 3D (on the iso-surface, through a 3D panel) or on a slice
// (an axial, coronal or sagittal plane; its anchors lie in that plane). Where each one shows:
//
//                        3D panels (iso, silhouette)    a slice (orientation o, position s,
//                                                       spacing d)
//   placed in 3D         always (as before slices)      when every anchor lies in the slab
//                                                       s - d/2 <= position < s + d/2
//   placed on a slice    always: its anchors are        when o is its plane's orientation and
//                        patient points like any other  every anchor lies in that slab
//
// The slab is half-open, so a point exactly between two slices shows on one of them (the one
// further along the normal), never on both. A 3D annotation whose anchors span several slices
// (a ruler from the skull's top to its base) shows on none: drawn on one slice it would look
// shorter than the length it reports.

#include "lw/volume/slice_plane.h"

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

// The orthogonal planes of the patient's LPS frame, as the slice views have them
// (lw/volume/slice_plane.h): "axial", "coronal", "sagittal" in the JSON files and the report.
using volume::parseSliceOrientation;
using volume::SliceOrientation;
using volume::sliceOrientationName;

// A slice position is a patient coordinate along the plane's normal:
//
//   axial     z (mm), + superior      (the plane's normal is +z)
//   coronal   y (mm), + posterior     (+y)
//   sagittal  x (mm), + left          (+x)
//
// as lw::volume::SliceGeometry::positionOf measures it.
double slicePositionOf(SliceOrientation orientation, const glm::dvec3& patient);

// The slice an annotation was placed on.
struct SlicePlacement {
    SliceOrientation orientation = SliceOrientation::Axial;
    double positionMm = 0.0; // the plane's slicePositionOf
    double spacingMm = 1.0;  // the distance between the view's slices there (> 0): its anchors
                             // lie within half of it from the plane
};

struct Annotation {
    AnnotationKind kind = AnnotationKind::Label;
    std::vector<glm::dvec3> anchors;     // patient coordinates (LPS, mm), anchorCount(kind) of them
    std::string text;                    // the label's text; a caption for the other kinds (UTF-8)
    std::optional<SlicePlacement> slice; // set when placed on a slice, empty when placed in 3D
};

// How many anchors each kind has.
int anchorCount(AnnotationKind kind);
// "label", "arrow", "ruler", "angle": the names in the JSON files and the report.
const char* kindName(AnnotationKind kind);
std::optional<AnnotationKind> parseKind(std::string_view name);

// The point moved along the plane's normal onto the slice: where an anchor of an annotation
// placed on that slice goes when it is dragged in a 3D panel, so it stays on its plane (validate
// refuses anchors further than half the spacing from it).
glm::dvec3 pointOnSlice(const SlicePlacement& slice, glm::dvec3 patient);

// Throws core::Error(subject, reason) when the anchors do not fit the kind, an anchor is not
// finite, a label has no text, or a slice placement has a position that is not finite, a
// spacing that is not positive, or an anchor further than half its spacing from its plane.
void validate(const Annotation& annotation, const std::string& subject);

// Whether the annotation is drawn on the slice of `orientation` at `positionMm` in a view whose
// slices are `spacingMm` apart (the table at the top of this file).
bool showsOnSlice(const Annotation& annotation, SliceOrientation orientation, double positionMm,
                  double spacingMm);

// The ruler's length in mm (distance between its two anchors).
double rulerLengthMm(const Annotation& ruler);
// The angle at the vertex (the second anchor) in degrees, 0..180; 0 when an arm has no length.
double angleDegrees(const Annotation& angle);

// The slice an annotation was placed on as a report names it: "axial 118.5 mm" (the position
// with one decimal); empty for an annotation placed in 3D.
std::string placementText(const Annotation& annotation);

// The measurement as a report shows it: "42.3 mm" for a ruler, "87.5°" for an angle (one
// decimal, UTF-8 degree sign), empty for labels and arrows. On a slice the plane follows after a
// middle dot: "42.3 mm · axial 118.5 mm", and a label or an arrow reports its plane alone
// ("axial 118.5 mm"), so every annotation of a report says where it was placed.
std::string measurementText(const Annotation& annotation);

} // namespace lw::annotation
