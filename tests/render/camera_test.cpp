#include "lw/core/error.h"
#include "lw/render/camera.h"
#include "lw/volume/volume.h"

#include <gtest/gtest.h>
#include <random>

using namespace lw::render;

namespace {

constexpr double kEps = 1e-9;

CameraSetup setupFor(Projection projection, double az, double el, FitMode fit = FitMode::Sphere) {
    CameraSetup setup;
    setup.bounds = {{-30, -50, -20}, {70, 10, 40}};
    setup.azimuthDeg = az;
    setup.elevationDeg = el;
    setup.projection = projection;
    setup.fit = fit;
    return setup;
}

void expectNear(glm::dvec3 a, glm::dvec3 b, double tolerance = 1e-9) {
    EXPECT_NEAR(a.x, b.x, tolerance);
    EXPECT_NEAR(a.y, b.y, tolerance);
    EXPECT_NEAR(a.z, b.z, tolerance);
}

} // namespace

TEST(Camera, TargetProjectsToImageCentre) {
    for (auto projection : {Projection::Perspective, Projection::Orthographic})
        for (auto [az, el] :
             {std::pair{0.0, 0.0}, std::pair{37.0, -20.0}, std::pair{200.0, 75.0}}) {
            const Camera camera(setupFor(projection, az, el), 320, 200);
            const ProjectedPoint p = camera.project(camera.target());
            EXPECT_NEAR(p.pixel.x, 160.0, kEps);
            EXPECT_NEAR(p.pixel.y, 100.0, kEps);
            EXPECT_GT(p.depth, 0.0);
            expectNear(camera.target(), camera.setup().bounds.center());
        }
}

TEST(Camera, AzimuthElevationConventions) {
    const Camera front(setupFor(Projection::Perspective, 0, 0), 100, 100);
    const glm::dvec3 t = front.target();
    // Anterior is -y in LPS: the eye sits in front of the face, looking toward +y, superior up.
    EXPECT_LT(front.eye().y, t.y);
    EXPECT_NEAR(front.eye().x, t.x, kEps);
    EXPECT_NEAR(front.eye().z, t.z, kEps);
    expectNear(front.forward(), {0, 1, 0});
    expectNear(front.up(), {0, 0, 1});
    // The patient's left (+x) appears on the viewer's right, superior (+z) at the top.
    EXPECT_GT(front.project(t + glm::dvec3(10, 0, 0)).pixel.x, 50.0);
    EXPECT_LT(front.project(t + glm::dvec3(0, 0, 10)).pixel.y, 50.0);

    const Camera left(setupFor(Projection::Perspective, 90, 0), 100, 100);
    EXPECT_GT(left.eye().x, t.x);
    expectNear(left.forward(), {-1, 0, 0});
    expectNear(left.up(), {0, 0, 1});

    const Camera back(setupFor(Projection::Perspective, 180, 0), 100, 100);
    EXPECT_GT(back.eye().y, t.y);

    const Camera above(setupFor(Projection::Perspective, 0, 90), 100, 100);
    EXPECT_GT(above.eye().z, t.z);
    expectNear(above.forward(), {0, 0, -1});
    // Looking down on the vertex with the face at the bottom of the screen.
    expectNear(above.up(), {0, 1, 0});
    EXPECT_GT(above.project(t + glm::dvec3(0, -10, 0)).pixel.y, 50.0);

    const Camera below(setupFor(Projection::Perspective, 0, -90), 100, 100);
    EXPECT_LT(below.eye().z, t.z);

    // A right-handed screen frame for any view.
    const Camera odd(setupFor(Projection::Perspective, 123, -47), 100, 100);
    expectNear(glm::cross(odd.right(), odd.up()), -odd.forward());
}

