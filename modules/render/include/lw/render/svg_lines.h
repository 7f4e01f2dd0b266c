#pragma once

// The visible silhouette as an SVG document: one <path> per polyline (visible_polylines.h), in
// image coordinates, the viewBox the frame's pixels, so it overlays the raster panel exactly and
// scales without losing sharpness. Plain text, no Qt: the CLI writes it on the GPU machine too,
// and the report embeds it.

#include "lw/render/visible_polylines.h"

#include <string>
#include <vector>

namespace lw::render {

struct SvgLineStyle {
    std::string colour = "#000000";
    double widthPx = 1.0;        // in image pixels (the viewBox unit)
    std::string background = ""; // e.g. "#ffffff"; empty: transparent
};

// Hidden lines (splitPolylines) as technical illustration draws them, here and in the report's
// PNG and PDF strokes alike: grey, half the visible lines' width, dashes of 4 and gaps of 3 of
// those widths, so a larger export scales them with its lines.
inline constexpr const char* kHiddenLineColour = "#8c8c8c";
inline constexpr double kHiddenLineWidthFactor = 0.5;
inline constexpr double kHiddenDashWidths = 4.0;
inline constexpr double kHiddenGapWidths = 3.0;

// `hidden` (optional) goes under the visible lines in the hidden style.
std::string silhouetteSvg(const std::vector<Polyline>& polylines, int width, int height,
                          const SvgLineStyle& style = {}, const std::vector<Polyline>& hidden = {});
// Only the <g> elements with the paths, for a document that has its own <svg> (the report).
std::string silhouettePaths(const std::vector<Polyline>& polylines, const SvgLineStyle& style,
                            const std::vector<Polyline>& hidden = {});

} // namespace lw::render
