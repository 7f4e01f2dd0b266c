// Method 1's GL pipeline on a headless EGL context (llvmpipe here and in CI, NVIDIA on the GPU
// machine). Linked with lw_gtest_main_gl: without an OpenGL 4.x context the binary exits with the
// SKIP code, so a machine without GL reports SKIP rather than a PASS that tested nothing.

#include "gl_test_context.h"
#include "lw/core/error.h"
#include "lw/core/image_compare.h"
#include "lw/core/png_io.h"
#include "lw/kernels/silhouette_segment.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/pixel_mask.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "test_support.h"

#include <gtest/gtest.h>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <numbers>
#include <utility>

using namespace lw::render;
using lw::core::ImageRgba8;
using lw::core::Rgba8;

namespace {

constexpr Rgba8 kWhite{255, 255, 255, 255};

bool isBackground(Rgba8 p) {
    return p.r == 255 && p.g == 255 && p.b == 255;
}

// An icosphere: a subdivided icosahedron pushed onto the sphere, outward normals, counter-clockwise
// seen from outside (as marching cubes delivers).
Mesh icosphere(glm::vec3 centre, float radius, int subdivisions) {
    const float t = (1.0f + std::sqrt(5.0f)) / 2.0f;
    std::vector<glm::vec3> unit{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    for (auto& p : unit)
        p = glm::normalize(p);
    std::vector<std::uint32_t> tris{0, 11, 5, 0, 5,  1,  0,  1,  7,  0,  7, 10, 0, 10, 11,
                                    1, 5,  9, 5, 11, 4,  11, 10, 2,  10, 7, 6,  7, 1,  8,
                                    3, 9,  4, 3, 4,  2,  3,  2,  6,  3,  6, 8,  3, 8,  9,
                                    4, 9,  5, 2, 4,  11, 6,  2,  10, 8,  6, 7,  9, 8,  1};
    for (int level = 0; level < subdivisions; ++level) {
        std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> midpoints;
        auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
            const auto key = std::minmax(a, b);
            auto [it, inserted] =
                midpoints.try_emplace({key.first, key.second}, std::uint32_t(unit.size()));
            if (inserted)
                unit.push_back(glm::normalize(unit[a] + unit[b]));
            return it->second;
        };
        std::vector<std::uint32_t> next;
        for (std::size_t i = 0; i < tris.size(); i += 3) {
            const std::uint32_t a = tris[i], b = tris[i + 1], c = tris[i + 2];
            const std::uint32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
            next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
        }
        tris = std::move(next);
    }
    Mesh mesh;
    for (const auto& n : unit) {
        mesh.positions.push_back(centre + radius * n);
        mesh.normals.push_back(n);
    }
    mesh.indices = std::move(tris);
    return mesh;
}

void append(Mesh& to, const Mesh& from) {
    const auto offset = std::uint32_t(to.positions.size());
    to.positions.insert(to.positions.end(), from.positions.begin(), from.positions.end());
    to.normals.insert(to.normals.end(), from.normals.begin(), from.normals.end());
    for (std::uint32_t index : from.indices)
        to.indices.push_back(index + offset);
}

Camera orthoCamera(const Aabb& bounds, int size, double az = 0.0, double el = 0.0) {
    CameraSetup setup;
    setup.bounds = bounds;
    setup.projection = Projection::Orthographic;
    setup.azimuthDeg = az;
    setup.elevationDeg = el;
    return Camera(setup, size, size);
}

// Projected centre and radius (pixels) of a sphere under an orthographic camera.
std::pair<glm::dvec2, double> projectedDisc(const Camera& camera, glm::dvec3 centre,
                                            double radius) {
    const glm::dvec2 c = camera.project(centre).pixel;
    const glm::dvec2 r = camera.project(centre + radius * camera.right()).pixel;
    return {c, glm::length(r - c)};
}

double distanceFrom(glm::dvec2 centre, int x, int y) {
    return glm::length(glm::dvec2(x + 0.5, y + 0.5) - centre);
}

std::filesystem::path outputDir() {
    std::filesystem::path dir = std::filesystem::current_path() / "silhouette_gl_output";
    std::filesystem::create_directories(dir);
    return dir;
}

class SilhouetteGl : public testing::Test {
protected:
    void SetUp() override { lw::test::glContext().makeCurrent(); }

