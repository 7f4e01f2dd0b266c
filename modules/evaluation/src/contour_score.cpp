#include "lw/evaluation/contour_score.h"

#include "lw/core/error.h"

#include <string>

namespace lw::evaluation {

using render::PixelMask;

namespace {

void checkComparable(const PixelMask& drawn, const PixelMask& truth, int tolerancePx) {
    if (drawn.width() != truth.width() || drawn.height() != truth.height())
        throw core::Error("contour score",
                          "mask sizes differ: drawn " + std::to_string(drawn.width()) + "x" +
                              std::to_string(drawn.height()) + ", truth " +
                              std::to_string(truth.width()) + "x" + std::to_string(truth.height()));
    if (tolerancePx < 0)
        throw core::Error("contour score", "tolerance must not be negative");
}

} // namespace

ContourScore scoreContours(const PixelMask& drawn, const PixelMask& truth, int tolerancePx) {
    checkComparable(drawn, truth, tolerancePx);
    const PixelMask nearDrawn = drawn.dilated(tolerancePx);
    const PixelMask nearTruth = truth.dilated(tolerancePx);
    ContourScore score;
    for (std::size_t i = 0; i < truth.pixels().size(); ++i) {
        if (truth.pixels()[i]) {
            ++score.truePixels;
            score.trueFound += nearDrawn.pixels()[i] ? 1 : 0;
        }
        if (drawn.pixels()[i]) {
            ++score.drawnPixels;
            score.drawnMatched += nearTruth.pixels()[i] ? 1 : 0;
        }
    }
    score.recall = score.truePixels ? double(score.trueFound) / double(score.truePixels) : 1.0;
    score.precision =
        score.drawnPixels ? double(score.drawnMatched) / double(score.drawnPixels) : 1.0;
    return score;
}

core::ImageRgba8 contourDiffImage(const PixelMask& drawn, const PixelMask& truth, int tolerancePx) {
    checkComparable(drawn, truth, tolerancePx);
    const PixelMask nearDrawn = drawn.dilated(tolerancePx);
    const PixelMask nearTruth = truth.dilated(tolerancePx);
    core::ImageRgba8 image(drawn.width(), drawn.height(), {255, 255, 255, 255});
    for (int y = 0; y < drawn.height(); ++y)
        for (int x = 0; x < drawn.width(); ++x) {
            if (drawn.get(x, y))
                image.at(x, y) =
                    nearTruth.get(x, y) ? core::Rgba8{0, 0, 0, 255} : core::Rgba8{230, 0, 0, 255};
            else if (truth.get(x, y))
                image.at(x, y) = nearDrawn.get(x, y) ? core::Rgba8{190, 190, 190, 255}
                                                     : core::Rgba8{0, 70, 230, 255};
        }
    return image;
}

} // namespace lw::evaluation
