// The accuracy sweep's views: the cube's 26 directions (faces first, poles included) in the
// camera's own convention, then seeded random ones; rounded so --view repeats them.
#include "lw/core/error.h"
#include "lw/evaluation/view_sweep.h"
#include "lw/render/camera.h"

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <numbers>

using namespace lw::evaluation;
using lw::render::Camera;
using lw::render::CameraSetup;

namespace {

// Where the real camera looks from (unit, from the target toward the eye).
glm::dvec3 eyeDirection(const View& view) {
    CameraSetup setup;
    setup.azimuthDeg = view.azimuthDeg;
    setup.elevationDeg = view.elevationDeg;
    return -Camera(setup, 64, 64).forward();
}

bool sweepLooksFrom(const std::vector<View>& views, glm::dvec3 direction) {
    const double tolerance = std::cos(0.1 * std::numbers::pi / 180.0);
    for (const View& view : views)
        if (glm::dot(eyeDirection(view), glm::normalize(direction)) > tolerance)
            return true;
    return false;
}

TEST(ViewSweep, DefaultHasTheCubesTwentySixDirectionsAndRandomOnes) {
    const std::vector<View> views = viewSweep();
    ASSERT_EQ(int(views.size()), kDefaultSweepViewCount);
    ASSERT_GE(kDefaultSweepViewCount, kCubeViewCount + 6);
    for (std::size_t i = 0; i < views.size(); ++i)
        for (std::size_t j = i + 1; j < views.size(); ++j)
            EXPECT_FALSE(views[i] == views[j]) << i << " and " << j << " are the same view";
    for (int z = -1; z <= 1; ++z)
        for (int y = -1; y <= 1; ++y)
            for (int x = -1; x <= 1; ++x)
                if (x || y || z) {
                    EXPECT_TRUE(sweepLooksFrom(views, {x, y, z})) << x << "," << y << "," << z;
                }
}

TEST(ViewSweep, FacesComeFirstPolesIncluded) {
    const std::vector<View> faces = viewSweep(6);
    ASSERT_EQ(faces.size(), 6u);
    for (const glm::dvec3 axis : {glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)}) {
        EXPECT_TRUE(sweepLooksFrom(faces, axis));
        EXPECT_TRUE(sweepLooksFrom(faces, -axis));
    }
    // The standard names: anterior is az 0 el 0, the poles have az 0.
    EXPECT_TRUE(std::find(faces.begin(), faces.end(), View{0.0, 0.0}) != faces.end());
    EXPECT_TRUE(std::find(faces.begin(), faces.end(), View{0.0, 90.0}) != faces.end());
    EXPECT_TRUE(std::find(faces.begin(), faces.end(), View{0.0, -90.0}) != faces.end());
    EXPECT_TRUE(std::find(faces.begin(), faces.end(), View{180.0, 0.0}) != faces.end());
}

TEST(ViewSweep, RandomViewsAreRepeatableRoundedAndInRange) {
    const std::vector<View> a = viewSweep(60, 7);
    EXPECT_EQ(a, viewSweep(60, 7));
    EXPECT_NE(a, viewSweep(60, 8));
    EXPECT_EQ(std::vector<View>(a.begin(), a.begin() + 26), viewSweep(26, 8));
    for (const View& view : a) {
        EXPECT_GT(view.azimuthDeg, -180.0);
        EXPECT_LE(view.azimuthDeg, 180.0);
        EXPECT_LE(std::abs(view.elevationDeg), 90.0);
        EXPECT_DOUBLE_EQ(view.azimuthDeg, std::round(view.azimuthDeg * 10.0) / 10.0);
        EXPECT_DOUBLE_EQ(view.elevationDeg, std::round(view.elevationDeg * 10.0) / 10.0);
    }
}

TEST(ViewSweep, RejectsAnEmptySweep) {
    EXPECT_THROW(viewSweep(0), lw::core::Error);
}

} // namespace
