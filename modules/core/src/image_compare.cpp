#include "lw/core/image_compare.h"

#include "lw/core/error.h"
#include "lw/core/png_io.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <sstream>
#include <string_view>

namespace lw::core {

namespace {

int channelDifference(Rgba8 a, Rgba8 b) {
    return std::max({std::abs(int(a.r) - int(b.r)), std::abs(int(a.g) - int(b.g)),
                     std::abs(int(a.b) - int(b.b)), std::abs(int(a.a) - int(b.a))});
}

} // namespace

std::string ImageComparison::describe() const {
    if (baselineMissing)
        return "missing baseline " + baselinePath.string() +
               ": run the test with LINEWORK_UPDATE_BASELINES=1 to write it, look at it, commit it";
    if (baselineWritten)
        return "baseline written: " + baselinePath.string() + " (LINEWORK_UPDATE_BASELINES)";
    std::ostringstream out;
    out << (matches ? "images match" : "images differ");
    if (!sizesMatch)
        out << " (sizes differ)";
    out << ": " << badPixels << " of " << pixelCount
        << " pixels over tolerance, max channel difference " << maxChannelDifference;
    if (expectedContent > 0 || actualContent > 0)
        out << "; content " << actualContent << " pixels against the baseline's "
            << expectedContent;
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

bool updatingBaselines() {
    const char* update = std::getenv("LINEWORK_UPDATE_BASELINES");
    return update && std::string_view(update) == "1";
}

namespace {

// The actual image beside the diff path, as "<diff stem>.actual.png".
void writeActualBeside(const ImageRgba8& actual, const std::filesystem::path& diffPath) {
    if (diffPath.empty() || actual.isEmpty())
        return;
    auto actualPath = diffPath;
    actualPath.replace_filename(diffPath.stem().string() + ".actual.png");
    writePng(actualPath, actual, PngFormat::Rgba);
}

// What the policy does before any comparison: write the baseline, or report it missing.
std::optional<ImageComparison> baselineWrittenOrMissing(const ImageRgba8& actual,
                                                        const std::filesystem::path& baselinePng,
                                                        const std::filesystem::path& diffPath) {
    ImageComparison result;
    result.baselinePath = baselinePng;
    if (updatingBaselines()) {
        if (baselinePng.has_parent_path())
            std::filesystem::create_directories(baselinePng.parent_path());
        writePng(baselinePng, actual, PngFormat::Rgba);
        result.baselineWritten = true;
        result.matches = true;
        return result;
    }
    if (std::filesystem::exists(baselinePng))
        return std::nullopt;
    writeActualBeside(actual, diffPath);
    result.baselineMissing = true;
    return result;
}

} // namespace

ImageComparison compareWithBaseline(const ImageRgba8& actual,
                                    const std::filesystem::path& baselinePng,
                                    ImageTolerance tolerance,
                                    const std::filesystem::path& diffPath) {
    if (std::optional<ImageComparison> early =
            baselineWrittenOrMissing(actual, baselinePng, diffPath))
        return *early;
    const ImageRgba8 expected = readPng(baselinePng);
    ImageComparison result = compareImages(actual, expected, tolerance, diffPath);
    result.baselinePath = baselinePng;
    if (result.diffWritten)
        writeActualBeside(actual, diffPath);
    return result;
}

std::size_t contentPixels(const ImageRgba8& image, Rgba8 background) {
    std::size_t count = 0;
    for (int y = 0; y < image.height(); ++y) {
        const Rgba8* row = image.row(y);
        for (int x = 0; x < image.width(); ++x)
            count +=
                row[x].r != background.r || row[x].g != background.g || row[x].b != background.b;
    }
    return count;
}

ImageComparison compareWithBaseline(const ImageRgba8& actual,
                                    const std::filesystem::path& baselinePng,
                                    ContentTolerance tolerance,
                                    const std::filesystem::path& diffPath) {
    if (std::optional<ImageComparison> early =
            baselineWrittenOrMissing(actual, baselinePng, diffPath))
        return *early;
    const ImageRgba8 expected = readPng(baselinePng);
    if (expected.isEmpty())
        throw Error(baselinePng.string(), "the baseline image is empty");
    const Rgba8 background = expected.at(0, 0);
    const std::size_t expectedContent = contentPixels(expected, background);
    const std::size_t actualContent = contentPixels(actual, background);
    ImageTolerance absolute;
    absolute.channelTolerance = tolerance.channelTolerance;
    absolute.maxBadPixels = std::size_t(std::ceil(tolerance.badShare * double(expectedContent)));
    ImageComparison result = compareWithBaseline(actual, baselinePng, absolute, diffPath);
    result.expectedContent = expectedContent;
    result.actualContent = actualContent;
    if (double(actualContent) < tolerance.minContentRatio * double(expectedContent))
        result.matches = false; // too little on screen: blank, washed out or lost
    return result;
}

} // namespace lw::core
