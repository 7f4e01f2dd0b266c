// Visible polylines and their SVG: the frame's own lines as vectors. On analytic shapes drawn by
// method 3 the silhouette chains close into loops, the polylines lie on the mask, cover it, and
// the SVG holds exactly them.
#include "lw/evaluation/analytic_shapes.h"
#include "lw/kernels/silhouette_segment.h"
#include "lw/render/contour_triangles.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/svg_lines.h"
#include "lw/render/visible_polylines.h"
#include "lw/volume/phantom.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>
#include <random>
#include <sstream>
#include <string>
#include <unordered_map>

namespace {

using namespace lw::render;
using namespace lw::evaluation;

struct ShapeView {
    const char* shape;
    double az, el;
    std::size_t closedLoopsAtLeast; // of the chains before visibility
};

class VisiblePolylines : public testing::TestWithParam<ShapeView> {
protected:
    void SetUp() override {
        const auto shape = makeAnalyticShape(GetParam().shape);
        volume = sampleShape(*shape, 64);
        CameraSetup setup;
        setup.bounds = shape->bounds();
        setup.azimuthDeg = GetParam().az;
        setup.elevationDeg = GetParam().el;
        camera = Camera(setup, 300, 300);
        auto renderer = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cpu);
        renderer->setVolume(volume);
        SilhouetteSettings settings;
        settings.isoReal = kShapeIso;
        frame = renderer->render(camera, settings);
        mesh = *renderer->surfaceMesh();
    }

    lw::volume::Volume volume;
    Camera camera;
    SilhouetteFrame frame;
    Mesh mesh;
};

// The pixels a polyline passes through (sampled at a quarter pixel).
PixelMask rasterize(const std::vector<Polyline>& lines, int width, int height) {
    PixelMask mask(width, height);
    for (const Polyline& line : lines) {
        const std::size_t n = line.points.size();
        for (std::size_t i = 0; i + 1 < n + (line.closed ? 1 : 0); ++i) {
            const glm::vec2 a = line.points[i], b = line.points[(i + 1) % n];
            const int steps = std::max(1, int(glm::length(b - a) * 4.0f));
            for (int s = 0; s <= steps; ++s) {
                const glm::vec2 p = a + (b - a) * (float(s) / float(steps));
                if (mask.contains(int(p.x), int(p.y)))
                    mask.set(int(p.x), int(p.y));
            }
        }
    }
    return mask;
}

// Share of `a`'s on pixels that have an on pixel of `b` within one pixel.
double coveredWithinOnePixel(const PixelMask& a, const PixelMask& b) {
    const PixelMask near = b.dilated(1);
    std::size_t on = 0, covered = 0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i)
        if (a.pixels()[i]) {
            ++on;
            covered += near.pixels()[i] != 0;
        }
    return on == 0 ? 1.0 : double(covered) / double(on);
}

TEST_P(VisiblePolylines, ChainsCloseAndThePolylinesAreTheFramesLines) {
    ASSERT_GT(frame.lines.count(), 100u) << "an empty frame tests nothing";
    const std::vector<SilhouetteChain> chains = chainSilhouette(mesh, camera);
    std::size_t closed = 0;
    for (const SilhouetteChain& chain : chains)
        closed += chain.closed ? 1 : 0;
    EXPECT_GE(closed, GetParam().closedLoopsAtLeast) << chains.size() << " chains";

    const std::vector<Polyline> lines = visiblePolylines(mesh, camera, frame.lines);
    ASSERT_FALSE(lines.empty());
    const PixelMask drawn = rasterize(lines, camera.width(), camera.height());
    // On the mask (within the one-pixel tolerance they were cut with) and covering it.
    EXPECT_GE(coveredWithinOnePixel(drawn, frame.lines), 0.999);
    EXPECT_GE(coveredWithinOnePixel(frame.lines, drawn), 0.97);
}

