// Method 3's software rasterizer: coverage under the top-left rule, depth keys, segments.
#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"

#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <set>
#include <utility>
#include <vector>

namespace {

using lw::kernels::cpu::DepthBuffer;
using lw::kernels::cpu::forEachCoveredPixel;
using lw::kernels::cpu::kSubpixelScale;
using lw::kernels::cpu::ScreenSegment;
using lw::kernels::cpu::ScreenVertices;

// Vertices given in continuous pixel coordinates, snapped as projectVertices does.
ScreenVertices makeVertices(const std::vector<glm::dvec2>& points,
                            const std::vector<float>& keys = {}) {
    ScreenVertices v;
    v.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
        v.xy[i] = {std::int32_t(std::lround(points[i].x * double(kSubpixelScale))),
                   std::int32_t(std::lround(points[i].y * double(kSubpixelScale)))};
        v.key[i] = keys.empty() ? 1.0f : keys[i];
        v.invW[i] = 1.0f;
        v.facing[i] = 1.0f;
        v.front[i] = 1;
    }
    return v;
}

std::set<std::pair<int, int>> covered(const ScreenVertices& v, std::uint32_t a, std::uint32_t b,
                                      std::uint32_t c, int width = 16, int height = 16) {
    std::set<std::pair<int, int>> pixels;
    forEachCoveredPixel(v, a, b, c, width, height, [&](int x, int y, float) {
        pixels.insert({x, y});
    });
    return pixels;
}

TEST(ZBufferRasterizer, SingleTriangleFollowsTopLeftRule) {
    // Right triangle whose legs run through pixel centres: the left edge (x = 0.5) and the top
    // edge (y = 0.5) own their centres, the hypotenuse x + y = 5 does not.
    const ScreenVertices v = makeVertices({{0.5, 0.5}, {4.5, 0.5}, {0.5, 4.5}});
    std::set<std::pair<int, int>> expected;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i + j < 4; ++i)
            expected.insert({i, j});
    EXPECT_EQ(covered(v, 0, 1, 2), expected);
    EXPECT_EQ(covered(v, 0, 2, 1), expected) << "winding must not matter";
    EXPECT_EQ(expected.size(), 10u);
}

TEST(ZBufferRasterizer, RightAndBottomEdgesExcluded) {
    // Mirror image: now the edges through centres are the right (x = 4.5) and bottom (y = 4.5)
    // ones, which own nothing; the hypotenuse x + y = 5 is now a left edge and owns its centres.
    const ScreenVertices v = makeVertices({{4.5, 4.5}, {0.5, 4.5}, {4.5, 0.5}});
    std::set<std::pair<int, int>> expected;
    for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 4; ++i)
            if (i + j >= 4)
                expected.insert({i, j});
    EXPECT_EQ(covered(v, 0, 1, 2), expected);
}

TEST(ZBufferRasterizer, DegenerateAndOffscreenTrianglesCoverNothing) {
    const ScreenVertices v = makeVertices(
        {{0.5, 0.5}, {3.5, 3.5}, {6.5, 6.5}, {-9.0, -9.0}, {-5.0, -9.0}, {-9.0, -5.0}});
    EXPECT_TRUE(covered(v, 0, 1, 2).empty());
    EXPECT_TRUE(covered(v, 3, 4, 5).empty());
}

TEST(ZBufferRasterizer, SharedEdgesNeitherGapNorOverlap) {
    // A jittered grid of vertices triangulated with random diagonals: every pixel centre inside the
    // outer rectangle is covered exactly once, including centres that lie exactly on inner edges
    // (the jitter is on the 1/2-pixel lattice so many edges pass through centres).
    std::mt19937 random(1234);
    std::uniform_int_distribution<int> jitter(-2, 2);
    std::uniform_int_distribution<int> coin(0, 1);
    constexpr int kCells = 8, kStep = 6, kSize = kCells * kStep + 4;
    std::vector<glm::dvec2> points;
    for (int j = 0; j <= kCells; ++j)
        for (int i = 0; i <= kCells; ++i) {
            const bool border = i == 0 || j == 0 || i == kCells || j == kCells;
            const double dx = border ? 0.0 : 0.5 * jitter(random),
                         dy = border ? 0.0 : 0.5 * jitter(random);
            points.push_back({1.0 + i * kStep + dx, 1.0 + j * kStep + dy});
        }
    const ScreenVertices v = makeVertices(points);
    std::vector<int> count(std::size_t(kSize * kSize), 0);
    auto vertex = [](int i, int j) { return std::uint32_t(j * (kCells + 1) + i); };
    for (int j = 0; j < kCells; ++j)
        for (int i = 0; i < kCells; ++i) {
            const std::uint32_t a = vertex(i, j), b = vertex(i + 1, j), c = vertex(i + 1, j + 1),
                                d = vertex(i, j + 1);
            const std::uint32_t tris[2][3] = {{a, b, c}, {a, c, d}};
            const std::uint32_t other[2][3] = {{a, b, d}, {b, c, d}};
            for (const auto& t : coin(random) ? tris : other)
                forEachCoveredPixel(v, t[0], t[1], t[2], kSize, kSize, [&](int x, int y, float) {
                    ++count[std::size_t(y * kSize + x)];
                });
        }
    // The outer rectangle [1, 1 + kCells*kStep] has its left/top edges on integers, away from
    // centres.
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            const bool inside = x + 0.5 > 1.0 && x + 0.5 < 1.0 + kCells * kStep && y + 0.5 > 1.0 &&
                                y + 0.5 < 1.0 + kCells * kStep;
            EXPECT_EQ(count[std::size_t(y * kSize + x)], inside ? 1 : 0)
                << "pixel " << x << "," << y;
        }
}

