#include "lw/core/error.h"
#include "lw/evaluation/contour_score.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace lw::render;
using namespace lw::evaluation;

namespace {

PixelMask circle(int size, double cx, double cy, double radius) {
    PixelMask mask(size, size);
    for (int i = 0; i < 2000; ++i) {
        const double a = 2.0 * 3.14159265358979 * i / 2000.0;
        mask.set(int(std::floor(cx + radius * std::cos(a))),
                 int(std::floor(cy + radius * std::sin(a))));
    }
    return mask;
}

PixelMask verticalLine(int size, int x) {
    PixelMask mask(size, size);
    for (int y = 10; y < size - 10; ++y)
        mask.set(x, y);
    return mask;
}

} // namespace

TEST(ContourScore, IdenticalMasksScorePerfectly) {
    const PixelMask truth = circle(100, 50, 50, 30);
    const ContourScore score = scoreContours(truth, truth, 1);
    EXPECT_EQ(score.recall, 1.0);
    EXPECT_EQ(score.precision, 1.0);
    EXPECT_EQ(score.truePixels, truth.count());
    EXPECT_EQ(score.drawnPixels, truth.count());
}

TEST(ContourScore, OnePixelShiftIsWithinTolerance) {
    const PixelMask truth = circle(100, 50, 50, 30);
    for (auto [dx, dy] : {std::pair{1, 0}, std::pair{0, -1}, std::pair{1, 1}}) {
        const ContourScore score = scoreContours(circle(100, 50 + dx, 50 + dy, 30), truth, 1);
        EXPECT_EQ(score.recall, 1.0);
        EXPECT_EQ(score.precision, 1.0);
    }
    const ContourScore strict = scoreContours(verticalLine(100, 41), verticalLine(100, 40), 0);
    EXPECT_EQ(strict.recall, 0.0);
    EXPECT_EQ(strict.precision, 0.0);
}

TEST(ContourScore, ThreePixelShiftScoresLow) {
    const ContourScore line = scoreContours(verticalLine(100, 43), verticalLine(100, 40), 1);
    EXPECT_EQ(line.recall, 0.0);
    EXPECT_EQ(line.precision, 0.0);
    // A shifted circle still meets itself where its tangent runs along the shift (about 60
    // degrees around the top and the bottom).
    const ContourScore shifted = scoreContours(circle(100, 53, 50, 30), circle(100, 50, 50, 30), 1);
    EXPECT_LT(shifted.recall, 0.5);
    EXPECT_LT(shifted.precision, 0.5);
    EXPECT_GT(shifted.recall, 0.0);
}

TEST(ContourScore, PartialDrawingsAndExtraLines) {
    const PixelMask truth = verticalLine(100, 40);
    PixelMask half(100, 100);
    for (int y = 10; y < 50; ++y)
        half.set(40, y);
    const ContourScore partial = scoreContours(half, truth, 1);
    EXPECT_EQ(partial.precision, 1.0);
    EXPECT_NEAR(partial.recall, 41.0 / 80.0, 1e-12); // row 50 is within 1 px of the drawn row 49

    PixelMask extra = truth;
    for (int y = 10; y < 90; ++y)
        extra.set(80, y);
    const ContourScore noisy = scoreContours(extra, truth, 1);
    EXPECT_EQ(noisy.recall, 1.0);
    EXPECT_NEAR(noisy.precision, 0.5, 1e-12);
}

TEST(ContourScore, EmptyMasksAndSizeMismatch) {
    const PixelMask empty(50, 50);
    const PixelMask line = verticalLine(50, 20);
    EXPECT_EQ(scoreContours(empty, line).recall, 0.0);
    EXPECT_EQ(scoreContours(empty, line).precision, 1.0);
    EXPECT_EQ(scoreContours(line, empty).precision, 0.0);
    EXPECT_EQ(scoreContours(line, empty).recall, 1.0);
    EXPECT_THROW(scoreContours(PixelMask(10, 10), PixelMask(10, 11)), lw::core::Error);
    EXPECT_THROW(scoreContours(line, line, -1), lw::core::Error);
}

TEST(PixelMask, DilationAndImageConversion) {
    PixelMask mask(7, 7);
    mask.set(3, 3);
    EXPECT_EQ(mask.dilated(1).count(), 9u);
    EXPECT_EQ(mask.dilated(2).count(), 25u);
    mask.set(0, 0);
    EXPECT_EQ(mask.dilated(1).count(), 13u); // clipped at the border
    const auto image = mask.toImage({255, 0, 0, 255}, {0, 0, 0, 255});
    EXPECT_EQ(PixelMask::fromImage(image), mask);
}

TEST(ContourScore, DiffImageColoursMatchesAndBothKindsOfMiss) {
    PixelMask truth(20, 20), drawn(20, 20);
    truth.set(5, 5);   // drawn beside it: matched
    drawn.set(6, 5);   // within 1 px of the truth: black
    drawn.set(15, 15); // nothing true near: red
    truth.set(2, 17);  // nothing drawn near: blue
    const lw::core::ImageRgba8 image = contourDiffImage(drawn, truth, 1);
    EXPECT_EQ(image.at(6, 5), (lw::core::Rgba8{0, 0, 0, 255}));
    EXPECT_EQ(image.at(5, 5), (lw::core::Rgba8{190, 190, 190, 255}));
    EXPECT_EQ(image.at(15, 15), (lw::core::Rgba8{230, 0, 0, 255}));
    EXPECT_EQ(image.at(2, 17), (lw::core::Rgba8{0, 70, 230, 255}));
    EXPECT_EQ(image.at(10, 10), (lw::core::Rgba8{255, 255, 255, 255}));
    EXPECT_THROW(contourDiffImage(PixelMask(3, 3), truth, 1), lw::core::Error);
}
