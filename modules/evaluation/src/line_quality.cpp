#include "lw/evaluation/line_quality.h"

#include "lw/core/error.h"
#include "lw/evaluation/contour_score.h"

#include <algorithm>
#include <string>
#include <vector>

namespace lw::evaluation {

using render::PixelMask;

namespace {

// The background pixels 4-connected to the image's frame (a flood fill from the frame's
// background pixels).
PixelMask outerBackground(const PixelMask& foreground) {
    const int width = foreground.width(), height = foreground.height();
    PixelMask outside(width, height);
    std::vector<std::pair<int, int>> stack;
    const auto visit = [&](int x, int y) {
        if (foreground.contains(x, y) && !foreground.get(x, y) && !outside.get(x, y)) {
            outside.set(x, y);
            stack.emplace_back(x, y);
        }
    };
    for (int x = 0; x < width; ++x) {
        visit(x, 0);
        visit(x, height - 1);
    }
    for (int y = 0; y < height; ++y) {
        visit(0, y);
        visit(width - 1, y);
    }
    while (!stack.empty()) {
        const auto [x, y] = stack.back();
        stack.pop_back();
        visit(x + 1, y);
        visit(x - 1, y);
        visit(x, y + 1);
        visit(x, y - 1);
    }
    return outside;
}

} // namespace

PixelMask outerOutline(const PixelMask& foreground) {
    const PixelMask outside = outerBackground(foreground);
    PixelMask outline(foreground.width(), foreground.height());
    const auto isOutside = [&](int x, int y) {
        return outside.contains(x, y) && outside.get(x, y);
    };
    for (int y = 0; y < foreground.height(); ++y)
        for (int x = 0; x < foreground.width(); ++x)
            if (foreground.get(x, y) && (isOutside(x - 1, y) || isOutside(x + 1, y) ||
                                         isOutside(x, y - 1) || isOutside(x, y + 1)))
                outline.set(x, y);
    return outline;
}

OutlineCoverage outlineCoverage(const PixelMask& outline, const PixelMask& lines, int tolerancePx) {
    // The outline is the truth the lines are scored against; its recall is the coverage.
    const ContourScore score = scoreContours(lines, outline, tolerancePx);
    if (score.truePixels == 0)
        throw core::Error("outline coverage",
                          "the shaded panel has no outline (no surface drawn at this view)");
    OutlineCoverage result;
    result.outlinePixels = score.truePixels;
    result.covered = score.trueFound;
    result.coverage = score.recall;
    return result;
}

FragmentShare fragmentShare(const PixelMask& lines, int minPixels) {
    if (minPixels < 1)
        throw core::Error("fragment share",
                          "the group size must be at least 1, got " + std::to_string(minPixels));
    FragmentShare result;
    for (const std::size_t size : lines.componentSizes()) {
        result.linePixels += size;
        if (size < std::size_t(minPixels))
            result.fragmentPixels += size;
    }
    result.share =
        result.linePixels ? double(result.fragmentPixels) / double(result.linePixels) : 0.0;
    return result;
}

LineAgreement lineAgreement(const PixelMask& first, const PixelMask& second, int tolerancePx) {
    // scoreContours gives an empty side a vacuous 1; here a blank drawing must not agree.
    const ContourScore score = scoreContours(first, second, tolerancePx);
    LineAgreement result;
    result.firstPixels = score.drawnPixels;
    result.secondPixels = score.truePixels;
    if (result.firstPixels == 0 || result.secondPixels == 0)
        return result;
    result.firstNearSecond = score.precision;
    result.secondNearFirst = score.recall;
    result.minimum = std::min(result.firstNearSecond, result.secondNearFirst);
    return result;
}

} // namespace lw::evaluation
