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

std::string silhouetteSvg(const std::vector<Polyline>& polylines, int width, int height,
                          const SvgLineStyle& style = {});
// Only the <g> element with the paths, for a document that has its own <svg> (the report).
std::string silhouettePaths(const std::vector<Polyline>& polylines, const SvgLineStyle& style);

} // namespace lw::render
