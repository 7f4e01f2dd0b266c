#pragma once

#include "lw/core/image.h"

#include <cstddef>
#include <filesystem>
#include <string>

namespace lw::core {

// What a baseline test may tolerate: pixels whose largest channel difference exceeds
// `channelTolerance` are "bad"; the images match while there are at most `maxBadPixels`.
struct ImageTolerance {
    int channelTolerance = 0;
    std::size_t maxBadPixels = 0;
};

// A baseline tolerance relative to what the picture shows (its content: the pixels that are not
// the background colour, read from the baseline's top-left pixel). Up to `badShare` x the
// baseline's content pixels may differ by more than `channelTolerance`, and the actual image must
// show at least `minContentRatio` x the baseline's content, so an empty or washed-out image never
// passes however loose the rest is.
struct ContentTolerance {
    int channelTolerance = 0;
    double badShare = 0.05;
    double minContentRatio = 0.5;
};

struct ImageComparison {
    bool sizesMatch = false;
    std::size_t expectedContent = 0; // content pixels of the baseline (ContentTolerance only)
    std::size_t actualContent = 0;   // and of the actual image
    int maxChannelDifference = 0;    // over the overlapping pixels; 255 when the sizes differ
    std::size_t badPixels = 0;       // over tolerance, plus every pixel outside the overlap
    std::size_t pixelCount = 0;      // pixels of the larger extent
    bool matches = false;
    bool diffWritten = false;
    std::filesystem::path diffPath;
    // compareWithBaseline only: the baseline file was not there (matches is false), or
    // LINEWORK_UPDATE_BASELINES asked for it to be written instead of compared (matches is true).
    bool baselineMissing = false;
    bool baselineWritten = false;
    std::filesystem::path baselinePath;

    // One line for test failure messages.
    std::string describe() const;
};

// Per-pixel comparison (max |difference| over r, g, b, a). Sizes may differ: the extent is the
// union of both and pixels present in only one image are bad.
ImageComparison compareImages(const ImageRgba8& actual, const ImageRgba8& expected,
                              ImageTolerance tolerance);

// The diff picture: the expected image dimmed to a faint grey (so one sees where things are),
// pixels that differ within tolerance in yellow, bad pixels in red, pixels outside the overlap
// in magenta.
ImageRgba8 diffImage(const ImageRgba8& actual, const ImageRgba8& expected,
                     ImageTolerance tolerance);

// Compares and, when the images do not match and `diffPath` is not empty, writes the diff image
// there as PNG (atomically) and records that in the result.
ImageComparison compareImages(const ImageRgba8& actual, const ImageRgba8& expected,
                              ImageTolerance tolerance, const std::filesystem::path& diffPath);

// The baseline policy of every image test. With LINEWORK_UPDATE_BASELINES=1 in the environment
// `actual` is written to `baselinePng` (atomically; a person then looks at it and commits it) and
// nothing is compared. Otherwise `actual` is compared with the baseline; on mismatch `diffPath`
// (if given) is written, and `actual` next to it as "<diff stem>.actual.png", so a reviewer can
// accept the new image by copying it over. A missing baseline does not match: describe() names
// the path to create and how (`actual` written beside the diff path as for a mismatch). An
// unreadable baseline throws core::Error.
ImageComparison compareWithBaseline(const ImageRgba8& actual,
                                    const std::filesystem::path& baselinePng,
                                    ImageTolerance tolerance,
                                    const std::filesystem::path& diffPath = {});
// The same with a tolerance relative to the baseline's content (see ContentTolerance).
// True when LINEWORK_UPDATE_BASELINES=1 asks compareWithBaseline to write baselines.
bool updatingBaselines();
ImageComparison compareWithBaseline(const ImageRgba8& actual,
                                    const std::filesystem::path& baselinePng,
                                    ContentTolerance tolerance,
                                    const std::filesystem::path& diffPath = {});
// Pixels whose colour differs from `background` in r, g or b.
std::size_t contentPixels(const ImageRgba8& image, Rgba8 background);

} // namespace lw::core