TEST(Camera, OrthographicVersusPerspective) {
    const Camera ortho(setupFor(Projection::Orthographic, 30, 20), 200, 200);
    const Camera persp(setupFor(Projection::Perspective, 30, 20), 200, 200);
    const glm::dvec3 t = ortho.target();
    const glm::dvec3 lateral = 15.0 * ortho.right();
    const glm::dvec3 nearPoint = t + lateral - 20.0 * ortho.forward();
    const glm::dvec3 farPoint = t + lateral + 20.0 * ortho.forward();
    // Ortho: depth does not move a point on screen; perspective: nearer points spread out.
    EXPECT_NEAR(ortho.project(nearPoint).pixel.x, ortho.project(farPoint).pixel.x, 1e-9);
    EXPECT_GT(persp.project(nearPoint).pixel.x, persp.project(farPoint).pixel.x + 1.0);
    // Ortho rays are parallel, perspective rays share the eye.
    expectNear(ortho.rayThroughPixel(3, 4).direction, ortho.rayThroughPixel(150, 190).direction);
    expectNear(persp.rayThroughPixel(3, 4).origin, persp.eye());
    expectNear(persp.rayThroughPixel(150, 190).origin, persp.eye());
    EXPECT_GT(glm::length(persp.rayThroughPixel(3, 4).direction -
                          persp.rayThroughPixel(150, 190).direction),
              0.1);
    // The viewer direction: constant for ortho, toward the eye for perspective.
    expectNear(ortho.toViewer(nearPoint), -ortho.forward());
    expectNear(persp.toViewer(nearPoint), glm::normalize(persp.eye() - nearPoint));
}

TEST(Camera, RayThroughPixelAndProjectAgree) {
    std::mt19937 random(7);
    std::uniform_int_distribution<int> px(0, 255), py(0, 143);
    for (auto projection : {Projection::Perspective, Projection::Orthographic}) {
        const Camera camera(setupFor(projection, -60, 35), 256, 144);
        for (int i = 0; i < 50; ++i) {
            const int x = px(random), y = py(random);
            const Ray ray = camera.rayThroughPixel(x, y);
            EXPECT_NEAR(glm::length(ray.direction), 1.0, 1e-12);
            double previousDepth = -1e300;
            for (double t : {10.0, 100.0, 250.0}) {
                const ProjectedPoint p = camera.project(ray.at(t));
                EXPECT_NEAR(p.pixel.x, x + 0.5, 1e-7);
                EXPECT_NEAR(p.pixel.y, y + 0.5, 1e-7);
                EXPECT_GT(p.depth, previousDepth);
                previousDepth = p.depth;
            }
        }
    }
}

TEST(Camera, MatricesMatchProject) {
    for (auto projection : {Projection::Perspective, Projection::Orthographic}) {
        const Camera camera(setupFor(projection, 20, -10), 300, 150);
        const glm::dmat4 viewProjection = camera.viewProjectionMatrix();
        for (glm::dvec3 p :
             {glm::dvec3(0, 0, 0), glm::dvec3(60, -40, 30), glm::dvec3(-25, 5, -15)}) {
            const glm::dvec4 clip = viewProjection * glm::dvec4(p, 1.0);
            const glm::dvec3 ndc = glm::dvec3(clip) / clip.w;
            const ProjectedPoint projected = camera.project(p);
            EXPECT_NEAR(0.5 * (ndc.x + 1.0) * 300, projected.pixel.x, 1e-6);
            EXPECT_NEAR(0.5 * (1.0 - ndc.y) * 150, projected.pixel.y, 1e-6);
            EXPECT_NEAR(ndc.z, projected.ndcDepth, 1e-9);
            EXPECT_GT(projected.ndcDepth, -1.0);
            EXPECT_LT(projected.ndcDepth, 1.0);
        }
    }
}

TEST(Camera, FitKeepsTheBoxInsideTheViewport) {
    for (auto projection : {Projection::Perspective, Projection::Orthographic})
        for (auto fit : {FitMode::Sphere, FitMode::Box})
            for (auto [az, el] :
                 {std::pair{0.0, 0.0}, std::pair{45.0, 30.0}, std::pair{-100.0, -60.0}}) {
                const Camera camera(setupFor(projection, az, el, fit), 240, 160);
                double maxX = 0.0,
                       maxY = 0.0; // largest offset from the centre, relative to half the size
                for (int i = 0; i < 8; ++i) {
                    const ProjectedPoint p = camera.project(camera.setup().bounds.corner(i));
                    EXPECT_GE(p.pixel.x, 0.0);
                    EXPECT_LE(p.pixel.x, 240.0);
                    EXPECT_GE(p.pixel.y, 0.0);
                    EXPECT_LE(p.pixel.y, 160.0);
                    EXPECT_GT(p.ndcDepth, -1.0);
                    EXPECT_LT(p.ndcDepth, 1.0);
                    maxX = std::max(maxX, std::abs(p.pixel.x - 120.0) / 120.0);
                    maxY = std::max(maxY, std::abs(p.pixel.y - 80.0) / 80.0);
                }
                if (fit == FitMode::Box) // tight: one side touches the margin (5%)
                    EXPECT_NEAR(std::max(maxX, maxY), 1.0 / 1.05, 1e-6);
                else
                    EXPECT_LT(std::max(maxX, maxY), 1.0 / 1.05 + 1e-9);
            }
}

