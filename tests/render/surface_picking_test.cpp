// Picking a pixel -> the surface point in patient coordinates (LPS, mm), through the depth
// buffer and through the mesh, on a sphere of known radius sampled on a regular anisotropic grid
// and on a tilted, unevenly spaced stack (geometry carried, nothing resampled).
#include "lw/render/surface_picking.h"
#include "picking_volumes.h"

#include <cstdio>
#include <gtest/gtest.h>

using namespace lw;
using lw::test::KnownSphere;

namespace {

struct PickErrors {
    int picked = 0;
    double worstDepth = 0.0; // mm off the sphere, depth-buffer picks
    double worstMesh = 0.0;  // mm off the sphere, mesh ray picks
};

// Picks every 11th pixel of the view and measures how far each point is from the true sphere.
PickErrors pickAcrossTheView(const render::Mesh& mesh, const KnownSphere& sphere,
                             const render::Camera& camera) {
    const std::vector<float> depth = test::depthBuffer(mesh, camera);
    PickErrors errors;
    for (int y = 3; y < camera.height(); y += 11)
        for (int x = 3; x < camera.width(); x += 11) {
            const glm::dvec2 pixel{x + 0.5, y + 0.5};
            const auto fromDepth = render::pickFromDepthBuffer(depth, camera, pixel);
            const auto fromMesh = render::pickMeshSurface(mesh, camera, pixel);
            EXPECT_EQ(fromDepth.has_value(), fromMesh.has_value()) << x << "," << y;
            if (!fromDepth || !fromMesh)
                continue;
            ++errors.picked;
            const auto off = [&](glm::dvec3 p) {
                return std::abs(glm::distance(p, sphere.centre) - sphere.radius);
            };
            errors.worstDepth = std::max(errors.worstDepth, off(*fromDepth));
            errors.worstMesh = std::max(errors.worstMesh, off(*fromMesh));
            // The nearest surface is picked, never the far side: the sphere's outward normal
            // there faces the eye (up to grazing at the rim).
            const glm::dvec3 outward = glm::normalize(*fromMesh - sphere.centre);
            EXPECT_GT(glm::dot(outward, camera.toViewer(*fromMesh)), -0.05);
        }
    return errors;
}

struct PickCase {
    const char* name;
    volume::Volume (*make)(KnownSphere*);
    double tolerance; // mm: marching cubes' chords inside the sphere, far below a voxel
};

class SurfacePicking : public ::testing::TestWithParam<PickCase> {};

TEST_P(SurfacePicking, PicksLieOnTheKnownSphereInEveryView) {
    KnownSphere sphere;
    const volume::Volume volume = GetParam().make(&sphere);
    const render::Mesh mesh = render::extractIsoSurface(volume, 0.0);
    ASSERT_FALSE(mesh.isEmpty());
    const double views[][2] = {{0, 0}, {90, 0}, {-135, 30}, {40, -60}, {10, 89}};
    for (const auto& view : views)
        for (const auto projection :
             {render::Projection::Orthographic, render::Projection::Perspective}) {
            SCOPED_TRACE(std::to_string(view[0]) + "," + std::to_string(view[1]));
            const PickErrors errors = pickAcrossTheView(
                mesh, sphere, test::cameraOnSphere(sphere, view[0], view[1], projection));
            std::printf("%s view %g,%g %s: %d picks, worst %.4f mm (depth), %.4f mm (mesh)\n",
                        GetParam().name, view[0], view[1],
                        projection == render::Projection::Orthographic ? "ortho" : "persp",
                        errors.picked, errors.worstDepth, errors.worstMesh);
            EXPECT_GT(errors.picked, 80); // the sphere covers about a quarter of the view
            EXPECT_LT(errors.worstDepth, GetParam().tolerance);
            EXPECT_LT(errors.worstMesh, GetParam().tolerance);
        }
}

INSTANTIATE_TEST_SUITE_P(KnownSpheres, SurfacePicking,
                         ::testing::Values(PickCase{"regular", test::regularSphereVolume, 0.1},
                                           PickCase{"tilted", test::tiltedSphereVolume, 0.1}),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(SurfacePicking, NothingWhereNoSurfaceIsOrOutsideTheViewport) {
    KnownSphere sphere;
    const volume::Volume volume = test::regularSphereVolume(&sphere);
    const render::Mesh mesh = render::extractIsoSurface(volume, 0.0);
    const render::Camera camera =
        test::cameraOnSphere(sphere, 0, 0, render::Projection::Perspective);
    const std::vector<float> depth = test::depthBuffer(mesh, camera);
    const glm::dvec2 corner{1.5, 1.5}; // the sphere is framed: the corners show background
    EXPECT_FALSE(render::pickFromDepthBuffer(depth, camera, corner));
    EXPECT_FALSE(render::pickMeshSurface(mesh, camera, corner));
    EXPECT_FALSE(render::pickFromDepthBuffer(depth, camera, {-1.0, 10.0}));
    EXPECT_FALSE(render::pickFromDepthBuffer(depth, camera, {10.0, camera.height() + 0.5}));
    // A buffer of another size than the camera's viewport is not read.
    EXPECT_FALSE(render::pickFromDepthBuffer(std::vector<float>(10, 0.5f), camera, {128, 128}));
}

} // namespace
