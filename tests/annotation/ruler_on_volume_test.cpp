// A ruler between two picked surface points measures a volume of known size: the diameter of a
// sphere, picked from its left and its right through the iso panel's depth buffer.
#include "lw/annotation/annotation.h"
#include "lw/render/surface_picking.h"
#include "picking_volumes.h"

#include <cstdio>
#include <gtest/gtest.h>

using namespace lw;
using lw::test::KnownSphere;

namespace {

// The surface point under the centre pixel of the view from (az, el).
glm::dvec3 pickCentre(const render::Mesh& mesh, const KnownSphere& sphere, double az, double el,
                      render::Projection projection) {
    const render::Camera camera = test::cameraOnSphere(sphere, az, el, projection, 512);
    const auto point = render::pickFromDepthBuffer(test::depthBuffer(mesh, camera), camera,
                                                   {camera.width() / 2.0, camera.height() / 2.0});
    EXPECT_TRUE(point.has_value());
    return point.value_or(glm::dvec3(0.0));
}

struct RulerCase {
    const char* name;
    volume::Volume (*make)(KnownSphere*);
    double tolerance; // relative
};

class RulerOnVolume : public ::testing::TestWithParam<RulerCase> {};

TEST_P(RulerOnVolume, MeasuresTheDiameterOfTheKnownSphere) {
    KnownSphere sphere;
    const volume::Volume volume = GetParam().make(&sphere);
    const render::Mesh mesh = render::extractIsoSurface(volume, 0.0);
    const double voxel = std::max({volume.geometry().spacingI(), volume.geometry().spacingJ(),
                                   volume.geometry().sliceStep()});
    // Opposite views: left-right, anterior-posterior, superior-inferior and an oblique pair.
    const double views[][4] = {
        {90, 0, -90, 0}, {0, 0, 180, 0}, {0, 89.9, 0, -89.9}, {35, 25, 215, -25}};
    for (const auto& v : views)
        for (const auto projection :
             {render::Projection::Orthographic, render::Projection::Perspective}) {
            annotation::Annotation ruler{annotation::AnnotationKind::Ruler,
                                         {pickCentre(mesh, sphere, v[0], v[1], projection),
                                          pickCentre(mesh, sphere, v[2], v[3], projection)},
                                         {}};
            const double length = annotation::rulerLengthMm(ruler);
            const double diameter = 2.0 * sphere.radius;
            SCOPED_TRACE(std::to_string(v[0]) + "," + std::to_string(v[1]) + ": " +
                         annotation::measurementText(ruler));
            std::printf("%s %g,%g: %.3f mm for %.1f mm (%.3f %%)\n", GetParam().name, v[0], v[1],
                        length, diameter, 100.0 * (length - diameter) / diameter);
            EXPECT_NEAR(length, diameter, GetParam().tolerance * diameter);
            EXPECT_LT(std::abs(length - diameter), voxel); // within one voxel
        }
}

// The issue asks for 0.5 % on a known volume and one voxel on the tilted series; both hold with
// room to spare (marching cubes' chords and half a pixel off the centre).
INSTANTIATE_TEST_SUITE_P(KnownSpheres, RulerOnVolume,
                         ::testing::Values(RulerCase{"regular", test::regularSphereVolume, 0.005},
                                           RulerCase{"tilted", test::tiltedSphereVolume, 0.005}),
                         [](const auto& info) { return std::string(info.param.name); });

} // namespace
