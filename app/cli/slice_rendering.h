#pragma once

// `linework-cli render --panel slice`: one axial, coronal or sagittal slice of the series in
// patient space (lw/volume/slice_plane.h), windowed to grey, with the iso contour on it.

#include "arguments.h"
#include "lw/core/image.h"
#include "lw/volume/slice_contour.h"
#include "lw/volume/slice_plane.h"

#include <iosfwd>
#include <set>
#include <string>
#include <vector>

namespace lw::cli {

// The option names only the slice panel reads (--plane, --position, --window).
const std::set<std::string>& sliceOptions();

// Grey values from a window in real units: level - width / 2 is black, level + width / 2 white.
struct GreyWindow {
    double width = 2000.0;
    double level = 500.0;
};
// "W/L", width > 0; throws UsageError otherwise.
GreyWindow parseGreyWindow(const std::string& text);

// The slice as grey pixels through `window`; pixels outside the volume black.
core::ImageRgba8 windowedSlice(const volume::SliceImage& slice, const GreyWindow& window);
// The contour's segments drawn over `image` one pixel wide in `colour`.
void drawContour(core::ImageRgba8& image, const std::vector<volume::ContourSegment>& contour,
                 core::Rgba8 colour);

// Runs `render INPUT --panel slice ...` (the arguments already parsed, INPUT and -o OUT given):
// refuses the options of the 3D panels, writes the PNG and reports on `out`.
int renderSliceCommand(const Arguments& arguments, const std::string& input,
                       const std::string& output, std::ostream& out);

} // namespace lw::cli