    struct Drawn {
        SilhouetteGlStats stats;
        ImageRgba8 image;
    };
    Drawn draw(const Camera& camera, const SilhouetteGlOptions& options) {
        const SilhouetteGlStats stats = m_renderer.render(camera, options);
        return {stats, m_renderer.readImage()};
    }

    SilhouetteGlRenderer m_renderer;
};

} // namespace

TEST(GlContext, ReportsRenderer) {
    const EglHeadlessContext& context = lw::test::glContext();
    EXPECT_FALSE(context.renderer().empty());
    EXPECT_FALSE(context.version().empty());
    EXPECT_NE(context.description().find(context.renderer()), std::string::npos);
    std::printf("GL context: %s\n", context.description().c_str());
}

// Every GL object has one owner: a moved GlObject hands its name on, and a destroyed renderer
// leaves none of its programs, buffers, framebuffers or textures behind.
TEST(GlObjects, TheOwnerDeletesTheObject) {
    lw::test::glContext().makeCurrent();
    GlBuffer first = GlBuffer::create();
    const unsigned name = first.get();
    ASSERT_NE(name, 0u);
    glBindBuffer(GL_ARRAY_BUFFER, name); // a buffer name is an object once bound
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    GlBuffer second = std::move(first);
    EXPECT_FALSE(first);
    EXPECT_EQ(second.get(), name);
    EXPECT_TRUE(glIsBuffer(name));
    second.reset();
    EXPECT_FALSE(glIsBuffer(name));

    unsigned framebuffer = 0, colour = 0, positions = 0;
    {
        SilhouetteGlRenderer renderer;
        renderer.uploadMesh(icosphere({0, 0, 0}, 1.0f, 2));
        renderer.render(orthoCamera({{-1, -1, -1}, {1, 1, 1}}, 32));
        framebuffer = renderer.framebuffer();
        colour = renderer.colourTexture();
        positions = renderer.positionBuffer();
        EXPECT_TRUE(glIsFramebuffer(framebuffer) && glIsTexture(colour) && glIsBuffer(positions));
    }
    EXPECT_FALSE(glIsFramebuffer(framebuffer));
    EXPECT_FALSE(glIsTexture(colour));
    EXPECT_FALSE(glIsBuffer(positions));
}

TEST_F(SilhouetteGl, IsoPanelShadesTheProjectedDisc) {
    const Mesh sphere = icosphere({0, 0, 0}, 1.0f, 4);
    const Camera camera = orthoCamera({{-1, -1, -1}, {1, 1, 1}}, 160);
    const auto [centre, radius] = projectedDisc(camera, {0, 0, 0}, 1.0);
    m_renderer.uploadMesh(sphere);
    SilhouetteGlOptions options;
    options.panel = GlPanel::Iso;
    const ImageRgba8 image = m_renderer.renderImage(camera, options);
    ASSERT_EQ(image.width(), 160);
    ASSERT_EQ(image.height(), 160);
    std::size_t inside = 0, shadedInside = 0, outside = 0, backgroundOutside = 0;
    int darkest = 255, brightest = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const double d = distanceFrom(centre, x, y);
            const Rgba8 p = image.at(x, y);
            if (d < radius - 2.0) {
                ++inside;
                shadedInside += !isBackground(p);
                darkest = std::min<int>(darkest, p.g);
                brightest = std::max<int>(brightest, p.g);
            } else if (d > radius + 2.0) {
                ++outside;
                backgroundOutside += isBackground(p);
            }
        }
    EXPECT_GT(inside, 1000u);
    EXPECT_EQ(shadedInside, inside);
    EXPECT_EQ(backgroundOutside, outside);
    // Shading, not a flat fill: the rim facing away from the light is much darker than the
    // highlight.
    EXPECT_GT(brightest - darkest, 80);
    // The light sits above-left of the eye: the upper-left quadrant is brighter than the
    // lower-right.
    const Rgba8 upperLeft = image.at(int(centre.x - radius * 0.4), int(centre.y - radius * 0.4));
    const Rgba8 lowerRight = image.at(int(centre.x + radius * 0.4), int(centre.y + radius * 0.4));
    EXPECT_GT(int(upperLeft.g), int(lowerRight.g) + 20);
}

