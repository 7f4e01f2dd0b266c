// Closing the iso-surface where the volume's border cuts it (issue 7,
// kernels/cpu/border_cap_cpu.h): the closed surface is watertight in every geometry, it is the
// surface of the volume padded with a value far outside, and every method draws the cut outline, S
// and L alike.
#include "backends_under_test.h"
#include "lw/kernels/cpu/border_cap_cpu.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/volume/volume.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace lw;
using render::Mesh;

// A ball centred near a corner of the volume: the border cuts it on three faces.
volume::Volume cutBall(volume::VolumeGeometry geometry) {
    const glm::ivec3 dims(20, 18, 16);
    volume::Volume volume(dims, volume::VoxelType::Float32, std::move(geometry));
    const glm::vec3 centre(4.3f, 5.1f, 12.2f);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                volume.dataAs<float>()[volume.index(x, y, z)] =
                    9.0f - glm::length(glm::vec3(x, y, z) - centre);
    return volume;
}

struct GeometryCase {
    const char* name;
    volume::VolumeGeometry geometry;
};

std::vector<GeometryCase> geometries() {
    std::vector<glm::dvec3> tiltedUneven;
    double offset = 0.0;
    for (int k = 0; k < 16; ++k) {
        tiltedUneven.push_back({0.0, 0.35 * offset, offset}); // sheared: a gantry tilt
        offset += k % 3 == 0 ? 1.5 : 0.75;                    // uneven gaps
    }
    return {
        {"regular", volume::VolumeGeometry::regular({-3.0, 2.0, 1.0}, {0.8, 0.9, 1.25})},
        {"tilted_uneven",
         volume::VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 0.7, 0.7, tiltedUneven)},
    };
}

using EdgeUses = std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int>;

std::array<float, 3> key(glm::vec3 p) {
    return {p.x, p.y, p.z};
}

// Directed edges by vertex position (the cap repeats the open surface's border-plane vertices,
// same bits, not their indices): +1 per use in one direction, a count per undirected edge.
// Triangles with two vertices at one position are left out: where the cap meets itself along an
// edge of the volume, the crossings of two faces' pad edges sit on the same border voxel (the
// padding's limit puts them there), joined by slivers of zero area; leaving a sliver out drops
// one pair of opposite edges.
void countEdges(const Mesh& mesh, EdgeUses& directed, EdgeUses& undirected) {
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::vec3 p0 = mesh.positions[mesh.indices[3 * t]],
                        p1 = mesh.positions[mesh.indices[3 * t + 1]],
                        p2 = mesh.positions[mesh.indices[3 * t + 2]];
        if (p0 == p1 || p1 == p2 || p0 == p2)
            continue;
        for (int e = 0; e < 3; ++e) {
            const auto a = key(mesh.positions[mesh.indices[3 * t + std::size_t(e)]]);
            const auto b = key(mesh.positions[mesh.indices[3 * t + std::size_t((e + 1) % 3)]]);
            ++directed[{a, b}];
            ++undirected[{std::min(a, b), std::max(a, b)}];
        }
    }
}

// Edges not shared by exactly two triangles wound opposite ways: the surface's holes.
std::size_t openEdges(const Mesh& mesh) {
    EdgeUses directed, undirected;
    countEdges(mesh, directed, undirected);
    std::size_t open = 0;
    for (const auto& [edge, uses] : undirected) {
        const bool twice = uses == 2;
        const bool opposite = directed.count(edge) && directed.count({edge.second, edge.first}) &&
                              directed[edge] == 1 && directed[{edge.second, edge.first}] == 1;
        open += twice && opposite ? 0 : 1;
    }
    return open;
}

class BorderCapGeometry : public testing::TestWithParam<GeometryCase> {};

