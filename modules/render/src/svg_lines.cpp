#include "lw/render/svg_lines.h"

#include <cstdio>

namespace lw::render {
namespace {

// Two decimals: a hundredth of a pixel is below anything a printer or a screen shows.
void appendPoint(std::string& out, char command, glm::vec2 p) {
    char text[64];
    std::snprintf(text, sizeof text, "%c%.2f %.2f", command, double(p.x), double(p.y));
    out += text;
}

// The attribute value with the XML specials escaped (colours come from settings).
std::string attribute(const std::string& value) {
    std::string out;
    for (const char c : value) {
        switch (c) {
        case '&':
            out += "&amp;";
            break;
        case '<':
            out += "&lt;";
            break;
        case '"':
            out += "&quot;";
            break;
        default:
            out += c;
        }
    }
    return out;
}

// One <path> per polyline.
void appendPaths(std::string& svg, const std::vector<Polyline>& polylines) {
    for (const Polyline& line : polylines) {
        if (line.points.size() < 2)
            continue;
        svg += "<path d=\"";
        appendPoint(svg, 'M', line.points.front());
        for (std::size_t i = 1; i < line.points.size(); ++i)
            appendPoint(svg, 'L', line.points[i]);
        if (line.closed)
            svg += "Z";
        svg += "\"/>\n";
    }
}

} // namespace

std::string silhouetteSvg(const std::vector<Polyline>& polylines, int width, int height,
                          const SvgLineStyle& style, const std::vector<Polyline>& hidden) {
    char header[512];
    std::snprintf(header, sizeof header,
                  "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
                  "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"%d\" "
                  "height=\"%d\" viewBox=\"0 0 %d %d\">\n",
                  width, height, width, height);
    std::string svg = header;
    if (!style.background.empty())
        svg +=
            "<rect width=\"100%\" height=\"100%\" fill=\"" + attribute(style.background) + "\"/>\n";
    svg += silhouettePaths(polylines, style, hidden);
    svg += "</svg>\n";
    return svg;
}

std::string silhouettePaths(const std::vector<Polyline>& polylines, const SvgLineStyle& style,
                            const std::vector<Polyline>& hidden) {
    std::string svg;
    if (!hidden.empty()) {
        char group[320];
        std::snprintf(group, sizeof group,
                      "<g fill=\"none\" stroke-width=\"%.3f\" stroke-dasharray=\"%.3f %.3f\" "
                      "stroke=\"%s\">\n",
                      style.widthPx * kHiddenLineWidthFactor, style.widthPx * kHiddenDashWidths,
                      style.widthPx * kHiddenGapWidths, kHiddenLineColour);
        svg += group;
        appendPaths(svg, hidden);
        svg += "</g>\n";
    }
    char group[256];
    std::snprintf(group, sizeof group,
                  "<g fill=\"none\" stroke-width=\"%.3f\" stroke-linecap=\"round\" "
                  "stroke-linejoin=\"round\" stroke=\"",
                  style.widthPx);
    svg += group + attribute(style.colour) + "\">\n";
    appendPaths(svg, polylines);
    svg += "</g>\n";
    return svg;
}

} // namespace lw::render
