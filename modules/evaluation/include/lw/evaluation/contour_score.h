#pragma once

#include "lw/core/image.h"
#include "lw/render/pixel_mask.h"

#include <cstddef>

namespace lw::evaluation {

// The accuracy measure of issue 3 (the paper's Table 5, measured instead of hand-drawn).
struct ContourScore {
    double recall = 0.0;    // share of true contour pixels with a drawn pixel within tolerance
    double precision = 0.0; // share of drawn pixels with a true contour pixel within tolerance
    std::size_t truePixels = 0;
    std::size_t drawnPixels = 0;
    std::size_t trueFound = 0;    // true pixels that have a drawn pixel within tolerance
    std::size_t drawnMatched = 0; // drawn pixels that have a true pixel within tolerance
};

// Distances are Chebyshev (a pixel's 8 neighbours are at distance 1). An empty truth gives
// recall 1 and an empty drawing precision 1 (vacuously: nothing missed, nothing wrong); an empty
// drawing of a visible shape still fails through recall 0. Throws core::Error when the sizes
// differ or tolerancePx < 0.
ContourScore scoreContours(const render::PixelMask& drawn, const render::PixelMask& truth,
                           int tolerancePx = 1);

// The score as a picture, to look at where a drawing and its truth part: a drawn pixel with a
// true pixel within tolerance black, one without red (what precision counts against), a true
// pixel with no drawn pixel near blue (what recall counts against), a true pixel under or beside
// a matched drawing light grey, the rest white. Throws core::Error when the sizes differ.
core::ImageRgba8 contourDiffImage(const render::PixelMask& drawn, const render::PixelMask& truth,
                                  int tolerancePx = 1);

} // namespace lw::evaluation
