#pragma once

// Internal to lw::dicom: the recursive folder walk of a folder scan.

#include "lw/core/progress.h"
#include "lw/dicom/dicom_scanner.h"

#include <filesystem>
#include <set>
#include <vector>

namespace lw::dicom::detail {

struct WalkState {
    std::vector<std::filesystem::path> files;
    std::vector<FileError> errors;
    std::set<std::filesystem::path> visitedDirs; // canonical: guards against symlink loops
    core::Progress* progress = nullptr;
};

// Collects the regular files below `dir` (links followed, each folder once), in sorted folder
// order; unreadable folders and dangling links become errors.
void walkFolder(const std::filesystem::path& dir, WalkState& state);

} // namespace lw::dicom::detail
