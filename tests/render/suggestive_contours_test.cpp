// Suggestive contours (render/suggestive_contours.h): the per-vertex radial curvature against
// the analytic one, none on a sphere, and the drawing scored against the suggestive contours
// computed from the analytic function (evaluation/suggestive_reference.h).
#include "lw/evaluation/analytic_shapes.h"
#include "lw/evaluation/contour_score.h"
#include "lw/evaluation/suggestive_reference.h"
#include "lw/evaluation/true_contour.h"
#include "lw/evaluation/view_sweep.h"
#include "lw/render/iso_surface.h"
#include "lw/render/suggestive_contours.h"
#include "picking_volumes.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <gtest/gtest.h>
#include <vector>

namespace {

using namespace lw;

render::Camera shapeCamera(const evaluation::AnalyticShape& shape, const volume::Volume& volume,
                           evaluation::View view,
                           render::Projection projection = render::Projection::Perspective) {
    render::CameraSetup setup;
    setup.projection = projection;
    setup.bounds = shape.bounds();
    setup.azimuthDeg = view.azimuthDeg;
    setup.elevationDeg = view.elevationDeg;
    // As `accuracy`: two pixels per voxel.
    const int side =
        render::Camera::squareSizeForVoxelCoverage(setup, volume.geometry().spacingI(), 2.0);
    return render::Camera(setup, side, side);
}

// kappa_r of the vertices seen at a useful angle (not head-on, not grazing), against `expected`.
template <typename Expected>
void expectVertexCurvature(const volume::Volume& volume, const render::Camera& camera,
                           Expected&& expected, double tolerance, double scale) {
    const render::Mesh mesh = render::extractIsoSurface(volume, 0.0);
    const render::SuggestiveContourRenderer renderer(volume, mesh, 0.0);
    const std::vector<kernels::RadialCurvature> curvature = renderer.vertexCurvature(camera);
    std::size_t checked = 0, within = 0;
    double worst = 0.0;
    for (std::size_t v = 0; v < mesh.vertexCount(); v += 7) {
        if (!(curvature[v].nDotV > 0.2 && curvature[v].nDotV < 0.95))
            continue;
        const double error = std::abs(curvature[v].kr - expected(glm::dvec3(mesh.positions[v])));
        worst = std::max(worst, error);
        within += error < tolerance * scale;
        ++checked;
    }
    ASSERT_GT(checked, 100u);
    // Nearly all within the tolerance; the rest (curvature is a second derivative of voxels)
    // at most twice as far.
    EXPECT_GT(double(within) / double(checked), 0.95) << within << " of " << checked;
    EXPECT_LT(worst, 2.5 * tolerance * scale);
}

TEST(SuggestiveContours, VertexCurvatureOfASphereIsOneOverR) {
    const evaluation::SphereShape sphere({0, 0, 0}, 40.0);
    for (const int n : {64, 128}) {
        const volume::Volume volume = evaluation::sampleShape(sphere, n);
        const render::Camera camera = shapeCamera(sphere, volume, {30.0, 20.0});
        SCOPED_TRACE(n);
        expectVertexCurvature(
            volume, camera, [](glm::dvec3) { return 1.0 / 40.0; }, 0.03, 1.0 / 40.0);
    }
}

// A tilted stack with uneven gaps (18.5 degrees, gaps 1.1 to 2.3 mm): the Hessian is taken in
// the sheared frame over the real distances and brought back to patient coordinates.
TEST(SuggestiveContours, VertexCurvatureOnATiltedUnevenStack) {
    test::KnownSphere sphere;
    const volume::Volume volume = test::tiltedSphereVolume(&sphere);
    for (const auto& [az, el] : {std::pair{30.0, 20.0}, {-100.0, 60.0}}) {
        const render::Camera camera =
            test::cameraOnSphere(sphere, az, el, render::Projection::Perspective);
        SCOPED_TRACE(az);
        expectVertexCurvature(
            volume, camera, [&](glm::dvec3) { return 1.0 / sphere.radius; }, 0.12,
            1.0 / sphere.radius);
    }
}

// On a torus kappa_r changes sign (convex outside, saddle-shaped inside): the vertices' values
// against the analytic kappa_r at the same points.
TEST(SuggestiveContours, VertexCurvatureOfATorusMatchesTheAnalyticOne) {
    const evaluation::TorusShape torus;
    const volume::Volume volume = evaluation::sampleShape(torus, 128);
    for (const evaluation::View view : {evaluation::View{30.0, 20.0}, {0.0, 45.0}}) {
        const render::Camera camera = shapeCamera(torus, volume, view);
        SCOPED_TRACE(view.elevationDeg);
        // Tolerance: 4 % of the tube's curvature 1/14 mm.
        expectVertexCurvature(
            volume, camera,
            [&](glm::dvec3 p) { return evaluation::analyticRadialCurvature(torus, p, camera).kr; },
            0.04, 1.0 / 14.0);
    }
}

// The reference's sign convention, checked independently of the renderer: at a suggestive
// contour n.v has a local minimum along w (on the surface), which is what D_w kappa_r > 0 means
// (a zero of kappa_r with D_w kappa_r < 0 is a maximum).
TEST(SuggestiveContours, ReferencePointsAreMinimaOfNDotVAlongW) {
    const evaluation::TorusShape torus;
    const volume::Volume volume = evaluation::sampleShape(torus, 64);
    // Orthographic: v is the same everywhere, so d(n.v)/ds = kappa_r |w| along w exactly (with
    // perspective, v turns by 1/distance per mm as well).
    const render::Camera camera =
        shapeCamera(torus, volume, {0.0, 45.0}, render::Projection::Orthographic);
    const render::SuggestiveContourSettings settings;
    const double size = 0.5 * glm::length(torus.bounds().size());
    const render::PixelMask truth =
        evaluation::trueSuggestiveContourMask(torus, camera, settings, size);
    ASSERT_GT(truth.count(), 10u);
    // Back onto the surface along the gradient (the torus value is a signed distance).
    const auto onSurface = [&](glm::dvec3 p) {
        for (int i = 0; i < 4; ++i)
            p -= torus.value(p) * torus.gradient(p);
        return p;
    };
    const auto normal = [&](glm::dvec3 p) { return -glm::normalize(torus.gradient(p)); };
    const auto nDotV = [&](glm::dvec3 p) { return glm::dot(normal(p), camera.toViewer(p)); };
    const auto tangentW = [&](glm::dvec3 p) {
        const glm::dvec3 v = camera.toViewer(p);
        return glm::normalize(v - glm::dot(v, normal(p)) * normal(p));
    };
    std::size_t minima = 0, checked = 0;
    for (int y = 0; y < truth.height(); ++y)
        for (int x = 0; x < truth.width(); ++x) {
            if (!truth.get(x, y))
                continue;
            const render::Ray ray = camera.rayThroughPixel(x, y);
            const std::vector<double> t = evaluation::rayCrossings(torus, ray, 1e-3);
            if (t.empty())
                continue;
            // Newton along w, on the surface, to the zero of kappa_r near this pixel.
            const glm::dvec3 hit = ray.at(t.front());
            glm::dvec3 p = hit;
            for (int i = 0; i < 8; ++i) {
                const auto c = evaluation::analyticRadialCurvature(torus, p, camera);
                p = onSurface(p - c.kr / c.derivative * tangentW(p));
            }
            // The zero must be this pixel's (within a pixel or two of the hit) and not the
            // undefined kappa_r of a head-on point.
            const auto c = evaluation::analyticRadialCurvature(torus, p, camera);
            if (!(std::abs(c.kr) < 1e-6 && glm::distance(p, hit) < 2.0))
                continue;
            // Newton may land on a neighbouring zero with D_w kappa_r < 0: there n.v must have
            // a maximum instead, which checks the sign convention just as well.
            const double h = 0.5; // mm
            const double here = nDotV(p);
            const double ahead = nDotV(onSurface(p + h * tangentW(p)));
            const double behind = nDotV(onSurface(p - h * tangentW(p)));
            const bool minimum = ahead > here && behind > here;
            const bool maximum = ahead < here && behind < here;
            minima += c.derivative > 0.0 ? minimum : maximum;
            ++checked;
        }
    ASSERT_GT(checked, 10u);
    EXPECT_EQ(minima, checked);
}

TEST(SuggestiveContours, SphereHasNone) {
    const evaluation::SphereShape sphere;
    for (const int n : {64, 128}) {
        const volume::Volume volume = evaluation::sampleShape(sphere, n);
        const render::Mesh mesh = render::extractIsoSurface(volume, 0.0);
        render::SuggestiveContourRenderer renderer(volume, mesh, 0.0);
        const render::SuggestiveContourSettings settings;
        for (const evaluation::View view : evaluation::viewSweep(8)) {
            const render::Camera camera = shapeCamera(sphere, volume, view);
            EXPECT_EQ(renderer.render(camera, settings).lines.count(), 0u)
                << n << " at " << view.azimuthDeg << "," << view.elevationDeg;
            EXPECT_EQ(evaluation::trueSuggestiveContourMask(sphere, camera, settings, 40.0).count(),
                      0u);
        }
    }
}

// An iso-value above every voxel: no surface, no lines, no failure.
TEST(SuggestiveContours, EmptySurfaceDrawsNothing) {
    const evaluation::SphereShape sphere;
    const volume::Volume volume = evaluation::sampleShape(sphere, 16);
    const render::Mesh mesh = render::extractIsoSurface(volume, 1000.0);
    ASSERT_TRUE(mesh.isEmpty());
    render::SuggestiveContourRenderer renderer(volume, mesh, 1000.0);
    const render::SuggestiveFrame frame =
        renderer.render(shapeCamera(sphere, volume, {30.0, 20.0}), {});
    EXPECT_EQ(frame.kept.size(), 0u);
    EXPECT_EQ(frame.lines.count(), 0u);
    EXPECT_GT(frame.lines.width(), 0);
}

// A ring cut by the volume's top face and closed there (the review's default): the caps are flat
// discs in the border plane, so no suggestive contour may lie on them. The caps' vertices repeat
// the border's with the cut face's normal; taken as the field there, the ring's curvature
// (convex outside, saddle inside) would draw lines across the caps.
TEST(SuggestiveContours, NoneOnTheCapWhereTheBorderCutsTheSurface) {
    const evaluation::TorusShape ring({32.0, 32.0, 50.0}, {1.0, 0.0, 0.0}, 14.0, 6.0);
    const glm::ivec3 dims{64, 64, 64};
    volume::Volume volume(dims, volume::VoxelType::Float32,
                          volume::VolumeGeometry::regular({0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}));
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                volume.dataAs<float>()[volume.index(x, y, z)] = float(ring.value({x, y, z}));
    render::IsoSurfaceOptions options;
    options.closeAtBorder = true;
    const render::Mesh mesh = render::extractIsoSurface(volume, 0.0, options);
    ASSERT_GT(mesh.triangleCount(), render::extractIsoSurface(volume, 0.0).triangleCount());
    render::SuggestiveContourRenderer renderer(volume, mesh, 0.0);
    const double top = dims.z - 1;
    std::size_t segments = 0, onCap = 0;
    for (const evaluation::View view : evaluation::viewSweep(32)) {
        render::CameraSetup setup;
        setup.bounds = {glm::dvec3(0.0), glm::dvec3(dims - 1)};
        setup.azimuthDeg = view.azimuthDeg;
        setup.elevationDeg = view.elevationDeg;
        for (const render::EdgeSegment& s :
             renderer.segments(render::Camera(setup, 256, 256), {})) {
            ++segments;
            onCap += std::abs(s.point[0].z - top) < 1e-3 && std::abs(s.point[1].z - top) < 1e-3;
        }
    }
    EXPECT_GT(segments, 0u) << "the ring itself has suggestive contours";
    EXPECT_EQ(onCap, 0u) << "of " << segments;
}

// The segments chain through the mesh edges they share like the silhouette's (the torus from
// 45 degrees up: two strokes, left and right of the hole), and their visible polylines lie on
// the drawn pixels.
TEST(SuggestiveContours, SegmentsChainIntoStrokesOnTheMask) {
    const evaluation::TorusShape torus;
    const volume::Volume volume = evaluation::sampleShape(torus, 128);
    const render::Mesh mesh = render::extractIsoSurface(volume, 0.0);
    render::SuggestiveContourRenderer renderer(volume, mesh, 0.0);
    const render::Camera camera = shapeCamera(torus, volume, {0.0, 45.0});
    const render::SuggestiveContourSettings settings;
    const std::vector<render::EdgeSegment> segments = renderer.segments(camera, settings);
    ASSERT_GT(segments.size(), 20u);
    const std::vector<render::SilhouetteChain> chains = render::chainSegments(segments);
    EXPECT_GE(chains.size(), 2u);
    EXPECT_LE(chains.size(), 4u) << "one chain a stroke, not one a segment";
    const render::PixelMask drawn = renderer.render(camera, settings).lines;
    const std::vector<render::Polyline> polylines = render::visiblePolylines(chains, camera, drawn);
    ASSERT_GE(polylines.size(), 2u);
    const render::PixelMask near = drawn.dilated(1);
    for (const render::Polyline& line : polylines)
        for (const glm::vec2 p : line.points)
            EXPECT_TRUE(near.get(int(p.x), int(p.y))) << p.x << "," << p.y;
}

// Pooled over the views (the lines are short, tens to a few hundred pixels a view, so one
// view's ratio moves by several percent with a pixel or two); every view must draw something
// where the truth has lines, so an empty drawing fails.
struct Pooled {
    std::size_t truePixels = 0, trueFound = 0, drawnPixels = 0, drawnMatched = 0;
    double worstRecall = 1.0, worstPrecision = 1.0;
};

Pooled scoreShape(const evaluation::AnalyticShape& shape, int n,
                  const std::vector<evaluation::View>& views) {
    const volume::Volume volume = evaluation::sampleShape(shape, n);
    const render::Mesh mesh = render::extractIsoSurface(volume, 0.0);
    render::SuggestiveContourRenderer renderer(volume, mesh, 0.0);
    render::SuggestiveContourSettings settings;
    settings.featureSize = 0.5 * glm::length(shape.bounds().size());
    Pooled pooled;
    for (const evaluation::View& view : views) {
        const render::Camera camera = shapeCamera(shape, volume, view);
        const render::PixelMask drawn = renderer.render(camera, settings).lines;
        const render::PixelMask truth =
            evaluation::trueSuggestiveContourMask(shape, camera, settings, settings.featureSize);
        const evaluation::ContourScore score = evaluation::scoreContours(drawn, truth, 1);
        std::printf("%s %d view %g,%g: true %zu drawn %zu recall %.4f precision %.4f\n",
                    shape.name().c_str(), n, view.azimuthDeg, view.elevationDeg, score.truePixels,
                    score.drawnPixels, score.recall, score.precision);
        pooled.truePixels += score.truePixels;
        pooled.trueFound += score.trueFound;
        pooled.drawnPixels += score.drawnPixels;
        pooled.drawnMatched += score.drawnMatched;
        // Views with fewer than 20 true pixels (lines about to vanish at the thresholds) are in
        // the pooled figures only.
        if (score.truePixels >= 20) {
            pooled.worstRecall = std::min(pooled.worstRecall, score.recall);
            pooled.worstPrecision = std::min(pooled.worstPrecision, score.precision);
        }
    }
    std::printf("%s %d pooled: recall %.4f precision %.4f; worst (views >= 20 px) recall %.4f "
                "precision %.4f\n",
                shape.name().c_str(), n, double(pooled.trueFound) / double(pooled.truePixels),
                double(pooled.drawnMatched) / double(pooled.drawnPixels), pooled.worstRecall,
                pooled.worstPrecision);
    return pooled;
}

// Every fourth view of the accuracy command's 32-view sweep (a face, edges, corners, random
// ones); LINEWORK_SUGGESTIVE_SWEEP=1: all 32 (for BENCHMARKS.md).
std::vector<evaluation::View> scoredViews() {
    const std::vector<evaluation::View> sweep = evaluation::viewSweep(32);
    if (std::getenv("LINEWORK_SUGGESTIVE_SWEEP"))
        return sweep;
    std::vector<evaluation::View> views;
    for (std::size_t i = 0; i < sweep.size(); i += 4)
        views.push_back(sweep[i]);
    return views;
}

// The torus seen obliquely and the metaballs have suggestive contours (the torus's saddle-shaped
// inside, the blobs' necks); at 64^3 and 128^3, against the analytic reference.
TEST(SuggestiveContours, TorusAndMetaballsMatchTheAnalyticReference) {
    for (const char* name : {"torus", "metaballs"})
        for (const int n : {64, 128}) {
            const auto shape = evaluation::makeAnalyticShape(name);
            const Pooled pooled = scoreShape(*shape, n, scoredViews());
            SCOPED_TRACE(std::string(name) + " " + std::to_string(n));
            // Measured (dev-2c, BENCHMARKS.md): pooled >= 0.992 on these 8 views and >= 0.995 on
            // all 32; a single view with 20 or more true pixels >= 0.918 (recall) and 0.956
            // (precision) over the 32. The bounds leave room for rounding on other compilers,
            // not for a lost line: a missing stroke costs a view 0.2 or more.
            ASSERT_GT(pooled.truePixels, 100u);
            EXPECT_GT(double(pooled.trueFound) / double(pooled.truePixels), 0.97);
            EXPECT_GT(double(pooled.drawnMatched) / double(pooled.drawnPixels), 0.97);
            EXPECT_GT(pooled.worstRecall, 0.9);
            EXPECT_GT(pooled.worstPrecision, 0.9);
        }
}

} // namespace