TEST_F(SilhouetteGl, SilhouettePanelDrawsARingAtTheProjectedRadius) {
    const Mesh sphere = icosphere({10, -5, 3}, 20.0f, 4);
    const Aabb bounds{{-10, -25, -17}, {30, 15, 23}};
    for (auto [az, el] : {std::pair{0.0, 0.0}, std::pair{35.0, 20.0}, std::pair{-120.0, -60.0}}) {
        SCOPED_TRACE(testing::Message() << "az " << az << " el " << el);
        const Camera camera = orthoCamera(bounds, 200, az, el);
        const auto [centre, radius] = projectedDisc(camera, {10, -5, 3}, 20.0);
        m_renderer.uploadMesh(sphere);
        const ImageRgba8 image = m_renderer.renderImage(camera);
        std::size_t offRing = 0, lines = 0;
        // Bins of about two pixels of arc: finer bins could fall between pixel centres.
        std::vector<bool> angleCovered(180, false);
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) {
                const Rgba8 p = image.at(x, y);
                if (isBackground(p))
                    continue;
                ++lines;
                EXPECT_EQ(p, (Rgba8{0, 0, 0, 255})) << "line colour at " << x << "," << y;
                const double d = distanceFrom(centre, x, y);
                if (std::abs(d - radius) > 2.0)
                    ++offRing;
                const double angle = std::atan2(y + 0.5 - centre.y, x + 0.5 - centre.x);
                angleCovered[std::size_t(
                    int(std::floor((angle + std::numbers::pi) / (2 * std::numbers::pi) * 180.0)) %
                    180)] = true;
            }
        if (HasFailure())
            lw::core::writePng(outputDir() / ("ring_az" + std::to_string(int(az)) + ".png"), image);
        EXPECT_EQ(offRing, 0u) << "line pixels away from the projected radius " << radius;
        EXPECT_EQ(std::count(angleCovered.begin(), angleCovered.end(), false), 0)
            << "gaps in the ring";
        // A closed curve: every line pixel has at least two 8-neighbours on the line (a gap leaves
        // two pixels with one).
        std::size_t loose = 0;
        for (int y = 1; y + 1 < image.height(); ++y)
            for (int x = 1; x + 1 < image.width(); ++x) {
                if (isBackground(image.at(x, y)))
                    continue;
                int neighbours = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx)
                        neighbours += (dx || dy) && !isBackground(image.at(x + dx, y + dy));
                loose += neighbours < 2;
            }
        EXPECT_EQ(loose, 0u) << "line pixels with fewer than two neighbours (gaps)";
        // A one-pixel ring: about its circumference in pixels, not a filled band.
        EXPECT_GT(double(lines), 2.0 * std::numbers::pi * radius * 0.9);
        EXPECT_LT(double(lines), 2.0 * std::numbers::pi * radius * 1.6);
    }
}

