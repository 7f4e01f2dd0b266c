#include "lw/report/export_files.h"

#include "lw/core/error.h"
#include "lw/core/png_io.h"

#include <string>
#include <vector>

namespace lw::report {

void writeExportFile(const std::filesystem::path& path, const QByteArray& bytes,
                     core::Overwrite overwrite) {
    core::checkStaysInFolder(path);
    core::writeFileAtomically(path, bytes.constData(), std::size_t(bytes.size()), overwrite);
}

QByteArray encodePngBytes(const QImage& image, const std::filesystem::path& path) {
    if (image.isNull())
        throw core::Error(path.string(), "the image could not be encoded as PNG: it is empty");
    // An export is opaque: RGB32 rows go to libpng as they are, with the fast settings (one
    // filter, zlib level 1, run-length matching; core/png_io.h). Qt's own writer tries every
    // filter on every row and took 2.3 times as long on a 4096 x 2048 review export.
    const QImage rgb = image.format() == QImage::Format_RGB32
                           ? image
                           : image.convertToFormat(QImage::Format_RGB32);
    try {
        const std::vector<std::byte> png = core::encodePngFastFromBgrx(
            rgb.constBits(), rgb.width(), rgb.height(), std::size_t(rgb.bytesPerLine()));
        return QByteArray(reinterpret_cast<const char*>(png.data()), qsizetype(png.size()));
    } catch (const core::Error& error) {
        throw core::Error(path.string(),
                          std::string("the image could not be encoded as PNG: ") + error.what());
    }
}

} // namespace lw::report
