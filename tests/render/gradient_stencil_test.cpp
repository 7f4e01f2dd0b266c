// The smoothed gradient stencil (kernels/common voxel_grid.h, GradientStencil::Smoothed): exact
// on linear fields, at the faces and across uneven slice gaps as the central one is; weights
// that follow the real distances (the 3D Sobel operator on cubes, in-plane only across thick
// slices); normals steadier under voxel noise; and every consumer of the normals (marching
// cubes whole and chunked, the border cap, method 2's vertices) given the same stencil.

#include "float_volume.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cpu/raycast_silhouette_cpu.h"
#include "lw/kernels/voxel_grid.h"
#include "lw/render/iso_surface.h"

#include <cmath>
#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <random>
#include <vector>

namespace lw::render {
namespace {

using kernels::GradientStencil;
using kernels::McVec3;
using volume::Volume;
using volume::VoxelType;

using test::makeFloatVolume;

// Slices `gaps` mm apart (one entry per gap), square pixels of `pixel` mm, no tilt.
volume::VolumeGeometry stackGeometry(double pixel, const std::vector<double>& gaps) {
    std::vector<glm::dvec3> slices{{0.0, 0.0, 0.0}};
    for (const double gap : gaps)
        slices.push_back(slices.back() + glm::dvec3(0.0, 0.0, gap));
    return volume::VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, pixel, pixel, slices);
}

McVec3 gradientAt(const Volume& volume, GradientStencil stencil, glm::ivec3 p) {
    const kernels::VoxelGridSetup setup = kernels::cpu::voxelGridSetup(volume, stencil);
    const kernels::VoxelGradientSampler<float> sampler{volume.dataAs<float>(), setup.spans()};
    return sampler.gradient(p.x, p.y, p.z);
}

double angleDeg(glm::dvec3 a, glm::dvec3 b) {
    const double c = glm::dot(glm::normalize(a), glm::normalize(b));
    return std::acos(std::min(1.0, std::max(-1.0, c))) * 180.0 / 3.14159265358979323846;
}

class LinearField : public ::testing::TestWithParam<std::vector<double>> {};

// A linear field's differences are the same at every grid point, so any average of them is
// exact: the smoothed gradient equals the central one everywhere, faces and corners included,
// whatever the gaps.
TEST_P(LinearField, SmoothedGradientIsExact) {
    const std::vector<double> gaps = GetParam();
    const auto geometry = stackGeometry(0.8, gaps);
    const glm::ivec3 dims(7, 6, int(gaps.size()) + 1);
    const Volume v = makeFloatVolume(
        dims,
        [&](int x, int y, int z) {
            const glm::dvec3 p = geometry.indexToPatient({double(x), double(y), double(z)});
            return 3.0 * p.x - 2.0 * p.y + 0.5 * p.z;
        },
        geometry);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x) {
                const McVec3 central = gradientAt(v, GradientStencil::Central, {x, y, z});
                const McVec3 smoothed = gradientAt(v, GradientStencil::Smoothed, {x, y, z});
                ASSERT_NEAR(smoothed.x, 3.0f, 1e-4f) << x << "," << y << "," << z;
                ASSERT_NEAR(smoothed.y, -2.0f, 1e-4f) << x << "," << y << "," << z;
                ASSERT_NEAR(smoothed.z, central.z, 1e-4f) << x << "," << y << "," << z;
                ASSERT_NEAR(smoothed.z, 0.5f, 1e-4f) << x << "," << y << "," << z;
            }
}

INSTANTIATE_TEST_SUITE_P(Gaps, LinearField,
                         ::testing::Values(std::vector<double>{0.8, 0.8, 0.8, 0.8},
                                           std::vector<double>{5.0, 5.0, 5.0},
                                           std::vector<double>{0.8, 1.6, 0.8, 2.4, 0.8}));

// The cross weights are a Gaussian of the real distance, 1/2 at one pixel: the Sobel operator's
// 1-2-1 on cubes, and nothing across slices several pixels thick.
TEST(GradientStencil, CrossWeightsFollowTheSpacing) {
    const Volume cubes({4, 4, 4}, VoxelType::Float32, stackGeometry(0.7, {0.7, 0.7, 0.7}));
    const kernels::VoxelGridSetup cubic = kernels::cpu::voxelGridSetup(cubes);
    for (int axis = 0; axis < 3; ++axis)
        EXPECT_NEAR(cubic.spans().crossSide[axis], 0.25f, 1e-6f) << axis;
    // 5 mm slices of 0.5 mm pixels (the demo study's kind): in-plane only.
    const Volume thick({4, 4, 4}, VoxelType::Float32, stackGeometry(0.5, {5.0, 5.0, 5.0}));
    const kernels::VoxelGridSetup slab = kernels::cpu::voxelGridSetup(thick);
    EXPECT_NEAR(slab.spans().crossSide[0], 0.25f, 1e-6f);
    EXPECT_EQ(slab.spans().crossSide[2], 0.0f);
    // Slices 1.5 pixels apart: 0.5^2.25 = 0.21 relative to the centre.
    const Volume mid({4, 4, 4}, VoxelType::Float32, stackGeometry(1.0, {1.5, 1.5, 1.5}));
    const double relative = std::pow(0.5, 2.25);
    EXPECT_NEAR(kernels::cpu::voxelGridSetup(mid).spans().crossSide[2],
                relative / (1.0 + 2.0 * relative), 1e-6);
}

