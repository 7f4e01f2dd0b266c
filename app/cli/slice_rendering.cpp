#include "slice_rendering.h"

#include "cli_inputs.h"
#include "lw/core/png_io.h"
#include "lw/render/line_raster.h"
#include "panel_rendering.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <optional>
#include <ostream>
#include <sstream>

namespace lw::cli {
namespace {

// What only the 3D panels read: a slice has no method, camera, size of its own (its pixels are
// the volume's finest spacing), vector form or line styling beyond the contour's colour.
const std::vector<std::string> kSurfaceOnlyOptions = {
    "method",     "chunks",       "mode",       "visibility",           "view",      "camera",
    "size",       "backend",      "repeat",     "min-stroke",           "border",    "gradient",
    "oversample", "thick-slices", "line-width", "suggestive-threshold", "thin-walls"};
const std::vector<std::string> kSurfaceOnlyFlags = {"suggestive", "hidden-lines"};

void refuseSurfaceOptions(const Arguments& arguments) {
    for (const std::string& name : kSurfaceOnlyOptions)
        if (arguments.option(name))
            throw UsageError("--" + name, "applies to the 3D panels, not to --panel slice");
    for (const std::string& name : kSurfaceOnlyFlags)
        if (arguments.flag(name))
            throw UsageError("--" + name, "applies to the 3D panels, not to --panel slice");
    if (const auto format = arguments.option("format"); format && *format != "png")
        throw UsageError("--format " + *format, "a slice is written as PNG only");
    if (arguments.option("output")->ends_with(".svg"))
        throw UsageError("-o " + *arguments.option("output"), "a slice is written as PNG only");
}

std::string millimetres(double value) {
    std::ostringstream text;
    text << std::fixed << std::setprecision(2) << value;
    return text.str();
}

volume::SliceOrientation parsePlane(const Arguments& arguments) {
    const std::string name = arguments.option("plane", "axial");
    const auto orientation = volume::parseSliceOrientation(name);
    if (!orientation)
        throw UsageError("--plane " + name, "expected axial, coronal or sagittal");
    return *orientation;
}

// --position MM along the plane's normal, default the middle; outside the voxel centres' range
// is a usage error that names the range.
double parsePosition(const Arguments& arguments, const volume::SliceGeometry& geometry) {
    const double position = arguments.number("position", geometry.middlePosition());
    const double slack = 1e-6 * std::max(1.0, std::abs(position));
    if (!(position >= geometry.firstPosition - slack && position <= geometry.lastPosition + slack))
        throw UsageError("--position " + *arguments.option("position"),
                         "outside the series: " +
                             std::string(volume::sliceOrientationName(geometry.orientation)) +
                             " positions run from " + millimetres(geometry.firstPosition) + " to " +
                             millimetres(geometry.lastPosition) + " mm");
    return std::clamp(position, geometry.firstPosition, geometry.lastPosition);
}

// The default window: for CT (a DICOM CT series, or the phantom, which is in HU) a bone window,
// 2000/500, where the bone and the skin iso-values both fall on visible grey; for anything else,
// whose units we do not know, the whole value range.
GreyWindow defaultWindow(const input::OpenedVolume& opened, const std::string& input) {
    const bool ct =
        (opened.dicom && opened.dicom->modality == "CT") || input.starts_with("phantom:");
    if (ct)
        return {};
    const volume::ValueRange range = opened.volume.realRange();
    return {std::max(range.max - range.min, 1e-6), 0.5 * (range.min + range.max)};
}

// --line-colour #RRGGBB (validated as the vector lines' colour), default yellow.
core::Rgba8 contourColour(const Arguments& arguments) {
    if (!arguments.option("line-colour"))
        return {255, 255, 0, 255};
    const std::string hex = parseLineStyle(arguments, true).colour;
    const auto channel = [&](int n) {
        return std::uint8_t(
            std::strtol(hex.substr(std::size_t(1 + 2 * n), 2).c_str(), nullptr, 16));
    };
    return {channel(0), channel(1), channel(2), 255};
}

double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

} // namespace

const std::set<std::string>& sliceOptions() {
    static const std::set<std::string> names = {"plane", "position", "window"};
    return names;
}

GreyWindow parseGreyWindow(const std::string& text) {
    const std::vector<double> parts =
        parseUsage([&] { return parseNumbers(text, '/', "--window " + text); });
    if (parts.size() != 2 || !(parts[0] > 0.0) || !std::isfinite(parts[1]))
        throw UsageError("--window " + text,
                         "expected WIDTH/LEVEL in real units (HU for CT), width > 0");
    return {parts[0], parts[1]};
}

core::ImageRgba8 windowedSlice(const volume::SliceImage& slice, const GreyWindow& window) {
    const glm::ivec2 size = slice.geometry.size;
    std::vector<std::uint8_t> grey(std::size_t(size.x) * std::size_t(size.y));
    volume::windowToGrey(slice, window.width, window.level, grey.data(), std::size_t(size.x));
    core::ImageRgba8 image(size.x, size.y, {0, 0, 0, 255});
    for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x) {
            const std::uint8_t g = grey[std::size_t(y) * std::size_t(size.x) + std::size_t(x)];
            image.at(x, y) = {g, g, g, 255};
        }
    return image;
}

