#pragma once

// The engine's RGBA8 images (top row first) and Qt's, both ways: one copy of the conversion for
// the GUI's panels and render worker, the exports (GUI and CLI) and the tests.

#include "lw/core/image.h"

#include <QImage>
#include <cstring>

namespace lw::report {

inline QImage toQImage(const core::ImageRgba8& image) {
    QImage result(image.width(), image.height(), QImage::Format_RGBA8888);
    for (int y = 0; y < image.height(); ++y)
        std::memcpy(result.scanLine(y), image.row(y), std::size_t(image.width()) * 4);
    return result;
}

inline core::ImageRgba8 toCoreImage(const QImage& image) {
    const QImage rgba = image.convertToFormat(QImage::Format_RGBA8888);
    core::ImageRgba8 result(rgba.width(), rgba.height());
    for (int y = 0; y < rgba.height(); ++y)
        std::memcpy(result.row(y), rgba.constScanLine(y), std::size_t(rgba.width()) * 4);
    return result;
}

} // namespace lw::report