TEST(ZBufferRasterizer, DepthKeyIsInterpolatedAndNearestWins) {
    // Keys 1, 2, 3 at the corners: at a centre the key is the barycentric mix.
    const ScreenVertices v = makeVertices({{0.5, 0.5}, {8.5, 0.5}, {0.5, 8.5}}, {1.0f, 2.0f, 3.0f});
    forEachCoveredPixel(v, 0, 1, 2, 16, 16, [&](int x, int y, float key) {
        const double expected = 1.0 + double(x) / 8.0 + 2.0 * double(y) / 8.0;
        EXPECT_NEAR(key, expected, 1e-5) << x << "," << y;
    });

    // Two overlapping squares at different depths, drawn on two threads: the nearer key stays.
    ScreenVertices quads =
        makeVertices({{0, 0}, {10, 0}, {10, 10}, {0, 10}, {5, 5}, {15, 5}, {15, 15}, {5, 15}},
                     {0.5f, 0.5f, 0.5f, 0.5f, 0.8f, 0.8f, 0.8f, 0.8f});
    const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7};
    DepthBuffer depth;
    depth.reset(16, 16);
    lw::kernels::cpu::drawTrianglesDepth(quads, indices.data(), 4, depth, 2);
    EXPECT_FLOAT_EQ(depth.at(2, 2), 0.5f);
    EXPECT_FLOAT_EQ(depth.at(7, 7), 0.8f);
    EXPECT_FLOAT_EQ(depth.at(12, 12), 0.8f);
    EXPECT_FLOAT_EQ(depth.at(12, 2), 0.0f);
}

TEST(ZBufferRasterizer, SegmentsUseLineStepsAndResolveAgainstSurface) {
    // A horizontal segment across a surface square: visible where it is in front, hidden behind.
    ScreenVertices quad =
        makeVertices({{0, 0}, {16, 0}, {16, 16}, {0, 16}}, {0.6f, 0.6f, 0.6f, 0.6f});
    const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
    DepthBuffer surface, lines;
    surface.reset(32, 32);
    lines.reset(32, 32);
    lw::kernels::cpu::drawTrianglesDepth(quad, indices.data(), 2, surface);
    const std::vector<ScreenSegment> segments = {
        {{2.5, 4.5}, {28.5, 4.5}, 0.4f, 0.4f}, // behind the square (smaller key = farther)
        {{2.5, 8.5}, {28.5, 8.5}, 0.9f, 0.9f}, // in front
    };
    lw::kernels::cpu::drawSegmentsDepth(segments.data(), segments.size(), lines);
    std::vector<std::uint8_t> mask(32 * 32), all(32 * 32);
    lw::kernels::cpu::resolveSilhouette(surface, lines, 1e-4f, true, mask.data());
    lw::kernels::cpu::resolveSilhouette(surface, lines, 1e-4f, false, all.data());
    for (int x = 2; x <= 28; ++x) {
        EXPECT_EQ(all[std::size_t(4 * 32 + x)], 1) << x;
        EXPECT_EQ(mask[std::size_t(8 * 32 + x)], 1) << x;
        // Hidden inside the square; visible once the 3x3 neighbourhood reaches the empty side.
        EXPECT_EQ(mask[std::size_t(4 * 32 + x)], x >= 15 ? 1 : 0) << x;
    }
}

} // namespace