// A wide line is the visible one-pixel line drawn as the antialiased stroke the panels give
// methods 2 and 3 (PixelMask::strokeCoverage), the line colour blended over the background by
// its coverage, pixel for pixel.
TEST_F(SilhouetteGl, WideLinesAreTheVisibleThinLinesStroked) {
    Mesh scene = icosphere({0, 0, 0}, 1.0f, 4);
    append(scene, icosphere({0.7f, 0.2f, 0.9f}, 0.45f, 3)); // partly hidden behind the first
    const Camera camera = orthoCamera({{-1, -1, -1}, {1.2, 1.2, 1.9}}, 160, 20.0, 10.0);
    m_renderer.uploadMesh(scene);
    const Rgba8 colour{204, 26, 26, 255};
    auto image = [&](float width) {
        SilhouetteGlOptions options;
        options.lineWidth = width;
        // Exact multiples of 1/255: drivers round x.5 levels differently.
        options.lineColour = {204 / 255.0f, 26 / 255.0f, 26 / 255.0f, 1.0f};
        return m_renderer.renderImage(camera, options);
    };
    const ImageRgba8 thinImage = image(1.0f);
    PixelMask thin(thinImage.width(), thinImage.height());
    for (int y = 0; y < thinImage.height(); ++y)
        for (int x = 0; x < thinImage.width(); ++x)
            if (!isBackground(thinImage.at(x, y))) {
                EXPECT_EQ(thinImage.at(x, y), colour);
                thin.set(x, y);
            }
    ASSERT_GT(thin.count(), 200u);
    for (const float width : {2.0f, 3.0f, 4.0f, 5.0f}) {
        const std::vector<std::uint8_t> coverage = thin.strokeCoverage(width);
        const ImageRgba8 wide = image(width);
        // The line colour over white by the coverage; GL blends in floats, a level apart at most.
        const auto expected = [&](std::uint8_t line, std::size_t i) {
            return 255.0 + (double(line) - 255.0) * double(coverage[i]) / 255.0;
        };
        std::size_t differing = 0, partial = 0;
        for (int y = 0; y < wide.height(); ++y)
            for (int x = 0; x < wide.width(); ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(wide.width()) + std::size_t(x);
                const Rgba8 p = wide.at(x, y);
                differing += std::abs(p.r - expected(colour.r, i)) > 1.5 ||
                             std::abs(p.g - expected(colour.g, i)) > 1.5 ||
                             std::abs(p.b - expected(colour.b, i)) > 1.5;
                partial += coverage[i] > 0 && coverage[i] < 255;
            }
        EXPECT_EQ(differing, 0u) << "width " << width;
        EXPECT_GT(partial, thin.count() / 2) << "width " << width << ": antialiased edges";
    }
}

TEST_F(SilhouetteGl, VisibilityHidesTheSphereBehind) {
    // The eye is at -y (azimuth 0): the small sphere sits behind the big one and projects inside
    // it.
    Mesh scene = icosphere({0, 0, 0}, 1.0f, 4);
    append(scene, icosphere({0, 3.0f, 0}, 0.5f, 4));
    const Camera camera = orthoCamera({{-1, -1, -1}, {1, 3.5, 1}}, 200);
    const auto [centre, bigRadius] = projectedDisc(camera, {0, 0, 0}, 1.0);
    const double smallRadius = projectedDisc(camera, {0, 3, 0}, 0.5).second;
    ASSERT_LT(smallRadius + 5.0, bigRadius);
    m_renderer.uploadMesh(scene);
    auto ringPixels = [&](bool visibility) {
        SilhouetteGlOptions options;
        options.visibility = visibility;
        const ImageRgba8 image = m_renderer.renderImage(camera, options);
        std::size_t big = 0, small = 0, other = 0;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) {
                if (isBackground(image.at(x, y)))
                    continue;
                const double d = distanceFrom(centre, x, y);
                if (std::abs(d - bigRadius) <= 2.0)
                    ++big;
                else if (std::abs(d - smallRadius) <= 2.0)
                    ++small;
                else
                    ++other;
            }
        return std::tuple{big, small, other};
    };
    const double bigCircumference = 2.0 * std::numbers::pi * bigRadius;
    const double smallCircumference = 2.0 * std::numbers::pi * smallRadius;
    const auto [bigOn, smallOn, otherOn] = ringPixels(true);
    EXPECT_GT(double(bigOn), 0.9 * bigCircumference);
    EXPECT_EQ(smallOn, 0u);
    EXPECT_EQ(otherOn, 0u);
    const auto [bigOff, smallOff, otherOff] = ringPixels(false);
    EXPECT_GT(double(bigOff), 0.9 * bigCircumference);
    EXPECT_GT(double(smallOff), 0.9 * smallCircumference);
    EXPECT_EQ(otherOff, 0u);
}

