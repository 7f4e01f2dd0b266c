#pragma once

#include "lw/core/image.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace lw::render {

// A binary image (contour pixels, coverage), row-major with the top row first like the images
// it is drawn from; 0 = off, anything else = on.
class PixelMask {
public:
    PixelMask() = default;
    PixelMask(int width, int height); // all off; throws core::Error for negative sizes

    int width() const { return m_width; }
    int height() const { return m_height; }
    bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < m_width && y < m_height; }
    bool get(int x, int y) const { return m_pixels[index(x, y)] != 0; }
    void set(int x, int y, bool on = true) { m_pixels[index(x, y)] = on ? 1 : 0; }
    std::vector<std::uint8_t>& pixels() { return m_pixels; }
    const std::vector<std::uint8_t>& pixels() const { return m_pixels; }
    std::size_t count() const;

    // Every pixel within Chebyshev distance `radius` of an on pixel (a (2r+1)^2 square).
    PixelMask dilated(int radius) const;
    // The on pixels drawn as an antialiased stroke `lineWidth` pixels wide through their centres:
    // a byte a pixel, 255 = covered,
    //     coverage(p) = clamp(lineWidth / 2 + 0.5 - d(p), 0, 1),
    // d(p) = the distance from p's centre to the nearest on pixel's centre. The pixel-wide box
    // filter of a band lineWidth wide: a straight line of pixels gets its exact coverage, and a
    // one-pixel width gives the mask itself. The rule the live panels draw lines with (their GL
    // view applies it to a mask texture the same way).
    std::vector<std::uint8_t> strokeCoverage(double lineWidth) const;
    // That stroke's footprint: coverage is 0 from strokeReach pixels on, so strokeRadius whole
    // pixels around a line pixel hold all of it (0 for one-pixel lines: the mask itself). Shared
    // with the GL passes that draw the same strokes.
    static double strokeReach(double lineWidth) { return std::max(lineWidth, 1.0) / 2.0 + 0.5; }
    static int strokeRadius(double lineWidth) { return int(std::ceil(strokeReach(lineWidth))) - 1; }
    // Turns off every group of on pixels smaller than `minPixels`; returns how many pixels went.
    // A group is 8-connected, and with gapPixels = g pixels up to g apart (Chebyshev distance
    // g + 1) join it too. A stroke of a line drawing is such a group: this drops the speckle that
    // voxel-scale noise bumps leave on a CT's line drawing and keeps the contours, also a contour
    // that a method draws with one-pixel breaks.
    std::size_t removeComponentsSmallerThan(int minPixels, int gapPixels = 0);
    // Draws the pixel between two stroke ends a one-pixel gap apart (kernels::bridgesStrokeEnds);
    // returns how many pixels it drew.
    std::size_t bridgeStrokeEnds();
    // Stroke pruning as every method's frame gets it: removeComponentsSmallerThan(minPixels,
    // gapPixels); then, when strokes join across a gap (gapPixels >= 1), bridgeStrokeEnds and
    // removeComponentsSmallerThan(kernels::minPiecePixels(minPixels), 0) on the result: the gap
    // keeps a contour broken into dashes long enough for its one-pixel breaks to be bridged,
    // and the dots that only lay beside a longer stroke go then. Nothing for minPixels <= 1.
    // Returns the line pixels removed.
    std::size_t pruneStrokes(int minPixels, int gapPixels);
    // Sizes of the groups of on pixels, in the raster order of their first pixels, as above.
    std::vector<std::size_t> componentSizes(int gapPixels = 0) const;

    core::ImageRgba8 toImage(core::Rgba8 on = {255, 255, 255, 255},
                             core::Rgba8 off = {0, 0, 0, 255}) const;
    // On where a pixel's colour (r, g, b) differs from `background`: turns a rendered line
    // drawing into the mask that scoreContours() expects.
    static PixelMask fromImage(const core::ImageRgba8& image,
                               core::Rgba8 background = {0, 0, 0, 255});

    friend bool operator==(const PixelMask&, const PixelMask&) = default;

private:
    std::size_t index(int x, int y) const {
        return std::size_t(y) * std::size_t(m_width) + std::size_t(x);
    }

    int m_width = 0;
    int m_height = 0;
    std::vector<std::uint8_t> m_pixels;
};

} // namespace lw::render
