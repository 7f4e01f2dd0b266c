#pragma once

// Internal to lw::dicom: the path rules the folder walk, the DICOMDIR reader and the scanner
// share (names, containment, "is this a DICOMDIR").

#include <filesystem>
#include <string>

namespace lw::dicom::detail {

std::string lower(std::string text);
// Leading and trailing blanks (space, tab, CR, LF) removed; DICOMDIR values are space-padded.
std::string trimBlanks(std::string text);

bool isNamedDicomdir(const std::filesystem::path& path);

// Canonical where possible so that the same folder reached twice (symlinks) is recognised.
std::filesystem::path canonicalOrAbsolute(const std::filesystem::path& path);

// isDicomdirFile opens the file; on the error paths of a scan any failure means "no".
bool safeIsDicomdir(const std::filesystem::path& path) noexcept;

// `child` lies below `root` (both lexical: canonicalise first where links matter).
bool isInside(const std::filesystem::path& child, const std::filesystem::path& root);

// The Part 10 "DICM" marker after the 128-byte preamble.
bool hasDicmMagic(const std::filesystem::path& path);

} // namespace lw::dicom::detail