TEST(Camera, ImageSizeForVoxelCoverage) {
    for (auto projection : {Projection::Perspective, Projection::Orthographic}) {
        const CameraSetup setup = setupFor(projection, 10, 10);
        const double voxel = 0.8;
        const int size = Camera::squareSizeForVoxelCoverage(setup, voxel, 2.0);
        const Camera camera(setup, size, size);
        const double pixelsPerVoxel =
            voxel / camera.pixelFootprint(glm::length(camera.target() - camera.eye()));
        EXPECT_NEAR(pixelsPerVoxel, 2.0, 2.0 / size + 1e-9);
        EXPECT_GT(size, 100);
    }
    EXPECT_THROW(Camera::squareSizeForVoxelCoverage(CameraSetup{}, 0.0, 2.0), lw::core::Error);
}

TEST(Camera, InvalidSetupsThrow) {
    EXPECT_THROW(Camera(CameraSetup{}, 0, 10), lw::core::Error);
    CameraSetup inverted;
    inverted.bounds = {{1, 1, 1}, {0, 0, 0}};
    EXPECT_THROW(Camera(inverted, 10, 10), lw::core::Error);
    CameraSetup wide;
    wide.fovYDeg = 180.0;
    EXPECT_THROW(Camera(wide, 10, 10), lw::core::Error);
}

TEST(Camera, VolumeBoundsFollowTheGeometry) {
    using namespace lw::volume;
    const Volume volume({4, 6, 8}, VoxelType::UInt8,
                        VolumeGeometry::regular({10, 20, 30}, {0.5, 0.5, 2.0}));
    const Aabb box = volumeBounds(volume);
    expectNear(box.min, {10, 20, 30});
    expectNear(box.max, {11.5, 22.5, 44});
    // Flipped axes (a common DICOM orientation) still give min <= max.
    const Volume flipped({4, 6, 8}, VoxelType::UInt8,
                         VolumeGeometry::regular({10, 20, 30}, {1, 1, 1}, {-1, 0, 0}, {0, -1, 0}));
    const Aabb flippedBox = volumeBounds(flipped);
    expectNear(flippedBox.min, {7, 15, 30});
    expectNear(flippedBox.max, {10, 20, 37});
    EXPECT_THROW(volumeBounds(Volume()), lw::core::Error);
}

TEST(Camera, SurfaceBoundsFrameTheSurfaceNotTheAir) {
    // 64^3 of "air" (-1000) with a bright 6^3 block near one corner, 2 mm voxels, rescaled like CT.
    using lw::volume::Volume;
    Volume v({64, 64, 64}, lw::volume::VoxelType::Int16,
             lw::volume::VolumeGeometry::regular({-10, 20, 30}, {2, 2, 2}));
    v.setValueMapping({1.0, -1024.0});
    auto* voxels = v.dataAs<std::int16_t>();
    for (std::size_t i = 0; i < v.voxelCount(); ++i)
        voxels[i] = 24; // -1000 HU
    for (int z = 50; z < 56; ++z)
        for (int y = 4; y < 10; ++y)
            for (int x = 40; x < 46; ++x)
                voxels[v.index(x, y, z)] = 1524; // +500 HU
    const lw::render::Aabb all = lw::render::volumeBounds(v);
    const lw::render::Aabb surface = lw::render::surfaceBounds(v, 300.0);
    // The block's voxels, in mm, lie inside the surface box...
    EXPECT_LE(surface.min.x, -10 + 2 * 40.0);
    EXPECT_GE(surface.max.x, -10 + 2 * 45.0);
    EXPECT_LE(surface.min.z, 30 + 2 * 50.0);
    EXPECT_GE(surface.max.z, 30 + 2 * 55.0);
    // ...which is far smaller than the volume's (at most two 16-cell bricks per axis).
    EXPECT_LE(surface.size().x, 2 * 32.0 + 1e-9);
    EXPECT_LT(surface.radius(), 0.5 * all.radius());
    // No brick can hold an iso-value above every voxel: the whole volume is framed.
    const lw::render::Aabb none = lw::render::surfaceBounds(v, 3000.0);
    EXPECT_EQ(none.min, all.min);
    EXPECT_EQ(none.max, all.max);
}

