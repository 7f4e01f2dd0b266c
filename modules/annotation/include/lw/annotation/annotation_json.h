#pragma once

// The annotation file (`linework-cli export --annotations FILE.json`, and the study
// database's annotations of a series):
//
//   { "version": 2,
//     "annotations": [
//       { "type": "label", "points": [[x, y, z]], "text": "Lesion" },
//       { "type": "arrow", "points": [[tail], [head]], "text": "optional" },
//       { "type": "ruler", "points": [[x, y, z], [x, y, z]],
//         "slice": { "plane": "axial", "position": 118.5, "spacing": 5 } },
//       { "type": "angle", "points": [[arm end], [vertex], [arm end]] } ] }
//
// Points are patient coordinates (DICOM LPS, mm). Measurements are not stored: they follow from
// the points. "slice" (version 2) marks an annotation placed on a slice: its plane ("axial",
// "coronal", "sagittal"), the plane's position along its normal in mm (z, y or x: see
// slicePositionOf) and the view's slice spacing in mm; without it the annotation was placed in
// 3D. Version 1 files (before slices) are read as 3D annotations; a version-1 file with "slice"
// is refused, as is a version above 2 (a newer Linework's file). Unknown members are refused, so
// a misspelt "text" is not silently dropped.

#include "lw/annotation/annotation.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lw::annotation {

// The version written; versions kOldestAnnotationFileVersion..kAnnotationFileVersion are read.
inline constexpr int kAnnotationFileVersion = 2;
inline constexpr int kOldestAnnotationFileVersion = 1;
// A few hundred bytes an annotation: 16 MiB is tens of thousands of them. A larger file is
// refused before it is read.
inline constexpr std::size_t kMaxAnnotationFileBytes = std::size_t(16) << 20;

// Throws core::Error(subject, reason) naming the place ("annotations[2].points: ...", or the
// line and column of a JSON syntax error).
std::vector<Annotation> parseAnnotationsJson(std::string_view text, const std::string& subject);
// Reads and parses a file of at most kMaxAnnotationFileBytes; errors name the file.
std::vector<Annotation> readAnnotationsFile(const std::filesystem::path& path);
// The file's text for `annotations`, version kAnnotationFileVersion (parseAnnotationsJson
// reads back the same annotations, the coordinates and slice placements to 10 significant
// digits).
std::string annotationsToJson(const std::vector<Annotation>& annotations);

} // namespace lw::annotation