TEST_P(BorderCapGeometry, ClosedSurfaceIsWatertightAndOpenOneIsNot) {
    const volume::Volume volume = cutBall(GetParam().geometry);
    render::IsoSurfaceOptions closed;
    closed.closeAtBorder = true;
    const Mesh openMesh = render::extractIsoSurface(volume, 0.0);
    const Mesh closedMesh = render::extractIsoSurface(volume, 0.0, closed);
    ASSERT_GT(openMesh.triangleCount(), 100u);
    EXPECT_GT(openEdges(openMesh), 20u) << "the border cuts the ball open";
    EXPECT_EQ(openEdges(closedMesh), 0u);
    // The closed surface is the open one plus the cap, appended.
    const Mesh cap = kernels::cpu::borderCap(volume, 0.0);
    ASSERT_GT(cap.triangleCount(), 20u);
    EXPECT_EQ(closedMesh.triangleCount(), openMesh.triangleCount() + cap.triangleCount());
    EXPECT_TRUE(std::equal(openMesh.positions.begin(), openMesh.positions.end(),
                           closedMesh.positions.begin()));
    for (const glm::vec3 n : cap.normals)
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

TEST_P(BorderCapGeometry, CapLiesInTheBorderPlanes) {
    const volume::Volume volume = cutBall(GetParam().geometry);
    const Mesh cap = kernels::cpu::borderCap(volume, 0.0);
    const volume::VolumeGeometry& g = volume.geometry();
    const glm::dvec3 last = glm::dvec3(volume.dims() - 1);
    for (const glm::vec3 p : cap.positions) {
        // Back to (fractional) indices through the slice stack: one index lies on a face.
        const glm::dvec3 d = glm::dvec3(p) - g.origin();
        const glm::dmat3 frame(g.spacingI() * g.axisI(), g.spacingJ() * g.axisJ(), g.stackAxis());
        const glm::dvec3 u = glm::inverse(frame) * d; // (i, j, offset)
        const double i = u.x, j = u.y;
        const double firstOffset = g.sliceOffset(0.0), lastOffset = g.sliceOffset(last.z);
        const bool onI = std::abs(i) < 1e-3 || std::abs(i - last.x) < 1e-3;
        const bool onJ = std::abs(j) < 1e-3 || std::abs(j - last.y) < 1e-3;
        const bool onK = std::abs(u.z - firstOffset) < 1e-3 || std::abs(u.z - lastOffset) < 1e-3;
        EXPECT_TRUE(onI || onJ || onK) << p.x << " " << p.y << " " << p.z;
    }
}

INSTANTIATE_TEST_SUITE_P(Geometries, BorderCapGeometry, testing::ValuesIn(geometries()),
                         [](const testing::TestParamInfo<GeometryCase>& info) {
                             return std::string(info.param.name);
                         });

// The triangles as sorted position triples (rotated to start at the smallest vertex, so the
// winding stays part of the key), for comparing meshes numbered differently.
std::vector<std::array<float, 9>> triangleSet(const Mesh& mesh) {
    std::vector<std::array<float, 9>> set;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        std::array<std::array<float, 3>, 3> v;
        for (int c = 0; c < 3; ++c)
            v[std::size_t(c)] = key(mesh.positions[mesh.indices[3 * t + std::size_t(c)]]);
        const auto first = std::min_element(v.begin(), v.end()) - v.begin();
        std::array<float, 9> tri{};
        for (int c = 0; c < 3; ++c)
            for (int a = 0; a < 3; ++a)
                tri[std::size_t(3 * c + a)] = v[std::size_t((first + c) % 3)][std::size_t(a)];
        set.push_back(tri);
    }
    std::sort(set.begin(), set.end());
    return set;
}

// The closed surface of `volume` (float, iso 0, regular geometry of `spacing` from `origin`)
// against marching cubes of the volume padded by one voxel of -1e30 on every side.
void expectCapIsPaddedSurface(const volume::Volume& volume, glm::dvec3 origin, glm::dvec3 spacing) {
    const glm::ivec3 d = volume.dims();
    volume::Volume padded(d + 2, volume::VoxelType::Float32,
                          volume::VolumeGeometry::regular(origin - spacing, spacing));
    for (int z = 0; z < d.z + 2; ++z)
        for (int y = 0; y < d.y + 2; ++y)
            for (int x = 0; x < d.x + 2; ++x) {
                const bool inside = x >= 1 && x <= d.x && y >= 1 && y <= d.y && z >= 1 && z <= d.z;
                padded.dataAs<float>()[padded.index(x, y, z)] =
                    inside ? volume.dataAs<float>()[volume.index(x - 1, y - 1, z - 1)] : -1e30f;
            }
    render::IsoSurfaceOptions closing;
    closing.closeAtBorder = true;
    const auto expected = triangleSet(render::extractIsoSurface(padded, 0.0));
    const auto closed = triangleSet(render::extractIsoSurface(volume, 0.0, closing));
    ASSERT_EQ(closed.size(), expected.size());
    for (std::size_t t = 0; t < closed.size(); ++t)
        for (std::size_t c = 0; c < 9; ++c)
            ASSERT_NEAR(closed[t][c], expected[t][c], 1e-4) << "triangle " << t;
}