TEST_P(VisiblePolylines, SvgHoldsExactlyThePolylines) {
    const std::vector<Polyline> lines = visiblePolylines(mesh, camera, frame.lines);
    const std::string svg =
        silhouetteSvg(lines, camera.width(), camera.height(), {"#102030", 1.5, "#ffffff"});
    EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
    EXPECT_NE(svg.find("viewBox=\"0 0 300 300\""), std::string::npos);
    EXPECT_NE(svg.find("stroke=\"#102030\""), std::string::npos);
    EXPECT_EQ(svg.substr(svg.size() - 7), "</svg>\n");
    // One path per polyline, its points the polyline's (to the two decimals written).
    std::size_t paths = 0, closedPaths = 0, at = 0;
    while ((at = svg.find("<path d=\"", at)) != std::string::npos) {
        const std::size_t end = svg.find('"', at + 9);
        const std::string d = svg.substr(at + 9, end - at - 9);
        ASSERT_LT(paths, lines.size());
        const Polyline& line = lines[paths];
        std::istringstream in(d);
        char command = 0;
        float x = 0, y = 0;
        std::size_t points = 0;
        while (in >> command && command != 'Z' && in >> x >> y) {
            ASSERT_LT(points, line.points.size());
            EXPECT_NEAR(x, line.points[points].x, 0.006f);
            EXPECT_NEAR(y, line.points[points].y, 0.006f);
            ++points;
        }
        EXPECT_EQ(points, line.points.size());
        closedPaths += command == 'Z' ? 1 : 0;
        ++paths;
        at = end;
    }
    EXPECT_EQ(paths, lines.size());
    std::size_t closedLines = 0;
    for (const Polyline& line : lines)
        closedLines += line.closed ? 1 : 0;
    EXPECT_EQ(closedPaths, closedLines);
}

// The hidden parts: off the frame's lines, and with the visible parts the whole contour (what
// the frame draws without visibility); none when nothing was tested. The linked tori hide part
// of each other's contour at every view.
TEST(HiddenPolylines, WithTheVisibleOnesTheyAreTheWholeContour) {
    const auto shape = makeAnalyticShape("tori");
    const lw::volume::Volume volume = sampleShape(*shape, 64);
    CameraSetup setup;
    setup.bounds = shape->bounds();
    setup.azimuthDeg = 200;
    setup.elevationDeg = -35;
    const Camera camera(setup, 300, 300);
    auto renderer = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cpu);
    renderer->setVolume(volume);
    SilhouetteSettings settings;
    settings.isoReal = kShapeIso;
    settings.minStrokePixels = 0;
    const SilhouetteFrame visible = renderer->render(camera, settings);
    const Mesh mesh = *renderer->surfaceMesh();
    settings.visibility = false;
    const SilhouetteFrame all = renderer->render(camera, settings);
    ASSERT_GT(all.lines.count(), visible.lines.count() + 50) << "nothing hidden: tests nothing";

    const PolylineSplit split = splitPolylines(mesh, camera, visible.lines, {}, true);
    ASSERT_FALSE(split.hidden.empty());
    const PixelMask hidden = rasterize(split.hidden, 300, 300);
    // Away from the visible lines (a run ends within a pixel or two of where they begin).
    EXPECT_LE(coveredWithinOnePixel(hidden, visible.lines), 0.15);
    // Visible and hidden together: every line the frame draws without visibility.
    PixelMask both = rasterize(split.visible, 300, 300);
    for (std::size_t i = 0; i < both.pixels().size(); ++i)
        if (hidden.pixels()[i])
            both.set(int(i % 300), int(i / 300));
    EXPECT_GE(coveredWithinOnePixel(all.lines, both), 0.97);
    // Without visibility nothing is hidden.
    EXPECT_TRUE(splitPolylines(mesh, camera, all.lines, {}, true).hidden.empty());
    EXPECT_TRUE(splitPolylines(mesh, camera, visible.lines, {}, false).hidden.empty());

    // The SVG draws them beneath, thin, dashed and grey: one more group, one path each.
    const std::string svg =
        silhouetteSvg(split.visible, 300, 300, {"#000000", 2.0, ""}, split.hidden);
    const std::size_t hiddenGroup = svg.find("stroke-dasharray=\"8.000 6.000\"");
    ASSERT_NE(hiddenGroup, std::string::npos);
    EXPECT_LT(hiddenGroup, svg.find("stroke=\"#000000\""));
    EXPECT_NE(svg.find(std::string("stroke=\"") + kHiddenLineColour + "\""), std::string::npos);
    std::size_t paths = 0;
    for (std::size_t at = 0; (at = svg.find("<path ", at)) != std::string::npos; ++at)
        ++paths;
    EXPECT_EQ(paths, split.visible.size() + split.hidden.size());
}

