#pragma once

// The annotation file (`linework-cli export --annotations FILE.json`):
//
//   { "version": 1,
//     "annotations": [
//       { "type": "label", "points": [[x, y, z]], "text": "Lesion" },
//       { "type": "arrow", "points": [[tail], [head]], "text": "optional" },
//       { "type": "ruler", "points": [[x, y, z], [x, y, z]] },
//       { "type": "angle", "points": [[arm end], [vertex], [arm end]] } ] }
//
// Points are patient coordinates (DICOM LPS, mm). Measurements are not stored: they follow from
// the points. Unknown members are refused, so a misspelt "text" is not silently dropped.

#include "lw/annotation/annotation.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lw::annotation {

inline constexpr int kAnnotationFileVersion = 1;
// A few hundred bytes an annotation: 16 MiB is tens of thousands of them. A larger file is
// refused before it is read.
inline constexpr std::size_t kMaxAnnotationFileBytes = std::size_t(16) << 20;

// Throws core::Error(subject, reason) naming the place ("annotations[2].points: ...", or the
// line and column of a JSON syntax error).
std::vector<Annotation> parseAnnotationsJson(std::string_view text, const std::string& subject);
// Reads and parses a file of at most kMaxAnnotationFileBytes; errors name the file.
std::vector<Annotation> readAnnotationsFile(const std::filesystem::path& path);
// The file's text for `annotations` (parseAnnotationsJson reads back the same annotations, the
// coordinates to 10 significant digits).
std::string annotationsToJson(const std::vector<Annotation>& annotations);

} // namespace lw::annotation
