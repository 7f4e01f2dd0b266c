// Stroke pruning (SilhouetteSettings::minStrokePixels): the 8-connected groups of a line drawing
// under a size go, on every method and back-end present, after the method has drawn, and the
// one-pixel gaps between stroke ends are closed; the contours stay pixel for pixel.
#include "backends_under_test.h"
#include "lw/kernels/stroke_components.h"
#include "lw/render/camera.h"
#include "lw/render/pixel_mask.h"
#include "lw/render/renderer_factory.h"
#include "lw/volume/volume.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

namespace {

using namespace lw::render;

struct MaskCase {
    const char* name;
    std::vector<glm::ivec2> on;
    int minPixels;
    std::size_t removed;
    int gapPixels = 0;
};

class ComponentFilter : public testing::TestWithParam<MaskCase> {};

TEST_P(ComponentFilter, RemovesExactlyTheSmallGroups) {
    PixelMask mask(12, 8);
    for (const glm::ivec2 p : GetParam().on)
        mask.set(p.x, p.y);
    const std::size_t before = mask.count();
    const int gap = GetParam().gapPixels;
    EXPECT_EQ(mask.removeComponentsSmallerThan(GetParam().minPixels, gap), GetParam().removed);
    EXPECT_EQ(mask.count(), before - GetParam().removed);
    for (const std::size_t size : mask.componentSizes(gap))
        EXPECT_GE(size, std::size_t(std::max(GetParam().minPixels, 1)));
}

// Pieces of 2, 2 and 2 pixels with one-pixel gaps, then a pixel two pixels further on.
const std::vector<glm::ivec2> kBrokenLine = {{0, 1}, {1, 1}, {3, 1}, {4, 1},
                                             {6, 2}, {7, 2}, {10, 2}};

// A 6-pixel row, a diagonal of 3 (8-connected: one group), and a lone pixel.
const std::vector<glm::ivec2> kRowDiagonalDot = {{0, 0}, {1, 0}, {2, 0}, {3, 0},  {4, 0},
                                                 {5, 0}, {8, 2}, {9, 3}, {10, 4}, {1, 6}};

// Groups touching the image's edges and corners (the search must not wrap around into the next
// row): four lone corners, a 3-pixel run along the bottom edge, a 2-pixel run down the right
// edge one pixel short of the bottom-right corner.
const std::vector<glm::ivec2> kAtTheEdges = {{0, 0}, {11, 0}, {0, 7},  {11, 7}, {5, 7},
                                             {6, 7}, {7, 7},  {11, 4}, {11, 5}};

INSTANTIATE_TEST_SUITE_P(
    Masks, ComponentFilter,
    testing::Values(MaskCase{"off", kRowDiagonalDot, 0, 0},
                    MaskCase{"one keeps everything", kRowDiagonalDot, 1, 0},
                    MaskCase{"lone pixel", kRowDiagonalDot, 2, 1},
                    MaskCase{"diagonal is one group of three", kRowDiagonalDot, 4, 4},
                    MaskCase{"the row goes too", kRowDiagonalDot, 7, 10},
                    MaskCase{"empty", {}, 10, 0}, MaskCase{"corners go", kAtTheEdges, 2, 4},
                    MaskCase{"edge runs go too", kAtTheEdges, 4, 9},
                    MaskCase{"corner bridged to the right run", kAtTheEdges, 3, 3, 1},
                    // A line broken by one-pixel gaps is one stroke when
                    // gaps are bridged; two pixels apart is too far.
                    MaskCase{"broken line alone", kBrokenLine, 5, 7, 0},
                    MaskCase{"broken line bridged", kBrokenLine, 5, 1, 1},
                    MaskCase{"wide gap not bridged", kBrokenLine, 7, 7, 1}),
    [](const testing::TestParamInfo<MaskCase>& info) {
        std::string name = info.param.name;
        std::replace(name.begin(), name.end(), ' ', '_');
        return name;
    });

struct BridgeCase {
    const char* name;
    std::vector<glm::ivec2> on;
    std::vector<glm::ivec2> bridges; // the pixels bridgesStrokeEnds names, row by row
};

std::vector<glm::ivec2> row(int y, int x0, int x1) {
    std::vector<glm::ivec2> pixels;
    for (int x = x0; x <= x1; ++x)
        pixels.push_back({x, y});
    return pixels;
}

std::vector<glm::ivec2> joined(std::vector<glm::ivec2> a, const std::vector<glm::ivec2>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
}

std::vector<glm::ivec2> antiDiagonal(int sum) { // x + y = sum, inside 12 x 8
    std::vector<glm::ivec2> pixels;
    for (int y = 0; y < 8; ++y)
        if (sum - y >= 0 && sum - y < 12)
            pixels.push_back({sum - y, y});
    return pixels;
}

class StrokeEndBridge : public testing::TestWithParam<BridgeCase> {};

TEST_P(StrokeEndBridge, DrawsExactlyThePixelBetweenTwoEnds) {
    PixelMask mask(12, 8);
    for (const glm::ivec2 p : GetParam().on)
        mask.set(p.x, p.y);
    std::vector<glm::ivec2> found;
    for (int y = 0; y < mask.height(); ++y)
        for (int x = 0; x < mask.width(); ++x)
            if (lw::kernels::bridgesStrokeEnds(mask.pixels().data(), 12, 8, x, y))
                found.push_back({x, y});
    EXPECT_EQ(found, GetParam().bridges);
    PixelMask expected = mask;
    for (const glm::ivec2 p : GetParam().bridges)
        expected.set(p.x, p.y);
    EXPECT_EQ(mask.bridgeStrokeEnds(), GetParam().bridges.size());
    EXPECT_EQ(mask, expected);
}

INSTANTIATE_TEST_SUITE_P(
    Masks, StrokeEndBridge,
    testing::Values(BridgeCase{"gap in a row", joined(row(3, 1, 2), row(3, 4, 5)), {{3, 3}}},
                    BridgeCase{"gap in a diagonal", {{1, 1}, {2, 2}, {4, 4}, {5, 5}}, {{3, 3}}},
                    // Ends a knight's move apart: of the two pixels between them, the upper one.
                    BridgeCase{"knights move", joined(row(3, 0, 2), row(4, 4, 6)), {{3, 3}}},
                    BridgeCase{"lone pixels", {{3, 3}, {5, 3}}, {{4, 3}}},
                    BridgeCase{"at the image edge", {{0, 0}, {2, 0}}, {{1, 0}}},
                    BridgeCase{"gap of two pixels", joined(row(3, 1, 2), row(3, 5, 6)), {}},
                    BridgeCase{"parallel rows", joined(row(2, 0, 11), row(4, 0, 11)), {}},
                    BridgeCase{"parallel diagonals", joined(antiDiagonal(4), antiDiagonal(8)), {}},
                    BridgeCase{
                        "end beside a column",
                        joined(row(3, 0, 2), {{4, 0}, {4, 1}, {4, 2}, {4, 3}, {4, 4}, {4, 5}}),
                        {}},
                    // One end has a fork behind it: two neighbours, not an end.
                    BridgeCase{"forked end", joined(row(3, 4, 6), {{2, 3}, {1, 2}, {1, 4}}), {}}),
    [](const testing::TestParamInfo<BridgeCase>& info) {
        std::string name = info.param.name;
        std::replace(name.begin(), name.end(), ' ', '_');
        std::replace(name.begin(), name.end(), '\'', '_');
        return name;
    });

// Pruning as the frames get it: a line broken by one-pixel gaps is kept as one stroke (gap 1) and
// drawn whole; a wider gap stays open.
TEST(StrokePruneAndBridge, KeepsTheBrokenLineAndClosesItsGaps) {
    PixelMask mask(12, 8);
    for (const glm::ivec2 p : kBrokenLine)
        mask.set(p.x, p.y);
    EXPECT_EQ(mask.pruneStrokes(5, 1), 1u); // the pixel two further on
    PixelMask expected(12, 8);
    for (const glm::ivec2 p : joined(row(1, 0, 4), row(2, 6, 7)))
        expected.set(p.x, p.y);
    expected.set(5, 1); // (4, 1) to (6, 2): a knight's move, the upper pixel between
    EXPECT_EQ(mask, expected);
    PixelMask unbridged(12, 8);
    for (const glm::ivec2 p : kBrokenLine)
        unbridged.set(p.x, p.y);
    EXPECT_EQ(unbridged.pruneStrokes(5, 0), 7u); // no gap: every piece is short
    EXPECT_EQ(unbridged.count(), 0u);
}

// A random mask: runs and lone pixels, dense enough that groups merge across gaps.
PixelMask randomStrokes(int width, int height, unsigned seed) {
    PixelMask mask(width, height);
    std::mt19937 random(seed);
    const int strokes = std::max(1, width * height / 40);
    for (int i = 0; i < strokes; ++i) {
        int x = int(random() % unsigned(width)), y = int(random() % unsigned(height));
        const int length = 1 + int(random() % 12);
        const int dx = int(random() % 3) - 1, dy = int(random() % 3) - 1;
        for (int step = 0; step < length && x >= 0 && y >= 0 && x < width && y < height; ++step) {
            mask.set(x, y);
            x += dx;
            y += dy;
        }
    }
    return mask;
}

// A sparser random mask of dashed strokes: pieces of 1 to 6 pixels with one-pixel gaps, in the
// eight directions, so that many gaps lie between stroke ends and get bridged.
PixelMask dashedStrokes(int width, int height, unsigned seed) {
    PixelMask mask(width, height);
    std::mt19937 random(seed);
    const int strokes = std::max(1, width * height / 150);
    for (int i = 0; i < strokes; ++i) {
        glm::ivec2 p(int(random() % unsigned(width)), int(random() % unsigned(height)));
        glm::ivec2 step(int(random() % 3) - 1, int(random() % 3) - 1);
        if (step == glm::ivec2(0))
            step.x = 1;
        for (int dash = 0, dashes = 1 + int(random() % 4); dash < dashes; ++dash) {
            for (int n = 1 + int(random() % 6); n > 0 && mask.contains(p.x, p.y); --n, p += step)
                mask.set(p.x, p.y);
            p += step; // the gap
        }
    }
    return mask;
}

// The device's rules (lw/kernels/stroke_components.h), run on the host: each pixel's unions in a
// random order, as parallel threads may run them, then the groups' sizes and the short groups
// cleared, as the kernels do. The result must be PixelMask's.
PixelMask pruneByUnionFind(const PixelMask& mask, int minPixels, int gapPixels, unsigned seed) {
    const int width = mask.width(), height = mask.height();
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    const std::uint8_t* on = mask.pixels().data();
    std::vector<std::uint32_t> labels(pixels);
    for (std::size_t i = 0; i < pixels; ++i)
        labels[i] = on[i] ? std::uint32_t(i) : lw::kernels::kNotAStrokePixel;
    std::vector<std::uint32_t> order(pixels);
    std::iota(order.begin(), order.end(), 0u);
    std::shuffle(order.begin(), order.end(), std::mt19937(seed));
    for (const std::uint32_t i : order)
        lw::kernels::uniteWithEarlierNeighbours(
            on, labels.data(), width, height, 1 + gapPixels, int(i % std::uint32_t(width)),
            int(i / std::uint32_t(width)), lw::kernels::LabelCompareAndSwap{});
    std::vector<std::uint32_t> sizes(pixels, 0);
    for (std::size_t i = 0; i < pixels; ++i)
        if (on[i])
            ++sizes[lw::kernels::strokeRoot(labels.data(), std::uint32_t(i))];
    PixelMask out = mask;
    for (std::size_t i = 0; i < pixels; ++i)
        if (on[i] && sizes[lw::kernels::strokeRoot(labels.data(), std::uint32_t(i))] <
                         std::uint32_t(minPixels))
            out.pixels()[i] = 0;
    return out;
}

TEST(StrokeUnionFind, FindsPixelMasksGroupsInAnyOrder) {
    for (const glm::ivec2 size : {glm::ivec2(1, 1), glm::ivec2(1, 37), glm::ivec2(33, 9),
                                  glm::ivec2(64, 64), glm::ivec2(257, 31)})
        for (const int gap : {0, 1})
            for (const int minPixels : {2, 5, 12})
                for (const unsigned seed : {1u, 2u}) {
                    const PixelMask mask = randomStrokes(size.x, size.y, seed);
                    PixelMask expected = mask;
                    expected.removeComponentsSmallerThan(minPixels, gap);
                    EXPECT_TRUE(pruneByUnionFind(mask, minPixels, gap, seed * 7) == expected)
                        << size.x << "x" << size.y << " gap " << gap << " min " << minPixels
                        << " seed " << seed;
                }
}

// The groups by the plainest search there is: a breadth-first walk from every unlabelled line
// pixel over every pixel within `reach`, bounds checked. Returns each pixel's group number (-1:
// off) and the groups' sizes in the order of their first pixels.
std::pair<std::vector<int>, std::vector<std::size_t>>
groupsByBreadthFirstSearch(const PixelMask& mask, int reach) {
    std::vector<int> group(mask.pixels().size(), -1);
    std::vector<std::size_t> sizes;
    for (int y = 0; y < mask.height(); ++y)
        for (int x = 0; x < mask.width(); ++x) {
            if (!mask.get(x, y) || group[std::size_t(y * mask.width() + x)] >= 0)
                continue;
            std::vector<glm::ivec2> queue{{x, y}};
            group[std::size_t(y * mask.width() + x)] = int(sizes.size());
            for (std::size_t next = 0; next < queue.size(); ++next)
                for (int dy = -reach; dy <= reach; ++dy)
                    for (int dx = -reach; dx <= reach; ++dx) {
                        const glm::ivec2 n = queue[next] + glm::ivec2(dx, dy);
                        if (mask.contains(n.x, n.y) && mask.get(n.x, n.y) &&
                            group[std::size_t(n.y * mask.width() + n.x)] < 0) {
                            group[std::size_t(n.y * mask.width() + n.x)] = int(sizes.size());
                            queue.push_back(n);
                        }
                    }
            sizes.push_back(queue.size());
        }
    return {group, sizes};
}

// Turns off the pixels of `mask` whose group (groupsByBreadthFirstSearch) is under `minPixels`.
void clearGroupsUnder(PixelMask& mask,
                      const std::pair<std::vector<int>, std::vector<std::size_t>>& groups,
                      std::size_t minPixels) {
    const auto& [group, sizes] = groups;
    for (std::size_t i = 0; i < group.size(); ++i)
        if (group[i] >= 0 && sizes[std::size_t(group[i])] < minPixels)
            mask.pixels()[i] = 0;
}

// PixelMask's search (a union-find over the mask's runs, row cursors for the neighbours) against
// the plain one, on sizes around its eight-pixel row skipping, at gaps 0 to 2; and pruning, which
// does its three steps in one walk, against them one after the other: the groups within the gap
// removed when short, the separate bridge pass, the 8-connected pieces under half the length
// removed.
TEST(StrokeGroups, MatchTheBreadthFirstSearch) {
    std::size_t bridged = 0, piecesRemoved = 0; // over all cases: the later steps are exercised
    for (const glm::ivec2 size :
         {glm::ivec2(1, 1), glm::ivec2(1, 37), glm::ivec2(7, 5), glm::ivec2(9, 3),
          glm::ivec2(33, 9), glm::ivec2(64, 64), glm::ivec2(257, 31)})
        for (const int gap : {0, 1, 2})
            for (const unsigned seed : {3u, 4u, 5u, 6u}) {
                const PixelMask mask = seed % 2 ? randomStrokes(size.x, size.y, seed)
                                                : dashedStrokes(size.x, size.y, seed);
                const auto groups = groupsByBreadthFirstSearch(mask, 1 + gap);
                EXPECT_EQ(mask.componentSizes(gap), groups.second)
                    << size.x << "x" << size.y << " gap " << gap << " seed " << seed;
                for (const int minPixels : {2, 5, 12}) {
                    PixelMask expected = mask;
                    clearGroupsUnder(expected, groups, std::size_t(minPixels));
                    PixelMask removed = mask;
                    removed.removeComponentsSmallerThan(minPixels, gap);
                    EXPECT_TRUE(removed == expected) << size.x << "x" << size.y << " gap " << gap;
                    if (gap >= 1) {
                        bridged += expected.bridgeStrokeEnds();
                        const std::size_t before = expected.count();
                        clearGroupsUnder(expected, groupsByBreadthFirstSearch(expected, 1),
                                         std::size_t(minPixels / 2));
                        piecesRemoved += before - expected.count();
                    }
                    PixelMask pruned = mask;
                    pruned.pruneStrokes(minPixels, gap);
                    EXPECT_TRUE(pruned == expected) << size.x << "x" << size.y << " gap " << gap
                                                    << " seed " << seed << " min " << minPixels;
                }
            }
    EXPECT_GT(bridged, 100u);
    EXPECT_GT(piecesRemoved, 100u);
}

// A sphere of radius 18 voxels with dust: single voxels above the iso-value far from it, each a
// tiny closed surface whose contour is a speck of a few pixels.
lw::volume::Volume sphereWithDust() {
    const glm::ivec3 dims(64, 64, 64);
    lw::volume::Volume volume(dims, lw::volume::VoxelType::Float32);
    float* voxels = volume.dataAs<float>();
    const glm::vec3 centre(31.5f);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                voxels[volume.index(x, y, z)] = 18.0f - glm::length(glm::vec3(x, y, z) - centre);
    std::mt19937 random(11);
    for (int dust = 0; dust < 24; ++dust) {
        glm::ivec3 p;
        do {
            p = glm::ivec3(2 + int(random() % 60), 2 + int(random() % 60), 2 + int(random() % 60));
        } while (glm::length(glm::vec3(p) - centre) < 24.0f);
        voxels[volume.index(p.x, p.y, p.z)] = 1.0f;
    }
    return volume;
}

struct MethodOnBackend {
    SilhouetteMethod method;
    Backend backend;
};

class StrokePruning : public testing::TestWithParam<MethodOnBackend> {};

TEST_P(StrokePruning, DropsTheDustAndKeepsTheContour) {
    const lw::volume::Volume volume = sphereWithDust();
    auto renderer = createSilhouetteRenderer(GetParam().method, GetParam().backend);
    renderer->setVolume(volume);
    CameraSetup setup;
    setup.bounds = volumeBounds(volume);
    setup.azimuthDeg = 30;
    setup.elevationDeg = 20;
    const Camera camera(setup, 256, 256);
    SilhouetteSettings settings;
    settings.isoReal = 0.5;
    const SilhouetteFrame raw = renderer->render(camera, settings);
    const std::vector<std::size_t> sizes = raw.lines.componentSizes();
    const std::size_t specks = std::size_t(
        std::count_if(sizes.begin(), sizes.end(), [](std::size_t s) { return s < 12; }));
    ASSERT_GE(specks, 5u) << "the dust should draw specks to remove";
    const std::size_t largest = *std::max_element(sizes.begin(), sizes.end());
    ASSERT_GT(largest, 200u) << "the sphere's contour";

    settings.minStrokePixels = 12;
    const SilhouetteFrame pruned = renderer->render(camera, settings);
    for (const std::size_t size : pruned.lines.componentSizes(kStrokeGapPixels))
        EXPECT_GE(size, 12u);
    for (const std::size_t size : pruned.lines.componentSizes())
        EXPECT_GE(size, 6u);
    // What stays is exactly what the unpruned frame had there, with its one-pixel gaps between
    // stroke ends closed: the contour is untouched.
    PixelMask expected = raw.lines;
    expected.pruneStrokes(12, kStrokeGapPixels);
    EXPECT_EQ(pruned.lines, expected);
    // The CUDA back-ends prune on the device (method 1 its mask read back from GL), the CPU ones
    // on the host; the result is the same.
    EXPECT_EQ(pruned.strokesPruned, GetParam().backend == Backend::Cuda);
    EXPECT_GE(pruned.lines.count(), largest);
}

std::vector<MethodOnBackend> methodsOnBackends() {
#ifdef LINEWORK_STROKE_PRUNING_METHOD1
    // Method 1 needs a GL context: it runs in a binary of its own (render_stroke_pruning_gl_tests).
    const std::vector<SilhouetteMethod> methods{SilhouetteMethod::GeometryShader};
#else
    const std::vector<SilhouetteMethod> methods{SilhouetteMethod::RayCastVisibility,
                                                SilhouetteMethod::ZBuffer};
#endif
    std::vector<MethodOnBackend> cases;
    for (const Backend backend : lw::test::backendsUnderTest())
        for (const SilhouetteMethod method : methods)
            cases.push_back({method, backend});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(Methods, StrokePruning, testing::ValuesIn(methodsOnBackends()),
                         [](const testing::TestParamInfo<MethodOnBackend>& info) {
                             return "method" + std::to_string(int(info.param.method)) + "_" +
                                    std::string(backendName(info.param.backend));
                         });

} // namespace

// PixelMask::strokeCoverage, the live panels' antialiased strokes through the line pixels.
namespace {

std::uint8_t coverageAt(const std::vector<std::uint8_t>& coverage, const PixelMask& mask, int x,
                        int y) {
    return coverage[std::size_t(y) * std::size_t(mask.width()) + std::size_t(x)];
}

} // namespace

TEST(StrokeCoverage, OnePixelWideIsTheMaskItself) {
    PixelMask mask(37, 23);
    std::mt19937 random(7);
    for (int i = 0; i < 120; ++i)
        mask.set(int(random() % 37), int(random() % 23));
    const std::vector<std::uint8_t> coverage = mask.strokeCoverage(1.0);
    for (int y = 0; y < mask.height(); ++y)
        for (int x = 0; x < mask.width(); ++x)
            EXPECT_EQ(coverageAt(coverage, mask, x, y), mask.get(x, y) ? 255 : 0) << x << "," << y;
}

// A row of line pixels is a band `width` wide: each row beside it gets the share of the band it
// lies in (0.5 of a row is 128).
TEST(StrokeCoverage, AStraightLineGetsTheBandsCoverage) {
    struct Expected {
        double width;
        std::vector<std::uint8_t> rowsAway; // coverage 0, 1, 2, 3 rows from the line
    };
    for (const Expected& expected :
         {Expected{2.0, {255, 128, 0, 0}}, Expected{3.0, {255, 255, 0, 0}},
          Expected{4.0, {255, 255, 128, 0}}}) {
        PixelMask mask(20, 11);
        for (int x = 0; x < 20; ++x)
            mask.set(x, 5);
        const std::vector<std::uint8_t> coverage = mask.strokeCoverage(expected.width);
        for (int away = 0; away < 4; ++away)
            for (const int y : {5 - away, 5 + away})
                for (int x = 0; x < 20; ++x)
                    EXPECT_EQ(coverageAt(coverage, mask, x, y), expected.rowsAway[away])
                        << "width " << expected.width << ", pixel " << x << "," << y;
    }
}

// A lone pixel is a disc; one in a corner is cut by the border, not read past it.
TEST(StrokeCoverage, ALonePixelIsADiscCutAtTheBorder) {
    PixelMask mask(6, 6);
    mask.set(0, 0);
    const std::vector<std::uint8_t> coverage = mask.strokeCoverage(3.0); // reach 2 pixels
    EXPECT_EQ(coverageAt(coverage, mask, 0, 0), 255);
    EXPECT_EQ(coverageAt(coverage, mask, 1, 0), 255);
    EXPECT_EQ(coverageAt(coverage, mask, 1, 1), std::lround((2.0 - std::sqrt(2.0)) * 255.0));
    EXPECT_EQ(coverageAt(coverage, mask, 2, 0), 0);
    EXPECT_EQ(coverageAt(coverage, mask, 2, 1), 0);
    EXPECT_EQ(std::count_if(coverage.begin(), coverage.end(), [](std::uint8_t c) { return c > 0; }),
              4);
}