// A chain through the given image points (unprojected at mid depth), and the mask a frame draws
// for it: every pixel the line passes through.
SilhouetteChain chainThrough(const Camera& camera, const std::vector<glm::dvec2>& pixels) {
    SilhouetteChain chain;
    for (const glm::dvec2& p : pixels)
        chain.points.push_back(glm::vec3(camera.unproject(p, 0.0)));
    return chain;
}
void drawLine(const std::vector<glm::dvec2>& pixels, PixelMask& mask) {
    for (std::size_t i = 0; i + 1 < pixels.size(); ++i)
        for (int s = 0; s <= 100; ++s) {
            const glm::dvec2 p = pixels[i] + (pixels[i + 1] - pixels[i]) * (s / 100.0);
            mask.set(int(std::floor(p.x)), int(std::floor(p.y)));
        }
}
double lengthOf(const std::vector<Polyline>& lines) {
    double length = 0.0;
    for (const Polyline& line : lines)
        for (std::size_t i = 0; i + 1 < line.points.size(); ++i)
            length += glm::length(line.points[i + 1] - line.points[i]);
    return length;
}
// Distance of `p` to the polyline through `pixels`.
double distanceTo(glm::dvec2 p, const std::vector<glm::dvec2>& pixels) {
    double best = 1e9;
    for (std::size_t i = 0; i + 1 < pixels.size(); ++i) {
        const glm::dvec2 a = pixels[i], ab = pixels[i + 1] - a;
        const double t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
        best = std::min(best, glm::length(p - (a + t * ab)));
    }
    return best;
}

// Where lines crowd, a hidden chain runs a pixel beside a visible one, well within the one-pixel
// tolerance of the visible line's pixels: it must come out hidden, whole, and not as a second
// visible stroke (the false hatching of the exports); the drawn chain must come out whole.
TEST(VisiblePolylinesOwnPixels, AHiddenChainAPixelBesideAVisibleLineStaysHidden) {
    const Camera camera;
    // Slanted, so the raster steps and the hidden chain meets the drawn pixels at each step.
    std::vector<glm::dvec2> drawn, beside;
    for (int i = 0; i <= 20; ++i) {
        const glm::dvec2 p(100.3 + 10.0 * i, 200.4 + 0.235 * i);
        drawn.push_back(p);
        beside.push_back(p + glm::dvec2(0.0, 1.0));
    }
    PixelMask mask(camera.width(), camera.height());
    drawLine(drawn, mask);
    const std::vector<SilhouetteChain> chains = {chainThrough(camera, drawn),
                                                 chainThrough(camera, beside)};

    const PolylineSplit split = splitPolylines(chains, camera, mask, {}, true);
    ASSERT_EQ(split.visible.size(), 1u);
    EXPECT_NEAR(lengthOf(split.visible), 200.0, 0.5);
    for (const glm::vec2& p : split.visible[0].points)
        EXPECT_LT(distanceTo(glm::dvec2(p), drawn), 0.01) << p.x << ", " << p.y;
    ASSERT_EQ(split.hidden.size(), 1u);
    EXPECT_NEAR(lengthOf(split.hidden), 200.0, 0.5);
    for (const glm::vec2& p : split.hidden[0].points)
        EXPECT_LT(distanceTo(glm::dvec2(p), beside), 0.01) << p.x << ", " << p.y;

    // Each chain is decided by itself: the order of the chains changes nothing.
    const PolylineSplit reversed = splitPolylines({chains[1], chains[0]}, camera, mask, {}, true);
    ASSERT_EQ(reversed.visible.size(), 1u);
    EXPECT_EQ(reversed.visible[0].points, split.visible[0].points);
}