// A sphere of radius 10 voxels with uniform noise of +-15 % of the field's step per voxel: the
// smoothed normals lie closer to the true radial direction than the central ones, on average
// and in the worst tenth.
TEST(GradientStencil, SmoothedNormalsAreSteadierUnderNoise) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> noise(-0.15, 0.15);
    const glm::dvec3 centre(15.3, 15.6, 15.1);
    const Volume v = makeFloatVolume({32, 32, 32}, [&](int x, int y, int z) {
        return 10.0 - glm::length(glm::dvec3(x, y, z) - centre) + noise(random);
    });
    const auto errors = [&](GradientStencil stencil) {
        IsoSurfaceOptions options;
        options.gradientStencil = stencil;
        const Mesh mesh = extractIsoSurface(v, 0.0, options);
        std::vector<double> angles;
        for (std::size_t i = 0; i < mesh.vertexCount(); ++i)
            angles.push_back(
                angleDeg(glm::dvec3(mesh.normals[i]), glm::dvec3(mesh.positions[i]) - centre));
        std::sort(angles.begin(), angles.end());
        double sum = 0.0;
        for (const double a : angles)
            sum += a;
        return std::pair(sum / double(angles.size()), angles[angles.size() * 9 / 10]);
    };
    const auto [centralMean, centralP90] = errors(GradientStencil::Central);
    const auto [smoothMean, smoothP90] = errors(GradientStencil::Smoothed);
    EXPECT_GT(centralMean, 2.0) << "the noise should tilt the central normals";
    EXPECT_LT(smoothMean, 0.6 * centralMean);
    EXPECT_LT(smoothP90, 0.6 * centralP90);
}

// The stencil changes the normals only, never the vertices; whole and chunked extraction agree
// bit for bit with it as without it, and the border cap takes it too.
TEST(GradientStencil, ChangesNormalsOnlyAndEverySchedule) {
    std::mt19937 random(3);
    std::uniform_real_distribution<double> noise(-0.2, 0.2);
    const Volume v = makeFloatVolume({20, 18, 9}, [&](int x, int y, int z) {
        return 7.0 - glm::length(glm::dvec3(x - 9.5, y - 8.7, (z - 4.0) * 2.5)) + noise(random);
    });
    IsoSurfaceOptions central, smoothed, chunked;
    smoothed.gradientStencil = chunked.gradientStencil = GradientStencil::Smoothed;
    central.closeAtBorder = smoothed.closeAtBorder = chunked.closeAtBorder = true;
    chunked.brickCells = 5;
    const Mesh a = extractIsoSurface(v, 0.0, central);
    const Mesh b = extractIsoSurface(v, 0.0, smoothed);
    const Mesh c = extractIsoSurface(v, 0.0, chunked);
    ASSERT_GT(a.triangleCount(), 500u);
    EXPECT_TRUE(a.positions == b.positions);
    EXPECT_TRUE(a.indices == b.indices);
    EXPECT_FALSE(a.normals == b.normals);
    EXPECT_TRUE(b.positions == c.positions);
    EXPECT_TRUE(b.normals == c.normals);
    EXPECT_TRUE(b.indices == c.indices);
}

// Method 2 rebuilds the marching-cubes vertices cell by cell; with the smoothed stencil its
// segments are still those of the mesh (same normals bit for bit): one segment per triangle the
// normals' zero crossing passes through, compared by count and by the set of endpoints.
TEST(GradientStencil, MethodTwoSegmentsFollowTheSmoothedMesh) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> noise(-0.2, 0.2);
    const Volume v = makeFloatVolume({24, 24, 24}, [&](int x, int y, int z) {
        return 8.0 - glm::length(glm::dvec3(x - 11.7, y - 11.4, z - 11.9)) + noise(random);
    });
    const volume::BrickGrid grid = volume::BrickGrid::build(v, glm::ivec3(23));
    kernels::cpu::RayCastSilhouetteCpu method2;
    ASSERT_TRUE(method2.prepare(v, grid, 0.0, true, 1, nullptr, GradientStencil::Smoothed));
    kernels::cpu::SilhouetteView view;
    view.eyeOrDirection = {40.0, 31.0, 27.0};
    std::vector<kernels::SegmentEndpoints> segments;
    method2.extractSegments(view, segments, 1);

    IsoSurfaceOptions options;
    options.gradientStencil = GradientStencil::Smoothed;
    const Mesh mesh = extractIsoSurface(v, 0.0, options);
    std::size_t crossing = 0;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        int positive = 0;
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t i = mesh.indices[3 * t + std::size_t(k)];
            const glm::dvec3 toEye = view.eyeOrDirection - glm::dvec3(mesh.positions[i]);
            positive += glm::dot(glm::dvec3(mesh.normals[i]), toEye) > 0.0 ? 1 : 0;
        }
        crossing += positive == 1 || positive == 2 ? 1 : 0;
    }
    ASSERT_GT(segments.size(), 50u);
    // Exact zeros of n.v at a vertex (measure zero on this field) would be the only difference.
    EXPECT_EQ(segments.size(), crossing);
}

} // namespace
} // namespace lw::render