void drawContour(core::ImageRgba8& image, const std::vector<volume::ContourSegment>& contour,
                 core::Rgba8 colour) {
    render::PixelMask mask(image.width(), image.height());
    // The contour puts pixel centres at integers, the rasterizer at x + 0.5.
    for (const volume::ContourSegment& s : contour)
        render::rasterizeLine(mask, s.a + 0.5, s.b + 0.5);
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            if (mask.get(x, y))
                image.at(x, y) = colour;
}

int renderSliceCommand(const Arguments& arguments, const std::string& input,
                       const std::string& output, std::ostream& out) {
    refuseSurfaceOptions(arguments);
    if (!arguments.option("iso"))
        throw UsageError("render", "needs --iso HU (the contour's value)");
    const double iso = arguments.number("iso", 0.0);
    const volume::SliceOrientation orientation = parsePlane(arguments);
    const auto window = arguments.option("window");
    std::optional<GreyWindow> chosenWindow;
    if (window)
        chosenWindow = parseGreyWindow(*window);
    const core::Rgba8 colour = contourColour(arguments);
    const auto threads = unsigned(std::max(0.0, arguments.number("threads", 0.0)));

    const input::OpenedVolume opened =
        openCliInput(input, arguments.option("series"), importLimits(arguments));
    const volume::SliceGeometry geometry = volume::sliceGeometry(opened.volume, orientation);
    const double position = parsePosition(arguments, geometry);
    const auto start = std::chrono::steady_clock::now();
    const volume::SliceImage slice =
        volume::sampleSlice(opened.volume, geometry, position, threads);
    const double sampleMs = millisecondsSince(start);
    const auto contourStart = std::chrono::steady_clock::now();
    const std::vector<volume::ContourSegment> contour = volume::isoContour(slice, iso);
    const double contourMs = millisecondsSince(contourStart);

    core::ImageRgba8 image =
        windowedSlice(slice, chosenWindow.value_or(defaultWindow(opened, input)));
    drawContour(image, contour, colour);
    core::writePng(output, image, core::PngFormat::Rgb);
    out << "wrote " << output << " (" << image.width() << "x" << image.height() << ", "
        << volume::sliceOrientationName(orientation) << " at " << millimetres(position) << " mm, "
        << millimetres(geometry.pixelMm) << " mm pixels, " << contour.size()
        << " contour segments; sampled in " << millimetres(sampleMs) << " ms, contour in "
        << millimetres(contourMs) << " ms)\n";
    return 0;
}

} // namespace lw::cli