// Drawing piece by piece (method 1's L): clear(), then per piece its surface depth and its lines'
// depth without resolving, then one resolve. Either order gives the one-draw image, bit for bit:
// both depth buffers keep per-pixel minima whatever the order.
TEST_F(SilhouetteGl, PieceByPieceInEitherOrderEqualsOneDraw) {
    const Mesh front = icosphere({0, 0, 0}, 1.0f, 4);
    const Mesh back = icosphere({0.6f, 3.0f, 0.3f}, 0.7f, 4);
    Mesh scene = front;
    append(scene, back);
    const Camera camera = orthoCamera({{-1, -1, -1}, {1.5, 3.7, 1.2}}, 200, 10.0, 15.0);
    for (const bool visibility : {true, false}) {
        SilhouetteGlOptions options;
        options.visibility = visibility;
        options.countSegments = true;
        m_renderer.uploadMesh(scene);
        const SilhouetteGlStats wholeStats = m_renderer.render(camera, options);
        const ImageRgba8 whole = m_renderer.readImage();
        options.clear = false;
        options.resolve = false;
        for (const bool backFirst : {true, false}) {
            m_renderer.clearMesh();
            EXPECT_EQ(m_renderer.triangleCount(), 0u);
            m_renderer.clear(camera.width(), camera.height(), options.background);
            std::size_t segments = 0;
            for (const Mesh* piece :
                 backFirst ? std::array{&back, &front} : std::array{&front, &back}) {
                m_renderer.uploadMesh(*piece);
                segments += m_renderer.render(camera, options).segments;
            }
            m_renderer.resolve(options);
            EXPECT_EQ(segments, wholeStats.segments);
            const ImageRgba8 pieces = m_renderer.readImage();
            std::size_t differing = 0;
            for (int y = 0; y < whole.height(); ++y)
                for (int x = 0; x < whole.width(); ++x)
                    differing += isBackground(whole.at(x, y)) != isBackground(pieces.at(x, y));
            EXPECT_EQ(differing, 0u) << "visibility " << visibility << ", back first " << backFirst;
        }
    }
}

TEST_F(SilhouetteGl, SegmentCountMatchesTheCpuRule) {
    const Mesh sphere = icosphere({1, 2, 3}, 5.0f, 3);
    CameraSetup setup;
    setup.bounds = {{-4, -3, -2}, {6, 7, 8}};
    setup.azimuthDeg = 25.0;
    setup.elevationDeg = 17.0;
    for (auto projection : {Projection::Orthographic, Projection::Perspective}) {
        setup.projection = projection;
        const Camera camera(setup, 96, 96);
        const bool ortho = camera.isOrthographic();
        const glm::vec3 eyeOrDirection =
            ortho ? glm::vec3(-camera.forward()) : glm::vec3(camera.eye());
        std::size_t expected = 0;
        for (std::size_t i = 0; i < sphere.indices.size(); i += 3) {
            glm::vec3 p[3];
            float d[3];
            for (int k = 0; k < 3; ++k) {
                p[k] = sphere.positions[sphere.indices[i + k]];
                d[k] = lw::kernels::silhouetteDistance(p[k], sphere.normals[sphere.indices[i + k]],
                                                       eyeOrDirection, ortho);
            }
            lw::kernels::SegmentEndpoints segment;
            expected += lw::kernels::silhouetteSegment(p, d, segment);
        }
        ASSERT_GT(expected, 20u);
        m_renderer.uploadMesh(sphere);
        SilhouetteGlOptions options;
        options.countSegments = true;
        options.visibility = false;
        for (float width : {1.0f, 3.0f}) {
            options.lineWidth = width;
            const SilhouetteGlStats stats = m_renderer.render(camera, options);
            EXPECT_EQ(stats.triangles, sphere.triangleCount());
            // GPU and CPU may round a d near zero differently: allow a couple of triangles.
            EXPECT_NEAR(double(stats.segments), double(expected), 2.0)
                << (ortho ? "ortho" : "perspective");
        }
    }
}

// Pixels that are background in one image and not in the other.
std::size_t differingPixels(const ImageRgba8& a, const ImageRgba8& b) {
    std::size_t differing = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x)
            differing += isBackground(a.at(x, y)) != isBackground(b.at(x, y));
    return differing;
}

namespace {

// Two spheres, one partly behind the other from the angled camera of twoSpheresSetup().
Mesh twoSpheres(int subdivisions) {
    Mesh scene = icosphere({0, 0, 0}, 1.0f, subdivisions);
    append(scene, icosphere({0.6f, 3.0f, 0.3f}, 0.7f, subdivisions));
    return scene;
}

CameraSetup twoSpheresSetup() {
    CameraSetup setup;
    setup.bounds = {{-1, -1, -1}, {1.5, 3.7, 1.2}};
    setup.azimuthDeg = 35.0;
    setup.elevationDeg = 20.0;
    return setup;
}

} // namespace

