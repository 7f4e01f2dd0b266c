#pragma once

// Writing what an export makes: every file atomically (a temporary sibling renamed into place,
// core::writeFileAtomically), an existing file only when overwriting was asked for, and a failed
// or refused write leaves nothing behind. Errors are core::Error naming the file and the reason.

#include "lw/core/file_util.h"

#include <QByteArray>
#include <QImage>
#include <filesystem>

namespace lw::report {

void writeExportFile(const std::filesystem::path& path, const QByteArray& bytes,
                     core::Overwrite overwrite);

// The image as PNG bytes (Qt's encoder); throws core::Error naming `path` when it fails.
QByteArray encodePngBytes(const QImage& image, const std::filesystem::path& path);

} // namespace lw::report