// A hidden chain crossing a visible line passes within the tolerance for two pixels or so, but
// on the line's own pixels for one: no visible tick across the line, even with no least length.
TEST(VisiblePolylinesOwnPixels, AHiddenChainCrossingAVisibleLineLeavesNoTick) {
    const Camera camera;
    const std::vector<glm::dvec2> line = {{100.5, 200.5}, {300.5, 200.5}};
    const std::vector<glm::dvec2> crossing = {{200.3, 150.2}, {201.1, 250.7}};
    PixelMask mask(camera.width(), camera.height());
    drawLine(line, mask);
    PolylineOptions options;
    options.minLengthPx = 0.0;
    const PolylineSplit split = splitPolylines(
        {chainThrough(camera, line), chainThrough(camera, crossing)}, camera, mask, options, true);
    ASSERT_EQ(split.visible.size(), 1u);
    EXPECT_NEAR(lengthOf(split.visible), 200.0, 0.5);
    // The crossing chain is hidden all through, across the line too.
    ASSERT_EQ(split.hidden.size(), 1u);
    EXPECT_NEAR(lengthOf(split.hidden), glm::length(crossing[1] - crossing[0]), 0.5);
}

// The chaining as first written, serial and with hash maps over the whole mesh: the reference
// the parallel chaining (a weld of the crossed triangles' vertices only, an edge table sorted)
// must match point for point.
namespace reference {

// Each vertex's first index with the same position bits, over all vertices.
std::vector<std::uint32_t> weldedIds(const Mesh& mesh) {
    struct Key {
        std::uint32_t bits[3];
        bool operator==(const Key& o) const { return std::memcmp(bits, o.bits, sizeof bits) == 0; }
    };
    struct Hash {
        std::size_t operator()(const Key& k) const {
            return std::size_t(k.bits[0]) * 73856093u ^ std::size_t(k.bits[1]) * 19349663u ^
                   std::size_t(k.bits[2]) * 83492791u;
        }
    };
    std::unordered_map<Key, std::uint32_t, Hash> first;
    std::vector<std::uint32_t> ids(mesh.vertexCount());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        Key key;
        std::memcpy(key.bits, &mesh.positions[v], sizeof key.bits);
        ids[v] = first.try_emplace(key, std::uint32_t(v)).first->second;
    }
    return ids;
}

std::vector<EdgeSegment> edgeSegments(const Mesh& mesh, const Camera& camera) {
    const bool ortho = camera.isOrthographic();
    const glm::vec3 eyeOrDirection = ortho ? glm::vec3(-camera.forward()) : glm::vec3(camera.eye());
    std::vector<float> distance(mesh.vertexCount());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        distance[v] = lw::kernels::silhouetteDistance(mesh.positions[v], mesh.normals[v],
                                                      eyeOrDirection, ortho);
    const std::vector<std::uint32_t> welded = weldedIds(mesh);
    std::vector<EdgeSegment> segments;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* v = &mesh.indices[3 * t];
        const std::uint32_t w[3] = {welded[v[0]], welded[v[1]], welded[v[2]]};
        const glm::vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
        const float d[3] = {distance[v[0]], distance[v[1]], distance[v[2]]};
        lw::kernels::SegmentEndpoints ends;
        lw::kernels::IsolineCrossing c;
        if (lw::kernels::silhouetteSegment(p, d, ends, &c))
            segments.push_back(
                {{ends.a, ends.b},
                 {meshEdgeKey(w[c.lone], w[c.other1]), meshEdgeKey(w[c.lone], w[c.other2])}});
    }
    return segments;
}