TEST(BorderCap, IsTheSurfaceOfTheVolumePaddedFarOutside) {
    const glm::dvec3 origin(-3.0, 2.0, 1.0), spacing(0.5);
    expectCapIsPaddedSurface(cutBall(volume::VolumeGeometry::regular(origin, spacing)), origin,
                             spacing);
}

// Scattered inside voxels: rows whose only inside voxel is the first or the last, rows with
// none next to rows with some, and every face and edge of the box (the cap walks each shell row
// only over the columns its inside voxels reach).
TEST(BorderCap, IsThePaddedSurfaceOfScatteredVoxels) {
    const glm::dvec3 origin(1.0, -2.0, 0.5), spacing(0.5, 0.75, 2.0);
    for (const unsigned seed : {1u, 2u, 3u}) {
        std::mt19937 random(seed);
        std::bernoulli_distribution inside(0.15);
        volume::Volume volume(glm::ivec3(11, 7, 5), volume::VoxelType::Float32,
                              volume::VolumeGeometry::regular(origin, spacing));
        for (std::size_t v = 0; v < volume.voxelCount(); ++v)
            volume.dataAs<float>()[v] = inside(random) ? 1.0f : -1.0f;
        SCOPED_TRACE("seed " + std::to_string(seed));
        expectCapIsPaddedSurface(volume, origin, spacing);
    }
}

// The faces' maxima, read once per volume, stand in for each iso-value's scan of the border: the
// same cap, byte for byte, at iso-values below, between and above the faces' values (NaN on a
// face is never inside).
TEST(BorderCap, FaceMaximaGiveTheSameCap) {
    std::mt19937 random(7);
    std::uniform_real_distribution<float> value(-1.0f, 1.0f);
    volume::Volume volume(glm::ivec3(9, 7, 5), volume::VoxelType::Float32,
                          volume::VolumeGeometry::regular({0.0, 0.0, 0.0}, {0.5, 0.6, 1.5}));
    for (std::size_t v = 0; v < volume.voxelCount(); ++v)
        volume.dataAs<float>()[v] = value(random);
    volume.dataAs<float>()[volume.index(0, 3, 2)] = std::numeric_limits<float>::quiet_NaN();
    const kernels::cpu::BorderFaceMaxima maxima = kernels::cpu::borderFaceMaxima(volume);
    const glm::ivec3 d = volume.dims();
    std::array<double, 6> expected;
    expected.fill(-std::numeric_limits<double>::infinity());
    for (int z = 0; z < d.z; ++z)
        for (int y = 0; y < d.y; ++y)
            for (int x = 0; x < d.x; ++x) {
                const double v = volume.dataAs<float>()[volume.index(x, y, z)];
                const bool on[6] = {x == 0,       x == d.x - 1, y == 0,
                                    y == d.y - 1, z == 0,       z == d.z - 1};
                for (std::size_t f = 0; f < 6; ++f)
                    if (on[f] && v > expected[f])
                        expected[f] = v;
            }
    EXPECT_EQ(maxima.value, expected);
    // Bytes, not values: the NaN's neighbours have NaN normals, equal to nothing.
    const auto sameBytes = [](const Mesh& a, const Mesh& b) {
        const auto same = [](const auto& u, const auto& v) {
            return u.size() == v.size() &&
                   (u.empty() ||
                    std::memcmp(u.data(), v.data(), u.size() * sizeof(u.front())) == 0);
        };
        return same(a.positions, b.positions) && same(a.normals, b.normals) &&
               a.indices == b.indices;
    };
    for (const double iso :
         {-2.0, -0.5, 0.0, 0.7, *std::min_element(expected.begin(), expected.end()),
          *std::max_element(expected.begin(), expected.end()), 2.0}) {
        const Mesh scanned = kernels::cpu::borderCap(volume, iso);
        EXPECT_TRUE(sameBytes(
            kernels::cpu::borderCap(volume, iso, kernels::GradientStencil::Central, &maxima),
            scanned))
            << iso;
    }
}