// Pass 2 over the line candidates only (mayHoldContour: what method 1 computes on the host for a
// software rasterizer, and the GPU's cull everywhere else) draws every line it draws over all
// triangles: the same segments and the same pixels, for both projections, visibility on and off.
TEST_F(SilhouetteGl, LineCandidatesDrawEveryLine) {
    const Mesh scene = twoSpheres(4);
    m_renderer.uploadMesh(scene);
    CameraSetup setup = twoSpheresSetup();
    for (auto projection : {Projection::Orthographic, Projection::Perspective}) {
        setup.projection = projection;
        const Camera camera(setup, 211, 173);
        const glm::vec4 viewer = camera.viewerHomogeneous();
        std::vector<std::uint32_t> candidates;
        for (std::size_t i = 0; i < scene.indices.size(); i += 3) {
            const std::uint32_t* v = &scene.indices[i];
            const glm::vec3 p[3] = {scene.positions[v[0]], scene.positions[v[1]],
                                    scene.positions[v[2]]};
            const glm::vec3 n[3] = {scene.normals[v[0]], scene.normals[v[1]], scene.normals[v[2]]};
            if (lw::kernels::mayHoldContour(p, n, viewer))
                candidates.insert(candidates.end(), v, v + 3);
        }
        ASSERT_GT(candidates.size(), 0u);
        EXPECT_LT(candidates.size(), scene.indices.size() / 4) << "candidates should be few";
        m_renderer.reserveLineCandidates(scene.triangleCount());
        m_renderer.writeLineCandidatesTail(0, candidates);
        for (const bool visibility : {true, false}) {
            SilhouetteGlOptions options;
            options.visibility = visibility;
            options.countSegments = true;
            const Drawn all = draw(camera, options);
            options.useLineCandidates = true;
            options.lineCandidateIndices = candidates.size();
            const Drawn some = draw(camera, options);
            // The GPU's own segments, drawn as lines (GlLineCompute).
            options.useLineCandidates = false;
            options.cullLineCandidatesOnGpu = true;
            const Drawn gpu = draw(camera, options);
            const std::string where =
                std::string(camera.isOrthographic() ? "ortho" : "perspective") +
                (visibility ? "" : ", no visibility");
            ASSERT_GT(all.stats.segments, 20u) << where;
            EXPECT_EQ(some.stats.segments, all.stats.segments) << where;
            EXPECT_EQ(differingPixels(all.image, some.image), 0u) << where;
            ASSERT_TRUE(m_renderer.cullsOnGpu()) << "the test contexts run compute shaders";
            EXPECT_EQ(gpu.stats.segments, all.stats.segments) << where << ", on the GPU";
            EXPECT_EQ(differingPixels(all.image, gpu.image), 0u) << where << ", on the GPU";
        }
    }
}

// The GPU's segment buffer starts at a quarter of the triangles' count. A mesh whose normals flip
// from vertex to vertex holds a segment in most triangles: the first frame finds more than the
// buffer holds, grows it and draws again, and gives what pass 2 over all triangles gives.
TEST_F(SilhouetteGl, GpuSegmentsBeyondTheFirstBufferAreAllDrawn) {
    Mesh scene = icosphere({0, 0, 0}, 1.0f, 4);
    for (std::size_t v = 0; v < scene.normals.size(); v += 2)
        scene.normals[v] = -scene.normals[v];
    m_renderer.uploadMesh(scene);
    const Camera camera = orthoCamera({{-1, -1, -1}, {1, 1, 1}}, 160, 30.0, 20.0);
    for (const bool visibility : {true, false}) {
        SilhouetteGlOptions options;
        options.visibility = visibility;
        options.countSegments = true;
        const Drawn all = draw(camera, options);
        options.cullLineCandidatesOnGpu = true;
        const Drawn gpu = draw(camera, options);
        EXPECT_GT(all.stats.segments, scene.triangleCount() / 2) << "most triangles hold one";
        EXPECT_FALSE(gpu.stats.incomplete) << "render() draws again until every segment fitted";
        EXPECT_EQ(gpu.stats.segments, all.stats.segments) << "visibility " << visibility;
        EXPECT_EQ(differingPixels(all.image, gpu.image), 0u) << "visibility " << visibility;
    }
}