void walkChain(const std::vector<EdgeSegment>& segments,
               const std::unordered_multimap<std::uint64_t, std::size_t>& byEdge,
               std::vector<std::uint8_t>& used, std::size_t start, int side,
               std::vector<glm::vec3>& points, bool& closed) {
    for (std::size_t current = start;;) {
        const std::uint64_t edge = segments[current].edge[side];
        const auto [first, last] = byEdge.equal_range(edge);
        std::size_t next = current;
        for (auto it = first; it != last; ++it)
            if (it->second != current)
                next = it->second;
        if (next == current || std::distance(first, last) != 2)
            return;
        if (next == start) {
            closed = true;
            return;
        }
        if (used[next])
            return;
        used[next] = 1;
        side = segments[next].edge[0] == edge ? 1 : 0;
        points.push_back(segments[next].point[side]);
        current = next;
    }
}

std::vector<SilhouetteChain> chainSegments(const std::vector<EdgeSegment>& segments) {
    std::unordered_multimap<std::uint64_t, std::size_t> byEdge;
    for (std::size_t s = 0; s < segments.size(); ++s)
        for (const std::uint64_t edge : segments[s].edge)
            byEdge.emplace(edge, s);
    std::vector<std::uint8_t> used(segments.size(), 0);
    std::vector<SilhouetteChain> chains;
    for (std::size_t s = 0; s < segments.size(); ++s) {
        if (used[s])
            continue;
        used[s] = 1;
        std::vector<glm::vec3> back;
        bool closed = false;
        walkChain(segments, byEdge, used, s, 0, back, closed);
        SilhouetteChain chain;
        chain.points.assign(back.rbegin(), back.rend());
        chain.points.push_back(segments[s].point[0]);
        chain.points.push_back(segments[s].point[1]);
        if (!closed)
            walkChain(segments, byEdge, used, s, 1, chain.points, closed);
        else
            chain.points.erase(chain.points.begin());
        chain.closed = closed;
        chains.push_back(std::move(chain));
    }
    return chains;
}

} // namespace reference

// The same chains or polylines, point for point, in the same order.
template <typename Line>
void expectSameLines(const std::vector<Line>& actual, const std::vector<Line>& expected) {
    ASSERT_EQ(actual.size(), expected.size());
    for (std::size_t i = 0; i < actual.size(); ++i) {
        EXPECT_EQ(actual[i].closed, expected[i].closed) << "line " << i;
        ASSERT_EQ(actual[i].points, expected[i].points) << "line " << i;
    }
}

struct PhantomView {
    bool closeAtBorder;
    double az, el;
    Projection projection;
};

void PrintTo(const PhantomView& view, std::ostream* out) {
    *out << (view.closeAtBorder ? "closed" : "open") << " at " << view.az << "," << view.el
         << (view.projection == Projection::Orthographic ? " ortho" : " perspective");
}

class PolylinesAsTheReference : public testing::TestWithParam<PhantomView> {};

// The CT phantom's capsules run out of the volume's first slices: closed there, the cap repeats
// the border vertices (what the weld joins); open, the chains end at the border edges.
TEST_P(PolylinesAsTheReference, ChainsAndPolylinesArePointForPointTheSame) {
    const lw::volume::Volume volume =
        lw::volume::makePhantom(glm::ivec3(96), lw::volume::PhantomKind::Ct);
    CameraSetup setup;
    setup.bounds = volumeBounds(volume);
    setup.azimuthDeg = GetParam().az;
    setup.elevationDeg = GetParam().el;
    setup.projection = GetParam().projection;
    const Camera camera(setup, 400, 400);
    auto renderer = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cpu);
    renderer->setVolume(volume);
    SilhouetteSettings settings;
    settings.isoReal = 300;
    settings.closeAtBorder = GetParam().closeAtBorder;
    const SilhouetteFrame frame = renderer->render(camera, settings);
    const Mesh mesh = *renderer->surfaceMesh();

    const std::vector<SilhouetteChain> expected =
        reference::chainSegments(reference::edgeSegments(mesh, camera));
    ASSERT_GT(expected.size(), 20u) << "too few chains to test anything";
    std::size_t open = 0;
    for (const SilhouetteChain& chain : expected)
        open += chain.closed ? 0 : 1;
    EXPECT_GT(open, 0u) << "no chain ends: the edge table's ends go untested";
    const std::vector<SilhouetteChain> chains = chainSilhouette(mesh, camera);
    expectSameLines(chains, expected);

    // Chains split in parallel: the same as one chain after the other.
    PolylineOptions options;
    options.minLengthPx = 2.0;
    const PolylineSplit split = splitPolylines(mesh, camera, frame.lines, options, true);
    PolylineSplit serial;
    for (const SilhouetteChain& chain : expected) {
        const PolylineSplit one = splitPolylines({chain}, camera, frame.lines, options, true);
        serial.visible.insert(serial.visible.end(), one.visible.begin(), one.visible.end());
        serial.hidden.insert(serial.hidden.end(), one.hidden.begin(), one.hidden.end());
    }
    ASSERT_FALSE(serial.visible.empty());
    expectSameLines(split.visible, serial.visible);
    expectSameLines(split.hidden, serial.hidden);

    // From only the triangles that may hold the contour, unshared (what the CUDA back-end
    // downloads for an export): the same chains and lines, point for point.
    const Mesh part = contourTriangles(mesh, camera);
    EXPECT_LT(part.triangleCount(), mesh.triangleCount() / 2) << "the selection selects little";
    expectSameLines(chainSilhouette(part, camera), expected);
    const PolylineSplit fromPart = splitPolylines(part, camera, frame.lines, options, true);
    expectSameLines(fromPart.visible, split.visible);
    expectSameLines(fromPart.hidden, split.hidden);
}

