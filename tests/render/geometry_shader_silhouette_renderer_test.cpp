// Method 1 behind the SilhouetteRenderer interface (GL adapter): mode a caches the mesh, S == L,
// visibility off draws a superset of on, and the counts match the mesh. Linked with
// lw_gtest_main_gl: without an OpenGL 4.x context the binary exits with the SKIP code instead of
// passing untested.
#include "gl_test_context.h"
#include "lw/core/error.h"
#include "lw/render/aabb.h"
#include "lw/render/camera.h"
#include "lw/render/geometry_shader_silhouette_renderer.h"
#include "lw/render/iso_surface.h"
#include "lw/render/phantom.h"
#include "lw/render/renderer_factory.h"

#include <gtest/gtest.h>
#include <memory>

namespace lw::render {
namespace {

// The benchmark phantom is small enough here and has what the checks need: several bones
// (contours hidden behind others) and bricks that split the surface.
const volume::Volume& phantom() {
    static const volume::Volume volume = makePhantom(glm::ivec3(48), PhantomKind::Ct);
    return volume;
}

Camera camera(double azimuth = 30.0, double elevation = 20.0) {
    CameraSetup setup;
    setup.bounds = volumeBounds(phantom());
    setup.azimuthDeg = azimuth;
    setup.elevationDeg = elevation;
    return Camera(setup, 256, 256);
}

SilhouetteSettings settings(ExtractionMode mode, int brickCells = 0, bool visibility = true) {
    SilhouetteSettings s;
    s.isoReal = kPhantomBoneIso;
    s.mode = mode;
    s.brickCells = brickCells;
    s.visibility = visibility;
    return s;
}

TEST(GeometryShaderSilhouetteRenderer, ModeAReusesTheMeshModeBExtractsEveryFrame) {
    GeometryShaderSilhouetteRenderer renderer(lw::test::glContext());
    renderer.setVolume(phantom());
    const SilhouetteFrame first = renderer.render(camera(), settings(ExtractionMode::CachedA));
    EXPECT_GT(first.times.extractMs, 0.0);
    const SilhouetteFrame second = renderer.render(camera(31.0), settings(ExtractionMode::CachedA));
    EXPECT_EQ(second.times.extractMs, 0.0) << "mode a must not extract again for a new view";
    EXPECT_GT(second.times.drawMs, 0.0);
    EXPECT_EQ(second.triangles, first.triangles);

    // Another iso-value invalidates the cache even in mode a.
    SilhouetteSettings otherIso = settings(ExtractionMode::CachedA);
    otherIso.isoReal = 200.5;
    EXPECT_GT(renderer.render(camera(31.0), otherIso).times.extractMs, 0.0);

    const SilhouetteFrame b1 = renderer.render(camera(), settings(ExtractionMode::EveryFrameB));
    const SilhouetteFrame b2 = renderer.render(camera(), settings(ExtractionMode::EveryFrameB));
    EXPECT_GT(b1.times.extractMs, 0.0);
    EXPECT_GT(b2.times.extractMs, 0.0) << "mode b extracts every frame";
    EXPECT_EQ(b2.lines, first.lines) << "mode a and b draw the same view identically";
}

TEST(GeometryShaderSilhouetteRenderer, CountsMatchTheMeshAndLinesAreDrawn) {
    GeometryShaderSilhouetteRenderer renderer(lw::test::glContext());
    renderer.setVolume(phantom());
    const SilhouetteFrame frame = renderer.render(camera(), settings(ExtractionMode::CachedA));
    const Mesh mesh = extractIsoSurface(phantom(), kPhantomBoneIso);
    ASSERT_FALSE(mesh.isEmpty());
    EXPECT_EQ(frame.triangles, mesh.triangleCount());
    EXPECT_EQ(renderer.mesh().triangleCount(), mesh.triangleCount());
    EXPECT_GT(frame.segments, 0u);
    EXPECT_LT(frame.segments, frame.triangles);
    EXPECT_EQ(frame.lines.width(), 256);
    EXPECT_EQ(frame.lines.height(), 256);
    EXPECT_GT(frame.lines.count(), 200u);
    EXPECT_LT(frame.lines.count(), std::size_t(256 * 256 / 4)) << "lines, not a filled surface";
}

TEST(GeometryShaderSilhouetteRenderer, ChunkedAndWholeGiveIdenticalMasks) {
    GeometryShaderSilhouetteRenderer renderer(lw::test::glContext());
    renderer.setVolume(phantom());
    for (const ExtractionMode mode : {ExtractionMode::CachedA, ExtractionMode::EveryFrameB}) {
        for (const bool visibility : {true, false}) {
            const SilhouetteFrame whole = renderer.render(camera(), settings(mode, 0, visibility));
            const SilhouetteFrame chunked =
                renderer.render(camera(), settings(mode, 16, visibility));
            EXPECT_EQ(chunked.triangles, whole.triangles);
            EXPECT_EQ(chunked.segments, whole.segments);
            EXPECT_TRUE(chunked.lines == whole.lines)
                << "S and L differ (mode " << int(mode) << ", visibility " << visibility << ")";
        }
    }
}

TEST(GeometryShaderSilhouetteRenderer, VisibilityOffIsASupersetOfOn) {
    GeometryShaderSilhouetteRenderer renderer(lw::test::glContext());
    renderer.setVolume(phantom());
    const SilhouetteFrame on =
        renderer.render(camera(), settings(ExtractionMode::CachedA, 0, true));
    const SilhouetteFrame off =
        renderer.render(camera(), settings(ExtractionMode::CachedA, 0, false));
    EXPECT_EQ(on.segments, off.segments) << "segments are counted before the depth test";
    std::size_t missing = 0;
    for (int y = 0; y < on.lines.height(); ++y)
        for (int x = 0; x < on.lines.width(); ++x)
            if (on.lines.get(x, y) && !off.lines.get(x, y))
                ++missing;
    EXPECT_EQ(missing, 0u) << "a visible silhouette pixel is missing with visibility off";
    EXPECT_GT(off.lines.count(), on.lines.count()) << "the phantom has hidden contours";
}

TEST(GeometryShaderSilhouetteRenderer, IsoPanelIsShadedForTheSameCamera) {
    GeometryShaderSilhouetteRenderer renderer(lw::test::glContext());
    renderer.setVolume(phantom());
    const core::ImageRgba8 iso =
        renderer.renderIsoPanel(camera(), settings(ExtractionMode::CachedA));
    ASSERT_EQ(iso.width(), 256);
    ASSERT_EQ(iso.height(), 256);
    std::size_t shaded = 0;
    for (int y = 0; y < iso.height(); ++y)
        for (int x = 0; x < iso.width(); ++x) {
            const core::Rgba8 p = iso.at(x, y);
            if (!(p.r == 255 && p.g == 255 && p.b == 255) && !(p.r == 0 && p.g == 0 && p.b == 0))
                ++shaded;
        }
    EXPECT_GT(shaded, std::size_t(256 * 256 / 50)) << "the surface covers part of the panel";
    // The silhouette frame after the iso panel uses the cached mesh.
    EXPECT_EQ(renderer.render(camera(), settings(ExtractionMode::CachedA)).times.extractMs, 0.0);
}

TEST(GeometryShaderSilhouetteRenderer, RenderBeforeSetVolumeThrows) {
    GeometryShaderSilhouetteRenderer renderer(lw::test::glContext());
    EXPECT_THROW(renderer.render(camera(), settings(ExtractionMode::CachedA)), core::Error);
}

TEST(GeometryShaderSilhouetteRenderer, FactoryGivesTheGlAdapterForMethod1) {
    std::unique_ptr<SilhouetteRenderer> renderer =
        createSilhouetteRenderer(SilhouetteMethod::GeometryShader, Backend::Cpu);
    ASSERT_NE(renderer, nullptr);
    EXPECT_EQ(renderer->method(), SilhouetteMethod::GeometryShader);
    EXPECT_EQ(renderer->backendName(), "gl");
    renderer->setVolume(phantom());
    const SilhouetteFrame frame = renderer->render(camera(), settings(ExtractionMode::CachedA));
    EXPECT_GT(frame.lines.count(), 200u);
    lw::test::glContext().makeCurrent(); // the factory's renderer made its own context current
}

} // namespace
} // namespace lw::render
