// The real-CT line quality measures on small masks whose answers are known exactly: the outer
// outline of a square with a hole, its coverage by a drawing that misses one side, the speckle
// share, the agreement of shifted drawings, and blank images that must fail, not pass.
#include "lw/core/error.h"
#include "lw/evaluation/line_quality.h"

#include <gtest/gtest.h>

using namespace lw::render;
using namespace lw::evaluation;

namespace {

// A filled square [x0, x1] x [y0, y1] (inclusive) on a 30 x 30 image.
PixelMask square(int x0, int y0, int x1, int y1, PixelMask mask = PixelMask(30, 30)) {
    for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
            mask.set(x, y);
    return mask;
}

// The border pixels of the same square.
PixelMask squareBorder(int x0, int y0, int x1, int y1) {
    PixelMask mask(30, 30);
    for (int x = x0; x <= x1; ++x) {
        mask.set(x, y0);
        mask.set(x, y1);
    }
    for (int y = y0; y <= y1; ++y) {
        mask.set(x0, y);
        mask.set(x1, y);
    }
    return mask;
}

} // namespace

TEST(LineQuality, OuterOutlineOfASquareWithAHoleIsItsBorderOnly) {
    PixelMask panel = square(5, 5, 24, 24); // 20 x 20
    for (int y = 12; y <= 16; ++y)          // a 5 x 5 hole: background enclosed by the surface
        for (int x = 12; x <= 16; ++x)
            panel.set(x, y, false);
    const PixelMask outline = outerOutline(panel);
    EXPECT_EQ(outline, squareBorder(5, 5, 24, 24));
    EXPECT_EQ(outline.count(), 76u); // 4 * 20 - 4 corners counted twice
}

TEST(LineQuality, TheImageFrameIsNoOutline) {
    // A surface running off the left edge: only its right, top and bottom sides are outline.
    const PixelMask outline = outerOutline(square(0, 10, 9, 19));
    EXPECT_EQ(outline.count(), 10u + 9u + 9u);
    EXPECT_FALSE(outline.get(0, 15));
    EXPECT_TRUE(outline.get(9, 15));
    EXPECT_TRUE(outerOutline(square(0, 0, 29, 29)).count() == 0u); // the whole image is surface
}

TEST(LineQuality, CoverageCountsOutlinePixelsWithinOnePixelOfALine) {
    const PixelMask outline = outerOutline(square(5, 5, 24, 24));
    // The lines one pixel outside the square on three sides, none along the right side.
    PixelMask lines(30, 30);
    for (int i = 4; i <= 25; ++i) {
        lines.set(i, 4);  // above the top side
        lines.set(i, 25); // below the bottom side
        lines.set(4, i);  // left of the left side
    }
    const OutlineCoverage covered = outlineCoverage(outline, lines, 1);
    EXPECT_EQ(covered.outlinePixels, 76u);
    // The right side's 18 inner pixels (rows 6-23 of column 24) have no line within 1 px; its
    // corner pixels are next to the top and bottom lines (which reach column 25).
    EXPECT_EQ(covered.covered, 76u - 18u);
    EXPECT_DOUBLE_EQ(covered.coverage, 58.0 / 76.0);
    EXPECT_EQ(outlineCoverage(outline, lines, 0).covered, 0u); // strict: the lines are beside it
}

TEST(LineQuality, BlankImagesFail) {
    const PixelMask outline = outerOutline(square(5, 5, 24, 24));
    const PixelMask blank(30, 30);
    EXPECT_EQ(outlineCoverage(outline, blank).coverage, 0.0);
    EXPECT_THROW(outlineCoverage(outerOutline(blank), outline), lw::core::Error); // blank panel
    const LineAgreement nothing = lineAgreement(blank, blank);
    EXPECT_EQ(nothing.minimum, 0.0);
    const LineAgreement oneSided = lineAgreement(outline, blank);
    EXPECT_EQ(oneSided.firstNearSecond, 0.0);
    EXPECT_EQ(oneSided.secondNearFirst, 0.0);
    EXPECT_EQ(oneSided.minimum, 0.0);
    EXPECT_THROW(outlineCoverage(outline, PixelMask(29, 30)), lw::core::Error);
}

TEST(LineQuality, FragmentShareCountsPixelsInSmallGroups) {
    PixelMask lines(30, 30);
    for (int x = 2; x < 14; ++x) // a 12-pixel stroke: kept
        lines.set(x, 3);
    for (int i = 0; i < 10; ++i) // a 10-pixel diagonal, 8-connected: exactly the size, kept
        lines.set(5 + i, 10 + i);
    lines.set(25, 25); // a 3-pixel speck and a single pixel: speckle
    lines.set(26, 26);
    lines.set(27, 26);
    lines.set(20, 5);
    const FragmentShare share = fragmentShare(lines, 10);
    EXPECT_EQ(share.linePixels, 26u);
    EXPECT_EQ(share.fragmentPixels, 4u);
    EXPECT_DOUBLE_EQ(share.share, 4.0 / 26.0);
    EXPECT_EQ(fragmentShare(PixelMask(30, 30)).share, 0.0);
    EXPECT_THROW(fragmentShare(lines, 0), lw::core::Error);
}

TEST(LineQuality, AgreementIsMeasuredBothWays) {
    const PixelMask border = squareBorder(5, 5, 24, 24);
    // One pixel out on every side: within tolerance everywhere.
    const LineAgreement shifted = lineAgreement(squareBorder(4, 4, 25, 25), border);
    EXPECT_EQ(shifted.minimum, 1.0);
    // The border plus a far stroke of 24 pixels: all of the border is near the drawing, but only
    // 76 of the drawing's 100 pixels are near the border.
    PixelMask extra = border;
    for (int x = 3; x < 27; ++x)
        extra.set(x, 28);
    const LineAgreement partial = lineAgreement(extra, border);
    EXPECT_EQ(partial.firstPixels, 100u);
    EXPECT_EQ(partial.secondPixels, 76u);
    EXPECT_DOUBLE_EQ(partial.firstNearSecond, 76.0 / 100.0);
    EXPECT_DOUBLE_EQ(partial.secondNearFirst, 1.0);
    EXPECT_DOUBLE_EQ(partial.minimum, 0.76);
    // Two pixels apart: no agreement at 1 px.
    EXPECT_EQ(lineAgreement(squareBorder(3, 3, 26, 26), border).minimum, 0.0);
}