INSTANTIATE_TEST_SUITE_P(Phantom, PolylinesAsTheReference,
                         testing::Values(PhantomView{true, 30, 20, Projection::Perspective},
                                         PhantomView{false, 30, 20, Projection::Perspective},
                                         PhantomView{true, 200, -60, Projection::Orthographic},
                                         PhantomView{false, 110, 75, Projection::Orthographic}),
                         [](const testing::TestParamInfo<PhantomView>& info) {
                             return std::string(info.param.closeAtBorder ? "Closed" : "Open") +
                                    std::to_string(info.index);
                         });

// Segments whose edges come from a small pool, so that edges are shared by one, two, three or
// more ends and some segments have both ends on one edge (folds, degenerate triangles): the
// sorted edge table joins exactly where the hash map did.
TEST(ChainSegments, EdgesSharedByAnyNumberOfEndsChainAsTheReference) {
    std::mt19937 random(12345);
    for (const std::uint32_t pool : {4u, 40u, 400u, 4000u}) {
        std::vector<EdgeSegment> segments(2000);
        for (std::size_t s = 0; s < segments.size(); ++s) {
            segments[s].point[0] = glm::vec3(float(s), 0.0f, 0.0f);
            segments[s].point[1] = glm::vec3(float(s), 1.0f, 0.0f);
            for (std::uint64_t& edge : segments[s].edge)
                edge = meshEdgeKey(random() % pool, random() % pool);
        }
        expectSameLines(chainSegments(segments), reference::chainSegments(segments));
    }
    EXPECT_TRUE(chainSegments({}).empty());
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, VisiblePolylines,
    testing::Values(ShapeView{"sphere", 30, 20, 1}, ShapeView{"torus", 30, 60, 2},
                    ShapeView{"tori", 200, -35, 2}, ShapeView{"superquadric", 75, 70, 1}),
    [](const testing::TestParamInfo<ShapeView>& info) { return std::string(info.param.shape); });

// The sphere seen whole: its contour is one closed polyline.
TEST(VisiblePolylinesSphere, TheWholeContourIsOneClosedPolyline) {
    const SphereShape sphere;
    const lw::volume::Volume volume = sampleShape(sphere, 64);
    CameraSetup setup;
    setup.bounds = sphere.bounds();
    const Camera camera(setup, 256, 256);
    auto renderer = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cpu);
    renderer->setVolume(volume);
    SilhouetteSettings settings;
    settings.isoReal = kShapeIso;
    const SilhouetteFrame frame = renderer->render(camera, settings);
    const std::vector<Polyline> lines =
        visiblePolylines(*renderer->surfaceMesh(), camera, frame.lines);
    ASSERT_EQ(lines.size(), 1u);
    EXPECT_TRUE(lines[0].closed);
}

} // namespace
