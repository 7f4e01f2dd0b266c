#include "lw/core/error.h"
#include "lw/evaluation/analytic_shapes.h"

#include <gtest/gtest.h>
#include <random>

using namespace lw::render;
using namespace lw::evaluation;

namespace {

glm::dvec3 randomPointIn(const Aabb& box, std::mt19937& random) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    return box.min + box.size() * glm::dvec3(unit(random), unit(random), unit(random));
}

} // namespace

class AnalyticShapeTest : public ::testing::TestWithParam<std::string> {};

TEST_P(AnalyticShapeTest, GradientMatchesFiniteDifferences) {
    const auto shape = makeAnalyticShape(GetParam());
    EXPECT_EQ(shape->name(), GetParam());
    std::mt19937 random(11);
    const double h = 1e-5;
    for (int i = 0; i < 300; ++i) {
        const glm::dvec3 p = randomPointIn(shape->bounds(), random);
        glm::dvec3 numeric;
        for (int axis = 0; axis < 3; ++axis) {
            glm::dvec3 step(0.0);
            step[axis] = h;
            numeric[axis] = (shape->value(p + step) - shape->value(p - step)) / (2.0 * h);
        }
        const glm::dvec3 analytic = shape->gradient(p);
        EXPECT_LT(glm::length(analytic - numeric), 1e-6 + 1e-5 * glm::length(analytic))
            << "at " << p.x << "," << p.y << "," << p.z;
        // Ray casting steps by |value| / lipschitz(): the bound must hold.
        EXPECT_LE(glm::length(analytic), shape->lipschitz() * (1.0 + 1e-9));
    }
}

TEST_P(AnalyticShapeTest, BoundsEncloseTheSolid) {
    const auto shape = makeAnalyticShape(GetParam());
    const Aabb box = shape->bounds();
    ASSERT_TRUE(box.isValid());
    const Aabb around{box.min - box.size(), box.max + box.size()};
    std::mt19937 random(5);
    int inside = 0, outsideBox = 0;
    for (int i = 0; i < 20000; ++i) {
        const glm::dvec3 p = randomPointIn(around, random);
        const bool inBox =
            glm::all(glm::greaterThanEqual(p, box.min)) && glm::all(glm::lessThanEqual(p, box.max));
        if (!inBox) {
            ++outsideBox;
            EXPECT_LT(shape->value(p), kShapeIso) << "solid outside its bounds";
        } else if (shape->value(p) >= kShapeIso) {
            ++inside;
        }
    }
    EXPECT_GT(inside, 20); // the solid fills a fair part of its box
    EXPECT_GT(outsideBox, 1000);
}

TEST_P(AnalyticShapeTest, SampledVolumeMatchesTheFunction) {
    const auto shape = makeAnalyticShape(GetParam());
    const int n = 20;
    const lw::volume::Volume volume = sampleShape(*shape, n);
    ASSERT_EQ(volume.dims(), glm::ivec3(n));
    ASSERT_EQ(volume.voxelType(), lw::volume::VoxelType::Float32);
    const auto& geometry = volume.geometry();
    EXPECT_DOUBLE_EQ(geometry.spacingI(), geometry.spacingJ());
    EXPECT_DOUBLE_EQ(geometry.spacingI(), geometry.sliceStep());
    // The bounding box lies inside the grid with at least two voxels to spare on every side.
    const Aabb box = shape->bounds();
    const glm::dvec3 first = geometry.indexToPatient({0, 0, 0});
    const glm::dvec3 last = geometry.indexToPatient(glm::dvec3(n - 1));
    const double spacing = geometry.spacingI();
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LE(first[axis] + 2 * spacing, box.min[axis] + 1e-9);
        EXPECT_GE(last[axis] - 2 * spacing, box.max[axis] - 1e-9);
    }
    const float* voxels = volume.dataAs<float>();
    int positive = 0;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                const float v = voxels[volume.index(x, y, z)];
                const double expected = shape->value(geometry.indexToPatient({x, y, z}));
                ASSERT_FLOAT_EQ(v, static_cast<float>(expected)) << x << "," << y << "," << z;
                positive += v >= kShapeIso ? 1 : 0;
                const bool border =
                    x == 0 || y == 0 || z == 0 || x == n - 1 || y == n - 1 || z == n - 1;
                if (border) {
                    ASSERT_LT(v, kShapeIso) << "surface not closed inside the grid";
                }
            }
    EXPECT_GT(positive, 0);
    EXPECT_THROW(sampleShape(*shape, 4), lw::core::Error);
}

INSTANTIATE_TEST_SUITE_P(AllShapes, AnalyticShapeTest, ::testing::ValuesIn(analyticShapeNames()),
                         [](const auto& info) { return info.param; });

TEST(AnalyticShapes, SignedDistanceValues) {
    const SphereShape sphere({1, 2, 3}, 10.0);
    EXPECT_DOUBLE_EQ(sphere.value({1, 2, 3}), 10.0);
    EXPECT_DOUBLE_EQ(sphere.value({11, 2, 3}), 0.0);
    EXPECT_DOUBLE_EQ(sphere.value({1, 2, 18}), -5.0);
    // Gradient points inward (toward larger values).
    EXPECT_NEAR(sphere.gradient({11, 2, 3}).x, -1.0, 1e-12);

    const TorusShape torus({0, 0, 0}, {0, 0, 1}, 40.0, 10.0);
    EXPECT_DOUBLE_EQ(torus.value({40, 0, 0}), 10.0);
    EXPECT_DOUBLE_EQ(torus.value({0, 0, 0}), -30.0); // the hole
    EXPECT_DOUBLE_EQ(torus.value({0, 50, 0}), 0.0);
    EXPECT_DOUBLE_EQ(torus.value({0, -40, 10}), 0.0);
}

TEST(AnalyticShapes, LinkedToriAreLinkedAndApart) {
    const LinkedToriShape tori(30.0, 9.0);
    // Each ring's tube passes through the other's hole: the centre of one ring is inside the
    // other ring's tube...
    EXPECT_GT(tori.value({30, 0, 0}), 0.0);
    EXPECT_GT(tori.value({0, 0, 0}), 0.0);
    // ...and the tubes never meet: along the segment between the two points the value dips below
    // iso.
    EXPECT_LT(tori.value({15, 0, 0}), 0.0);
    EXPECT_THROW(LinkedToriShape(30.0, 16.0), lw::core::Error);
}

TEST(AnalyticShapes, SuperquadricIsBoxLike) {
    const SuperquadricShape shape({0, 0, 0}, {40, 30, 20}, 0.3, 0.3);
    EXPECT_NEAR(shape.value({40, 0, 0}), 0.0, 1e-9);
    EXPECT_NEAR(shape.value({0, 0, 20}), 0.0, 1e-9);
    // A rounded box holds points near its edges that an ellipsoid would not.
    EXPECT_GT(shape.value({30, 22, 0}), 0.0);
    EXPECT_LT(SuperquadricShape({0, 0, 0}, {40, 30, 20}, 1.0, 1.0).value({30, 22, 0}), 0.0);
    EXPECT_THROW(SuperquadricShape({0, 0, 0}, {1, 1, 1}, 1.5, 0.5), lw::core::Error);
}

TEST(AnalyticShapes, UnknownNameThrows) {
    EXPECT_THROW(makeAnalyticShape("cube"), lw::core::Error);
}