// Where the first and the last slice alone hold inside voxels (a head cut by both ends of the
// series), their caps are made side by side: the same bytes as the one walk over the shell,
// which runs where a side face is marked as holding an inside voxel (it holds none here, so that
// walk emits the same cells in the same order), and the surface of the padded volume.
TEST(BorderCap, BothEndsMadeApartAreTheOneWalksBytes) {
    for (const int slices : {2, 3, 6}) {
        SCOPED_TRACE(std::to_string(slices) + " slices");
        const glm::dvec3 origin(0.5, -1.0, 2.0), spacing(0.5, 0.5, 1.25);
        volume::Volume volume(glm::ivec3(13, 11, slices), volume::VoxelType::Float32,
                              volume::VolumeGeometry::regular(origin, spacing));
        for (int z = 0; z < slices; ++z) // a tube along z, thicker at one end, off the sides
            for (int y = 0; y < 11; ++y)
                for (int x = 0; x < 13; ++x) {
                    const double r = std::hypot(x - 6.0, y - 5.0);
                    volume.dataAs<float>()[volume.index(x, y, z)] =
                        float(std::min(r - 1.5, 3.5 + 0.2 * z - r));
                }
        kernels::cpu::BorderFaceMaxima oneWalk = kernels::cpu::borderFaceMaxima(volume);
        for (std::size_t side = 0; side < 4; ++side)
            ASSERT_LT(oneWalk.value[side], 0.0) << "side face " << side;
        ASSERT_GE(oneWalk.value[4], 0.0);
        ASSERT_GE(oneWalk.value[5], 0.0);
        oneWalk.value[0] = 1.0;
        const Mesh apart = kernels::cpu::borderCap(volume, 0.0);
        const Mesh walked =
            kernels::cpu::borderCap(volume, 0.0, kernels::GradientStencil::Central, &oneWalk);
        ASSERT_GT(apart.triangleCount(), 0u);
        ASSERT_EQ(apart.positions.size(), walked.positions.size());
        EXPECT_EQ(std::memcmp(apart.positions.data(), walked.positions.data(),
                              apart.positions.size() * sizeof(apart.positions.front())),
                  0);
        EXPECT_EQ(std::memcmp(apart.normals.data(), walked.normals.data(),
                              apart.normals.size() * sizeof(apart.normals.front())),
                  0);
        EXPECT_EQ(apart.indices, walked.indices);
        expectCapIsPaddedSurface(volume, origin, spacing);
    }
}

TEST(BorderCap, EmptyWhenTheBorderHoldsNoInsideVoxel) {
    volume::Volume volume(glm::ivec3(12, 12, 12), volume::VoxelType::Int16);
    std::fill_n(volume.dataAs<std::int16_t>(), volume.voxelCount(), std::int16_t(0));
    volume.dataAs<std::int16_t>()[volume.index(6, 6, 6)] = 1000;
    EXPECT_EQ(kernels::cpu::borderCap(volume, 500.0).triangleCount(), 0u);
    // A volume entirely inside: the cap is the whole box.
    std::fill_n(volume.dataAs<std::int16_t>(), volume.voxelCount(), std::int16_t(1000));
    const Mesh box = kernels::cpu::borderCap(volume, 500.0);
    EXPECT_EQ(openEdges(box), 0u);
    EXPECT_GE(box.triangleCount(), 6u * 2u * 11u * 11u);
}

// A box of bone cut by two faces of the volume (x = 0 and the last slice), as where a scan's
// first or last slice cuts the skull.
volume::Volume boxCutByTheBorder() {
    const glm::ivec3 dims(40, 40, 40);
    volume::Volume volume(dims, volume::VoxelType::Int16);
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                volume.dataAs<std::int16_t>()[volume.index(x, y, z)] =
                    x <= 25 && y >= 8 && y <= 30 && z >= 10 ? 1000 : 0;
    return volume;
}