// A frame read only as a mask (method 1's engine frame) writes no colour: its mask comes from the
// frame's stamps and is the colour's mask, for both projections, visibility on and off; the image
// is not there to read.
TEST_F(SilhouetteGl, MaskOnlyFramesGiveTheColoursMask) {
    m_renderer.uploadMesh(twoSpheres(3));
    CameraSetup setup = twoSpheresSetup();
    for (auto projection : {Projection::Orthographic, Projection::Perspective})
        for (const bool visibility : {true, false}) {
            setup.projection = projection;
            const Camera camera(setup, 190, 150);
            SilhouetteGlOptions options;
            options.visibility = visibility;
            options.cullLineCandidatesOnGpu = true;
            m_renderer.render(camera, options);
            std::vector<std::uint8_t> fromColour, fromDepth;
            m_renderer.readRedMask(255, fromColour);
            // Another view's colour and another frame's stamps stay behind: the mask must not
            // come from them.
            CameraSetup other = setup;
            other.azimuthDeg = 100.0;
            m_renderer.render(Camera(other, 190, 150), options);
            options.maskOnly = true;
            m_renderer.render(Camera(other, 190, 150), options);
            m_renderer.render(camera, options);
            m_renderer.readRedMask(255, fromDepth);
            EXPECT_THROW((void)m_renderer.readImage(), lw::core::Error);
            const auto lines = std::count(fromColour.begin(), fromColour.end(), 1);
            EXPECT_GT(lines, 50) << "visibility " << visibility;
            EXPECT_TRUE(fromDepth == fromColour) << "visibility " << visibility;
        }
}

TEST_F(SilhouetteGl, ReuploadReusesBuffersAndGivesTheSameImage) {
    const Mesh small = icosphere({0, 0, 0}, 1.0f, 2);
    Mesh big = icosphere({0, 0, 0}, 1.0f, 4);
    append(big, icosphere({0.5f, -0.5f, 0.3f}, 0.4f, 3));
    const Camera camera = orthoCamera({{-1, -1, -1}, {1, 1, 1}}, 96, 40.0, 30.0);
    SilhouetteGlOptions options;
    options.panel = GlPanel::Iso;
    options.linesOnIso = true;
    m_renderer.uploadMesh(small);
    const ImageRgba8 first = m_renderer.renderImage(camera, options);
    m_renderer.uploadMesh(big);
    EXPECT_EQ(m_renderer.triangleCount(), big.triangleCount());
    const ImageRgba8 bigImage = m_renderer.renderImage(camera, options);
    EXPECT_NE(bigImage, first);
    m_renderer.uploadMesh(small); // fits in the big buffers: overwritten in place
    EXPECT_EQ(m_renderer.triangleCount(), small.triangleCount());
    EXPECT_EQ(m_renderer.renderImage(camera, options), first);
}

// The GUI paints into QOpenGLWidget's own framebuffer: the renderer must leave it bound.
TEST_F(SilhouetteGl, RestoresTheCallersFramebufferAndViewport) {
    GLuint fbo = 0, colour = 0;
    glGenFramebuffers(1, &fbo);
    glGenRenderbuffers(1, &colour);
    glBindRenderbuffer(GL_RENDERBUFFER, colour);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, 8, 8);
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
    glViewport(1, 2, 5, 6);
    m_renderer.uploadMesh(icosphere({0, 0, 0}, 1.0f, 1));
    m_renderer.renderImage(orthoCamera({{-1, -1, -1}, {1, 1, 1}}, 40));
    GLint draw = -1, read = -1, viewport[4] = {};
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw);
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read);
    glGetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(GLuint(draw), fbo);
    EXPECT_EQ(GLuint(read), fbo);
    EXPECT_EQ(viewport[0], 1);
    EXPECT_EQ(viewport[1], 2);
    EXPECT_EQ(viewport[2], 5);
    EXPECT_EQ(viewport[3], 6);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glDeleteFramebuffers(1, &fbo);
    glDeleteRenderbuffers(1, &colour);
    EXPECT_EQ(glGetError(), GLenum(GL_NO_ERROR));
}