TEST(Camera, RollTurnsTheScreenAboutTheViewAxis) {
    for (auto projection : {Projection::Perspective, Projection::Orthographic}) {
        CameraSetup setup = setupFor(projection, 30.0, 20.0);
        const Camera plain(setup, 400, 400);
        setup.rollDeg = 90.0;
        const Camera rolled(setup, 400, 400);
        // The camera turned counter-clockwise by 90 degrees: its up points to the old screen
        // left, so the picture turns clockwise.
        expectNear(rolled.up(), -plain.right());
        expectNear(rolled.right(), plain.up());
        expectNear(rolled.forward(), plain.forward());
        // A point to the plain view's right now projects below the centre.
        const glm::dvec3 p = plain.target() + 10.0 * plain.right();
        EXPECT_GT(plain.project(p).pixel.x, 200.0 + 1.0);
        EXPECT_NEAR(rolled.project(p).pixel.x, 200.0, 1e-6);
        EXPECT_GT(rolled.project(p).pixel.y, 200.0 + 1.0);
    }
}

TEST(Camera, ZoomMagnifiesAboutTheCentre) {
    for (auto projection : {Projection::Perspective, Projection::Orthographic}) {
        CameraSetup setup = setupFor(projection, -40.0, 10.0);
        const Camera fitted(setup, 300, 200);
        setup.zoom = 2.0;
        const Camera zoomed(setup, 300, 200);
        const glm::dvec3 p = fitted.target() + 7.0 * fitted.right() - 3.0 * fitted.up();
        const glm::dvec2 a = fitted.project(p).pixel - glm::dvec2(150, 100);
        const glm::dvec2 b = zoomed.project(p).pixel - glm::dvec2(150, 100);
        EXPECT_NEAR(b.x, 2.0 * a.x, 1e-6);
        EXPECT_NEAR(b.y, 2.0 * a.y, 1e-6);
        EXPECT_DOUBLE_EQ(zoomed.nearPlane(), fitted.nearPlane());
    }
    CameraSetup bad = setupFor(Projection::Perspective, 0, 0);
    bad.zoom = 0.0;
    EXPECT_THROW(Camera(bad, 10, 10), lw::core::Error);
}

TEST(Camera, PanMovesTheTargetAcrossTheScreenNotInDepth) {
    for (auto projection : {Projection::Perspective, Projection::Orthographic}) {
        CameraSetup setup = setupFor(projection, 120.0, -35.0);
        const Camera fitted(setup, 256, 256);
        setup.pan = {0.5, 0.0};
        const Camera panned(setup, 256, 256);
        // The box centre moves half the half-width (= a quarter of the screen) to the left.
        const ProjectedPoint centre = panned.project(setup.bounds.center());
        EXPECT_NEAR(centre.pixel.x, 128.0 - 64.0, 1e-6);
        EXPECT_NEAR(centre.pixel.y, 128.0, 1e-6);
        EXPECT_NEAR(centre.depth, fitted.project(setup.bounds.center()).depth, 1e-6);
    }
}

TEST(Camera, UnprojectInvertsProject) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> coordinate(-20.0, 20.0);
    for (auto projection : {Projection::Perspective, Projection::Orthographic}) {
        CameraSetup setup = setupFor(projection, 75.0, 70.0);
        setup.rollDeg = 15.0;
        setup.zoom = 1.7;
        setup.pan = {-0.2, 0.3};
        const Camera camera(setup, 640, 480);
        for (int i = 0; i < 20; ++i) {
            const glm::dvec3 p =
                setup.bounds.center() +
                glm::dvec3(coordinate(random), coordinate(random), coordinate(random));
            const ProjectedPoint projected = camera.project(p);
            expectNear(camera.unproject(projected.pixel, projected.ndcDepth), p, 1e-6);
        }
    }
}