// The outline of the shaded panel: surface pixels with a 4-neighbour of background (or the edge).
render::PixelMask shadedOutline(const Mesh& mesh, const render::Camera& camera) {
    const core::ImageRgba8 shaded = render::shadeSurfaceCpu(mesh, camera);
    const int w = camera.width(), h = camera.height();
    auto surface = [&](int x, int y) {
        if (x < 0 || y < 0 || x >= w || y >= h)
            return false;
        const core::Rgba8 p = shaded.at(x, y);
        return !(p.r == 255 && p.g == 255 && p.b == 255);
    };
    render::PixelMask outline(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (surface(x, y) && (!surface(x - 1, y) || !surface(x + 1, y) || !surface(x, y - 1) ||
                                  !surface(x, y + 1)))
                outline.set(x, y);
    return outline;
}

double coverage(const render::PixelMask& outline, const render::PixelMask& lines) {
    const render::PixelMask near = lines.dilated(1);
    std::size_t covered = 0;
    for (int y = 0; y < outline.height(); ++y)
        for (int x = 0; x < outline.width(); ++x)
            covered += outline.get(x, y) && near.get(x, y) ? 1 : 0;
    return double(covered) / double(std::max<std::size_t>(outline.count(), 1));
}

struct MethodOnBackend {
    render::SilhouetteMethod method;
    render::Backend backend;
};

class ClosedOutline : public testing::TestWithParam<MethodOnBackend> {};

TEST_P(ClosedOutline, EveryMethodDrawsTheCutOutlineSAndLAlike) {
    const volume::Volume volume = boxCutByTheBorder();
    auto renderer = render::createSilhouetteRenderer(GetParam().method, GetParam().backend);
    renderer->setVolume(volume);
    render::CameraSetup setup;
    setup.bounds = render::volumeBounds(volume);
    setup.azimuthDeg = 215;
    setup.elevationDeg = 25;
    const render::Camera camera(setup, 200, 200);
    render::SilhouetteSettings settings;
    settings.isoReal = 500;
    render::IsoSurfaceOptions closed;
    closed.closeAtBorder = true;
    const render::PixelMask outline =
        shadedOutline(render::extractIsoSurface(volume, settings.isoReal, closed), camera);
    ASSERT_GT(outline.count(), 300u) << "the box must show";

    const render::SilhouetteFrame whole = renderer->render(camera, settings);
    EXPECT_GE(coverage(outline, whole.lines), 0.98);
    settings.brickCells = 16;
    const render::SilhouetteFrame chunked = renderer->render(camera, settings);
    EXPECT_EQ(chunked.lines, whole.lines);

    // Open at the border, the cut faces' edges have no contour (the defect closing mends).
    settings.closeAtBorder = false;
    settings.brickCells = 0;
    const render::SilhouetteFrame open = renderer->render(camera, settings);
    EXPECT_LT(coverage(outline, open.lines), 0.9);
}

// Methods 2 and 3 here; method 1 (OpenGL) in the same tests built as render_border_cap_gl_tests,
// which needs a headless GL context.
std::vector<MethodOnBackend> methodsOnBackends() {
#if LINEWORK_BORDER_CAP_METHOD1
    const std::vector<render::SilhouetteMethod> methods{render::SilhouetteMethod::GeometryShader};
#else
    const std::vector<render::SilhouetteMethod> methods{render::SilhouetteMethod::RayCastVisibility,
                                                        render::SilhouetteMethod::ZBuffer};
#endif
    std::vector<MethodOnBackend> cases;
    for (const render::Backend backend : test::backendsUnderTest())
        for (const render::SilhouetteMethod method : methods)
            cases.push_back({method, backend});
    return cases;
}

INSTANTIATE_TEST_SUITE_P(Methods, ClosedOutline, testing::ValuesIn(methodsOnBackends()),
                         [](const testing::TestParamInfo<MethodOnBackend>& info) {
                             return "method" + std::to_string(int(info.param.method)) + "_" +
                                    std::string(render::backendName(info.param.backend));
                         });

} // namespace
