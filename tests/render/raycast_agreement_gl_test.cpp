// Methods 1 (GL geometry shader), 2 (ray-cast visibility) and 3 (z-buffer, when built) draw the
// same visible silhouette: >= 99% of either's pixels lie within 1 px of the other's. Linked
// with lw_gtest_main_gl: without an OpenGL 4.x context the binary exits with the SKIP code
// instead of passing untested.
#include "lw/evaluation/analytic_shapes.h"
#include "lw/evaluation/contour_score.h"
#include "lw/render/iso_surface.h"
#include "lw/render/raycast_silhouette_renderer.h"
#include "lw/render/silhouette_gl_renderer.h"

#if __has_include("lw/render/zbuffer_silhouette_renderer.h")
#include "lw/render/zbuffer_silhouette_renderer.h"
#define LW_TEST_HAVE_METHOD3 1
#else
#define LW_TEST_HAVE_METHOD3 0
#endif

#include <gtest/gtest.h>
#include <string>

namespace lw::render {
namespace {

using namespace lw::evaluation;

PixelMask glSilhouette(SilhouetteGlRenderer& gl, const volume::Volume& v, const Camera& camera,
                       int brickCells) {
    IsoSurfaceOptions options;
    options.brickCells = brickCells;
    gl.uploadMesh(extractIsoSurface(v, kShapeIso, options));
    SilhouetteGlOptions o;
    o.panel = GlPanel::Silhouette;
    o.background = {0.0f, 0.0f, 0.0f, 1.0f};
    o.lineColour = {1.0f, 1.0f, 1.0f, 1.0f};
    return PixelMask::fromImage(gl.renderImage(camera, o), {0, 0, 0, 255});
}

void expectAgree(const PixelMask& a, const PixelMask& b, const std::string& what) {
    const ContourScore score = scoreContours(a, b, 1);
    EXPECT_GT(score.truePixels, 100u) << what;
    EXPECT_GE(score.recall, 0.99) << what;
    EXPECT_GE(score.precision, 0.99) << what;
}

TEST(SilhouetteMethodsAgree, Method2AndMethod1AndMethod3) {
    SilhouetteGlRenderer gl;
    gl.initialize();
    for (const std::string name : {"sphere", "torus", "tori", "superquadric", "metaballs"}) {
        const auto shape = makeAnalyticShape(name);
        const volume::Volume v = sampleShape(*shape, 48);
        CameraSetup setup;
        setup.bounds = shape->bounds();
        setup.azimuthDeg = 30.0;
        setup.elevationDeg = 20.0;
        const int side = Camera::squareSizeForVoxelCoverage(setup, v.geometry().spacingI(), 2.0);
        const Camera camera(setup, side, side);
        for (const int brick : {0, 12}) {
            SilhouetteSettings settings;
            settings.isoReal = kShapeIso;
            settings.brickCells = brick;
            settings.testAlongSegment = true;
            RayCastSilhouetteRenderer method2;
            method2.setVolume(v);
            const PixelMask m2 = method2.render(camera, settings).lines;
            const PixelMask m1 = glSilhouette(gl, v, camera, brick);
            expectAgree(m2, m1, name + " m2 vs m1, brick " + std::to_string(brick));
#if LW_TEST_HAVE_METHOD3
            ZBufferSilhouetteRenderer method3;
            method3.setVolume(v);
            const PixelMask m3 = method3.render(camera, settings).lines;
            expectAgree(m3, m1, name + " m3 vs m1, brick " + std::to_string(brick));
#endif
        }
    }
}

} // namespace
} // namespace lw::render