TEST_F(SilhouetteGl, EmptyMeshGivesTheBackground) {
    m_renderer.uploadMesh(Mesh{});
    const Camera camera = orthoCamera({{-1, -1, -1}, {1, 1, 1}}, 32);
    SilhouetteGlOptions options;
    options.background = {0.0f, 0.0f, 0.0f, 1.0f};
    const ImageRgba8 image = m_renderer.renderImage(camera, options);
    EXPECT_EQ(image, ImageRgba8(32, 32, Rgba8{0, 0, 0, 255}));
}

TEST_F(SilhouetteGl, RejectsInconsistentMeshes) {
    Mesh mesh = icosphere({0, 0, 0}, 1.0f, 0);
    Mesh badIndex = mesh;
    badIndex.indices[5] = std::uint32_t(mesh.positions.size());
    EXPECT_THROW(m_renderer.uploadMesh(badIndex), lw::core::Error);
    Mesh badNormals = mesh;
    badNormals.normals.pop_back();
    EXPECT_THROW(m_renderer.uploadMesh(badNormals), lw::core::Error);
    Mesh badCount = mesh;
    badCount.indices.pop_back();
    EXPECT_THROW(m_renderer.uploadMesh(badCount), lw::core::Error);
}

// Golden images from llvmpipe. Tolerances leave room for another rasterizer (NVIDIA): shading
// may differ by a few levels everywhere and edge pixels may flip; lines may move by a pixel.
TEST_F(SilhouetteGl, GoldenImages) {
    Mesh scene = icosphere({0, 0, 0}, 1.0f, 4);
    append(scene, icosphere({0.9f, -0.4f, 0.5f}, 0.6f, 4));
    append(scene, icosphere({-0.8f, 0.6f, -0.6f}, 0.5f, 3));
    CameraSetup setup;
    setup.bounds = {{-1.3, -1.1, -1.1}, {1.5, 1.2, 1.1}};
    setup.azimuthDeg = 30.0;
    setup.elevationDeg = 20.0;
    setup.projection = Projection::Perspective;
    const Camera camera(setup, 128, 128);
    m_renderer.uploadMesh(scene);

    struct Golden {
        const char* name;
        SilhouetteGlOptions options;
        lw::core::ContentTolerance tolerance;
    };
    SilhouetteGlOptions iso;
    iso.panel = GlPanel::Iso;
    SilhouetteGlOptions silhouette;
    SilhouetteGlOptions hiddenToo;
    hiddenToo.visibility = false;
    hiddenToo.lineWidth = 2.0f;
    hiddenToo.lineColour = {26 / 255.0f, 51 / 255.0f, 178 / 255.0f,
                            1.0f}; // exact levels, see above
    const Golden goldens[] = {
        // Shares of each baseline's content (2747, 213 and 1197 pixels): shading may differ by a
        // few levels at edges; a line moving by a pixel flips its old and new pixels. A blank
        // or half-empty image fails whatever the share (minContentRatio).
        {"gl_spheres_iso", iso, {12, 0.09, 0.5}},
        {"gl_spheres_silhouette", silhouette, {0, 1.2, 0.5}},
        {"gl_spheres_silhouette_novis_wide", hiddenToo, {0, 0.55, 0.5}},
    };
    const std::filesystem::path baselines = lw::test::sourceDir() / "tests/render/baselines";
    for (const Golden& golden : goldens) {
        SCOPED_TRACE(golden.name);
        const ImageRgba8 image = m_renderer.renderImage(camera, golden.options);
        const std::filesystem::path baseline = baselines / (std::string(golden.name) + ".png");
        const auto comparison =
            lw::core::compareWithBaseline(image, baseline, golden.tolerance,
                                          outputDir() / (std::string(golden.name) + ".diff.png"));
        EXPECT_TRUE(comparison.matches) << comparison.describe();
        if (comparison.baselineWritten)
            std::printf("%s\n", comparison.describe().c_str());
    }
}
