#include "lw/core/image_compare.h"

#include "lw/core/png_io.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace lw::core {

namespace {

int channelDifference(Rgba8 a, Rgba8 b) {
    return std::max({std::abs(int(a.r) - int(b.r)), std::abs(int(a.g) - int(b.g)),
                     std::abs(int(a.b) - int(b.b)), std::abs(int(a.a) - int(b.a))});
}

} // namespace

std::string ImageComparison::describe() const {
    std::ostringstream out;
    out << (matches ? "images match" : "images differ");
    if (!sizesMatch)
        out << " (sizes differ)";
    out << ": " << badPixels << " of " << pixelCount
        << " pixels over tolerance, max channel difference " << maxChannelDifference;
    if (diffWritten)
        out << "; diff image: " << diffPath.string();
    return out.str();
}

ImageComparison compareImages(const ImageRgba8& actual, const ImageRgba8& expected,
                              ImageTolerance tolerance) {
    ImageComparison result;
    result.sizesMatch = actual.width() == expected.width() && actual.height() == expected.height();
    const int width = std::max(actual.width(), expected.width());
    const int height = std::max(actual.height(), expected.height());
    result.pixelCount = std::size_t(width) * std::size_t(height);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (!actual.contains(x, y) || !expected.contains(x, y)) {
                ++result.badPixels;
                result.maxChannelDifference = 255;
                continue;
            }
            const int d = channelDifference(actual.at(x, y), expected.at(x, y));
            result.maxChannelDifference = std::max(result.maxChannelDifference, d);
            if (d > tolerance.channelTolerance)
                ++result.badPixels;
        }
    }
    result.matches = result.sizesMatch && result.badPixels <= tolerance.maxBadPixels;
    return result;
}

ImageRgba8 diffImage(const ImageRgba8& actual, const ImageRgba8& expected,
                     ImageTolerance tolerance) {
    const int width = std::max(actual.width(), expected.width());
    const int height = std::max(actual.height(), expected.height());
    ImageRgba8 out(width, height, {0, 0, 0, 255});
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            if (!actual.contains(x, y) || !expected.contains(x, y)) {
                out.at(x, y) = {255, 0, 255, 255};
                continue;
            }
            const Rgba8 e = expected.at(x, y);
            const int d = channelDifference(actual.at(x, y), e);
            if (d > tolerance.channelTolerance) {
                out.at(x, y) = {255, 0, 0, 255};
            } else if (d > 0) {
                out.at(x, y) = {255, 255, 0, 255};
            } else {
                const auto grey =
                    static_cast<std::uint8_t>(32 + (int(e.r) + int(e.g) + int(e.b)) / 12);
                out.at(x, y) = {grey, grey, grey, 255};
            }
        }
    }
    return out;
}

ImageComparison compareImages(const ImageRgba8& actual, const ImageRgba8& expected,
                              ImageTolerance tolerance, const std::filesystem::path& diffPath) {
    ImageComparison result = compareImages(actual, expected, tolerance);
    if (!result.matches && !diffPath.empty()) {
        writePng(diffPath, diffImage(actual, expected, tolerance), PngFormat::Rgb);
        result.diffWritten = true;
        result.diffPath = diffPath;
    }
    return result;
}

ImageComparison compareWithBaseline(const ImageRgba8& actual,
                                    const std::filesystem::path& baselinePng,
                                    ImageTolerance tolerance,
                                    const std::filesystem::path& diffPath) {
    const ImageRgba8 expected = readPng(baselinePng);
    ImageComparison result = compareImages(actual, expected, tolerance, diffPath);
    if (result.diffWritten && !actual.isEmpty()) {
        auto actualPath = diffPath;
        actualPath.replace_filename(diffPath.stem().string() + ".actual.png");
        writePng(actualPath, actual, PngFormat::Rgba);
    }
    return result;
}

} // namespace lw::core
