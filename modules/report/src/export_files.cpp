#include "lw/report/export_files.h"

#include "lw/core/error.h"

#include <QBuffer>

namespace lw::report {

void writeExportFile(const std::filesystem::path& path, const QByteArray& bytes,
                     core::Overwrite overwrite) {
    core::checkStaysInFolder(path);
    core::writeFileAtomically(path, bytes.constData(), std::size_t(bytes.size()), overwrite);
}

QByteArray encodePngBytes(const QImage& image, const std::filesystem::path& path) {
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    // Qt maps quality 80 to zlib level 1: a 4096-pixel-wide export deflates several times faster
    // than at the default level, the file only slightly larger (flat panels compress well).
    if (image.isNull() || !image.save(&buffer, "PNG", 80))
        throw core::Error(path.string(), "the image could not be encoded as PNG");
    return bytes;
}

} // namespace lw::report
