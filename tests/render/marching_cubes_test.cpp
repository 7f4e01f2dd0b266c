#include "float_volume.h"
#include "lw/core/error.h"
#include "lw/core/limits.h"
#include "lw/kernels/marching_cubes_tables.h"
#include "lw/render/iso_surface.h"
#include "lw/volume/phantom.h"

#include <bit>
#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <map>
#include <random>
#include <utility>

namespace lw::render {
namespace {

using volume::Volume;
using volume::VoxelType;

using test::makeFloatVolume;

// Every undirected edge of a closed surface is shared by exactly two triangles, once in each
// direction (consistent winding). Returns a description of the first violation, or "".
std::string closedSurfaceProblem(const Mesh& mesh) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> directed;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
        for (int e = 0; e < 3; ++e) {
            const std::uint32_t a = mesh.indices[t * 3 + std::size_t(e)];
            const std::uint32_t b = mesh.indices[t * 3 + std::size_t((e + 1) % 3)];
            if (a == b)
                return "triangle " + std::to_string(t) + " repeats a vertex";
            ++directed[{a, b}];
        }
    for (const auto& [edge, count] : directed) {
        const auto back = directed.find({edge.second, edge.first});
        if (count != 1 || back == directed.end() || back->second != 1)
            return "edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) +
                   " used " + std::to_string(count) + " times forward, " +
                   std::to_string(back == directed.end() ? 0 : back->second) + " backward";
    }
    std::vector<bool> used(mesh.vertexCount(), false);
    for (auto i : mesh.indices) {
        if (i >= mesh.vertexCount())
            return "index out of range";
        used[i] = true;
    }
    for (std::size_t i = 0; i < used.size(); ++i)
        if (!used[i])
            return "vertex " + std::to_string(i) + " unused";
    return {};
}

void expectIdentical(const Mesh& a, const Mesh& b, const std::string& what) {
    ASSERT_EQ(a.positions.size(), b.positions.size()) << what;
    ASSERT_EQ(a.indices.size(), b.indices.size()) << what;
    EXPECT_EQ(
        std::memcmp(a.positions.data(), b.positions.data(), a.positions.size() * sizeof(glm::vec3)),
        0)
        << what;
    EXPECT_EQ(std::memcmp(a.normals.data(), b.normals.data(), a.normals.size() * sizeof(glm::vec3)),
              0)
        << what;
    EXPECT_TRUE(a.indices == b.indices) << what;
}

IsoSurfaceOptions bricks(int cells, unsigned threads = 0) {
    IsoSurfaceOptions o;
    o.brickCells = cells;
    o.threads = threads;
    return o;
}

TEST(MarchingCubes, EmptyAndFullVolumesHaveNoTriangles) {
    const Volume empty = makeFloatVolume({6, 5, 4}, [](int, int, int) { return 0.0; });
    const Volume full = makeFloatVolume({6, 5, 4}, [](int, int, int) { return 1.0; });
    EXPECT_TRUE(extractIsoSurface(empty, 0.5).isEmpty());
    EXPECT_TRUE(extractIsoSurface(full, 0.5).isEmpty());
    // Inside is value >= iso: a volume exactly at the iso-value is full, not a surface.
    EXPECT_TRUE(extractIsoSurface(full, 1.0).isEmpty());
    EXPECT_TRUE(extractIsoSurface(full, 0.5, bricks(2)).isEmpty());
    // Degenerate grids have no cells.
    const Volume flat = makeFloatVolume({6, 5, 1}, [](int x, int, int) { return x; });
    EXPECT_TRUE(extractIsoSurface(flat, 2.5).isEmpty());
}

TEST(MarchingCubes, OneVoxelGivesAClosedOctahedron) {
    const Volume v = makeFloatVolume(
        {3, 3, 3}, [](int x, int y, int z) { return x == 1 && y == 1 && z == 1 ? 1.0 : 0.0; });
    const Mesh mesh = extractIsoSurface(v, 0.5);
    EXPECT_EQ(mesh.triangleCount(), 8u);
    EXPECT_EQ(mesh.vertexCount(), 6u);
    EXPECT_EQ(closedSurfaceProblem(mesh), "");
    for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
        const glm::vec3 d = mesh.positions[i] - glm::vec3(1.0f);
        EXPECT_NEAR(glm::length(d), 0.5f, 1e-6f);
        EXPECT_GT(glm::dot(mesh.normals[i], glm::normalize(d)), 0.99f) << "normal not outward";
    }
}

// Every cube case on a 2x2x2 volume: the triangle count is the table's, every vertex lies on a
// crossing edge of the case (midpoint, values 0/1 at iso 0.5) and each crossing edge is used.
TEST(MarchingCubes, AllCubeCases) {
    for (int c = 0; c < 256; ++c) {
        const Volume v = makeFloatVolume({2, 2, 2}, [c](int x, int y, int z) {
            for (int k = 0; k < 8; ++k)
                if (kernels::kMcCornerOffset[k][0] == x && kernels::kMcCornerOffset[k][1] == y &&
                    kernels::kMcCornerOffset[k][2] == z)
                    return (c >> k) & 1 ? 1.0 : 0.0;
            return -1.0;
        });
        const Mesh mesh = extractIsoSurface(v, 0.5);
        EXPECT_EQ(mesh.triangleCount(), kernels::kMcTriangleCount.count[c]) << "case " << c;
        const int crossing = std::popcount(unsigned(kernels::kMcEdgeTable[c]));
        EXPECT_EQ(int(mesh.vertexCount()), crossing) << "case " << c;
        int seen = 0;
        for (const glm::vec3& p : mesh.positions) {
            bool onEdge = false;
            for (int e = 0; e < 12; ++e) {
                if (!((kernels::kMcEdgeTable[c] >> e) & 1))
                    continue;
                const auto* a = kernels::kMcCornerOffset[kernels::kMcEdgeCorners[e][0]];
                const auto* b = kernels::kMcCornerOffset[kernels::kMcEdgeCorners[e][1]];
                const glm::vec3 mid =
                    0.5f * (glm::vec3(a[0], a[1], a[2]) + glm::vec3(b[0], b[1], b[2]));
                if (glm::length(p - mid) < 1e-6f) {
                    onEdge = true;
                    seen |= 1 << e;
                }
            }
            EXPECT_TRUE(onEdge) << "case " << c << ": vertex off the crossing edges";
        }
        EXPECT_EQ(seen, int(kernels::kMcEdgeTable[c])) << "case " << c;
        // Open boundary edges of a single cell must lie in a cube face (they continue in the
        // neighbour); an edge through the cube's interior would be a hole.
        std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
        for (std::size_t t = 0; t < mesh.triangleCount(); ++t)
            for (int e = 0; e < 3; ++e) {
                auto a = mesh.indices[t * 3 + std::size_t(e)],
                     b = mesh.indices[t * 3 + std::size_t((e + 1) % 3)];
                ++edges[{std::min(a, b), std::max(a, b)}];
            }
        for (const auto& [edge, count] : edges) {
            if (count == 2)
                continue;
            EXPECT_EQ(count, 1) << "case " << c;
            const glm::vec3 p = mesh.positions[edge.first], q = mesh.positions[edge.second];
            bool sameFace = false;
            for (int axis = 0; axis < 3; ++axis)
                for (float side : {0.0f, 1.0f})
                    sameFace = sameFace || (p[axis] == side && q[axis] == side);
            EXPECT_TRUE(sameFace) << "case " << c << ": open edge crosses the cell";
        }
    }
}

TEST(MarchingCubes, EdgeTableMatchesCornerClassification) {
    for (int c = 0; c < 256; ++c) {
        int expected = 0;
        for (int e = 0; e < 12; ++e)
            if (((c >> kernels::kMcEdgeCorners[e][0]) & 1) !=
                ((c >> kernels::kMcEdgeCorners[e][1]) & 1))
                expected |= 1 << e;
        EXPECT_EQ(int(kernels::kMcEdgeTable[c]), expected) << "case " << c;
    }
}

Volume spherePhantom(glm::ivec3 dims) {
    return volume::makePhantom(dims, volume::PhantomKind::Sphere);
}

TEST(MarchingCubes, SphereIsWatertightAndIdenticalForEveryBrickSize) {
    const Volume v = spherePhantom({45, 38, 41});
    const Mesh whole = extractIsoSurface(v, 0.0);
    ASSERT_GT(whole.triangleCount(), 1000u);
    EXPECT_EQ(closedSurfaceProblem(whole), "");
    for (int cells : {1, 7, 8, 9, 31, 32, 33, 64}) {
        const Mesh chunked = extractIsoSurface(v, 0.0, bricks(cells));
        EXPECT_EQ(closedSurfaceProblem(chunked), "") << "bricks of " << cells;
        expectIdentical(whole, chunked, "bricks of " + std::to_string(cells));
    }
    expectIdentical(whole, extractIsoSurface(v, 0.0, bricks(0, 1)), "one thread");
    expectIdentical(whole, extractIsoSurface(v, 0.0, bricks(5, 3)), "three threads, bricks of 5");
}

// Random values make every ambiguous face configuration appear many times; a zero border keeps
// the surface closed. Any inconsistency between neighbouring cells would show up as a hole.
TEST(MarchingCubes, RandomVolumesAreWatertight) {
    std::mt19937 random(1234);
    std::uniform_int_distribution<int> value(0, 255);
    for (glm::ivec3 dims : {glm::ivec3(13, 11, 9), glm::ivec3(20, 7, 17), glm::ivec3(31, 29, 27)}) {
        Volume v(dims, VoxelType::UInt8);
        auto* data = v.dataAs<std::uint8_t>();
        for (int z = 0; z < dims.z; ++z)
            for (int y = 0; y < dims.y; ++y)
                for (int x = 0; x < dims.x; ++x) {
                    const bool border = x == 0 || y == 0 || z == 0 || x == dims.x - 1 ||
                                        y == dims.y - 1 || z == dims.z - 1;
                    data[v.index(x, y, z)] = border ? 0 : std::uint8_t(value(random));
                }
        // 128 is a stored value itself: ties (value == iso, inside) are exercised too.
        for (double iso : {127.5, 128.0}) {
            const Mesh whole = extractIsoSurface(v, iso);
            ASSERT_GT(whole.triangleCount(), 100u);
            EXPECT_EQ(closedSurfaceProblem(whole), "") << "iso " << iso;
            for (int cells : {1, 2, 3, 5}) {
                const Mesh chunked = extractIsoSurface(v, iso, bricks(cells));
                expectIdentical(whole, chunked, "bricks of " + std::to_string(cells));
            }
        }
    }
}

TEST(MarchingCubes, SphereNormalsPointOutward) {
    const glm::ivec3 dims(40, 40, 40);
    const glm::vec3 centre(19.5f);
    const Volume v = makeFloatVolume(
        dims, [&](int x, int y, int z) { return 12.0 - glm::length(glm::vec3(x, y, z) - centre); });
    const Mesh mesh = extractIsoSurface(v, 0.0, bricks(9));
    ASSERT_GT(mesh.triangleCount(), 1000u);
    for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
        const glm::vec3 radial = glm::normalize(mesh.positions[i] - centre);
        EXPECT_NEAR(glm::length(mesh.normals[i]), 1.0f, 1e-5f);
        ASSERT_GT(glm::dot(mesh.normals[i], radial), 0.99f) << "vertex " << i;
        EXPECT_NEAR(glm::length(mesh.positions[i] - centre), 12.0f, 0.05f);
    }
    // Winding: counter-clockwise seen from outside.
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const glm::vec3 a = mesh.positions[mesh.indices[3 * t]],
                        b = mesh.positions[mesh.indices[3 * t + 1]],
                        c = mesh.positions[mesh.indices[3 * t + 2]];
        const glm::vec3 face = glm::cross(b - a, c - a);
        if (glm::length(face) > 1e-6f) {
            ASSERT_GT(glm::dot(face, (a + b + c) / 3.0f - centre), 0.0f) << "triangle " << t;
        }
    }
}

// A plate one voxel thick (101 at iso 100) with a bright partial-volume layer on one side (60)
// and air on the other, across each axis in turn, and across uneven slices whose offsets run
// backwards. The central differences at the plate voxels point across the plate toward the
// bright layer, and the vertices on the bright side sit at t = 1/41 of their edge: the
// interpolated gradient alone gives them normals pointing into the plate, so every normal of the
// plate faces the same way and no contour can go round it. The edge's own difference must win:
// vertices on either side of the plate face away from it.
class SubVoxelPlate : public ::testing::TestWithParam<int> {};

TEST_P(SubVoxelPlate, NormalsFaceAwayFromThePlateOnBothSides) {
    const int across = GetParam() % 3; // the axis the plate is thin along
    const bool backwardSlices = GetParam() == 3;
    const glm::ivec3 dims(12, 12, 12);
    const int plate = 5;
    auto field = [&](int x, int y, int z) {
        const glm::ivec3 p(x, y, z);
        for (int a = 0; a < 3; ++a)
            if (a != across && (p[a] < 2 || p[a] > 9))
                return 0.0;
        return p[across] == plate ? 101.0 : (p[across] == plate + 1 ? 60.0 : 0.0);
    };
    volume::VolumeGeometry geometry;
    if (backwardSlices) {
        std::vector<glm::dvec3> slices;
        double position = 0.0;
        for (int k = 0; k < dims.z; ++k) {
            slices.push_back({0.0, 0.0, position});
            position -= (k % 2 == 0) ? 1.5 : 0.75;
        }
        geometry =
            volume::VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 1.0, 1.0, slices);
    }
    const Volume v = makeFloatVolume(dims, field, geometry);
    const Mesh mesh = extractIsoSurface(v, 100.0);
    ASSERT_GT(mesh.triangleCount(), 100u);
    EXPECT_EQ(closedSurfaceProblem(mesh), "");
    glm::dvec3 plateIndex(0.0);
    plateIndex[across] = plate;
    const glm::dvec3 platePoint = v.geometry().indexToPatient(plateIndex);
    glm::dvec3 brightIndex(plateIndex);
    brightIndex[across] += 1.0;
    const glm::dvec3 toBright =
        glm::normalize(v.geometry().indexToPatient(brightIndex) - platePoint);
    int checked = 0;
    for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
        const double side = glm::dot(glm::dvec3(mesh.positions[i]) - platePoint, toBright);
        if (std::abs(side) < 1e-4) // the rim: on an edge within the plate's layer
            continue;
        const double facing = glm::dot(glm::dvec3(mesh.normals[i]), toBright);
        ASSERT_GT(side * facing, 0.0) << "vertex " << i << " on side " << side;
        ++checked;
    }
    EXPECT_GT(checked, 100);
}

INSTANTIATE_TEST_SUITE_P(AcrossEachAxis, SubVoxelPlate, ::testing::Values(0, 1, 2, 3));

// A bone plate 3 mm thick, slanted 35 degrees from the slices, in a series of 5 mm slabs with
// 0.5 mm pixels (each slab the mean of the plate across its thickness, as a CT slab is): the
// central difference across slabs spans 10 mm, the plate, the air above it and the brain
// below, so it says little about the surface marching cubes places between two slabs. The
// normals of the plate's upper face must agree with the mesh's own faces there, or n.v turns
// where the mesh does not and its contour falls off the outline (the skull cap of a 5 mm series
// seen from below). The vertices' normals are compared with their faces' area-weighted mean.
TEST(MarchingCubes, ThickSlabNormalsFollowTheMesh) {
    const double slab = 5.0, pixel = 0.5, half = 1.5;
    const double tilt = 35.0 * 3.14159265358979323846 / 180.0;
    const glm::dvec3 plateNormal(std::sin(tilt), 0.0, std::cos(tilt));
    const glm::ivec3 dims(96, 8, 12);
    std::vector<glm::dvec3> slices;
    for (int k = 0; k < dims.z; ++k)
        slices.push_back({0.0, 0.0, slab * k});
    const auto geometry =
        volume::VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, pixel, pixel, slices);
    const glm::dvec3 centre(0.5 * pixel * (dims.x - 1), 0.0, 0.5 * slab * (dims.z - 1));
    auto pointValue = [&](glm::dvec3 p) {
        const double d = glm::dot(p - centre, plateNormal);
        return d > half ? -1000.0 : (d < -half ? 40.0 : 1500.0); // air, bone, brain
    };
    auto slabMean = [&](int x, int y, int z) {
        const int samples = 50;
        double sum = 0.0;
        for (int s = 0; s < samples; ++s) {
            const double dz = slab * ((s + 0.5) / samples - 0.5);
            sum += pointValue({pixel * x, pixel * y, slab * z + dz});
        }
        return sum / samples;
    };
    const Volume v = makeFloatVolume(dims, slabMean, geometry);
    const Mesh mesh = extractIsoSurface(v, 300.0);
    ASSERT_GT(mesh.triangleCount(), 500u);
    // Each vertex's area-weighted mean of its faces' normals (cross products, outward winding).
    std::vector<glm::dvec3> faceSum(mesh.vertexCount(), glm::dvec3(0.0));
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* tri = &mesh.indices[t * 3];
        const glm::dvec3 a(mesh.positions[tri[0]]), b(mesh.positions[tri[1]]),
            c(mesh.positions[tri[2]]);
        const glm::dvec3 area = glm::cross(b - a, c - a);
        for (int e = 0; e < 3; ++e)
            faceSum[tri[e]] += area;
    }
    double sumDot = 0.0;
    int upper = 0, astray = 0;
    for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
        const glm::dvec3 p(mesh.positions[i]);
        const bool interior = p.x > 4.0 && p.x < pixel * (dims.x - 1) - 4.0 && p.z > slab &&
                              p.z < slab * (dims.z - 2);
        if (!interior || glm::dot(p - centre, plateNormal) < 0.0 || glm::length(faceSum[i]) == 0.0)
            continue;
        const double agree = glm::dot(glm::dvec3(mesh.normals[i]), glm::normalize(faceSum[i]));
        sumDot += agree;
        astray += agree < std::cos(25.0 * 3.14159265358979323846 / 180.0);
        ++upper;
    }
    ASSERT_GT(upper, 50);
    // Central differences across the slabs: mean 0.93, 87 of 544 more than 25 degrees astray;
    // the slab edge's own difference: 0.97 and 8.
    EXPECT_GT(sumDot / upper, 0.95);
    EXPECT_LT(astray, upper / 20) << "of " << upper << " vertices of the upper face";
}

// A gantry-tilted stack with uneven slice gaps and anisotropic pixels, sampled from an analytic
// sphere in patient space: vertices must be the index-space vertices mapped through
// indexToPatient, lie on the sphere, and have radial normals (inverse-transpose transform).
TEST(MarchingCubes, TiltedUnevenGeometry) {
    const glm::dvec3 axisI(1, 0, 0), axisJ(0, 1, 0);
    const double spacingI = 0.7, spacingJ = 0.9;
    const double tilt = 25.0 * 3.14159265358979323846 / 180.0;
    std::vector<glm::dvec3> slices;
    double zPos = 0.0;
    for (int k = 0; k < 30; ++k) {
        slices.push_back({0.0, zPos * std::tan(tilt), zPos});
        zPos += (k % 3 == 0) ? 1.6 : 0.8; // uneven gaps
    }
    const auto geometry =
        volume::VolumeGeometry::fromSlicePositions(axisI, axisJ, spacingI, spacingJ, slices);
    ASSERT_TRUE(geometry.isTilted());
    ASSERT_FALSE(geometry.hasUniformSlices());
    const glm::ivec3 dims(44, 60, 30);
    const glm::dvec3 centre = geometry.indexToPatient({21.5, 30.0, 14.5});
    const double radius = 9.0;
    auto field = [&](int x, int y, int z) {
        return radius -
               glm::length(geometry.indexToPatient({double(x), double(y), double(z)}) - centre);
    };
    const Volume tilted = makeFloatVolume(dims, field, geometry);
    const Volume indexSpace = makeFloatVolume(dims, field); // same voxels, identity geometry
    const Mesh mesh = extractIsoSurface(tilted, 0.0, bricks(7));
    const Mesh reference = extractIsoSurface(indexSpace, 0.0);
    ASSERT_GT(mesh.triangleCount(), 1000u);
    ASSERT_EQ(mesh.vertexCount(), reference.vertexCount());
    EXPECT_TRUE(mesh.indices == reference.indices);
    EXPECT_EQ(closedSurfaceProblem(mesh), "");
    double worstPosition = 0.0, sumDot = 0.0, minDot = 1.0;
    for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
        const glm::dvec3 expected = geometry.indexToPatient(glm::dvec3(reference.positions[i]));
        worstPosition =
            std::max(worstPosition, glm::length(glm::dvec3(mesh.positions[i]) - expected));
        const glm::dvec3 radial = glm::normalize(glm::dvec3(mesh.positions[i]) - centre);
        EXPECT_NEAR(glm::length(glm::dvec3(mesh.positions[i]) - centre), radius, 0.15);
        const double d = glm::dot(glm::dvec3(mesh.normals[i]), radial);
        sumDot += d;
        minDot = std::min(minDot, d);
    }
    EXPECT_LT(worstPosition, 1e-4) << "vertices do not follow indexToPatient";
    EXPECT_GT(sumDot / double(mesh.vertexCount()), 0.995);
    EXPECT_GT(minDot, 0.95);
}

TEST(MarchingCubes, IsoIsGivenInRealUnits) {
    Volume stored({12, 12, 12}, VoxelType::UInt16);
    auto* data = stored.dataAs<std::uint16_t>();
    for (int z = 0; z < 12; ++z)
        for (int y = 0; y < 12; ++y)
            for (int x = 0; x < 12; ++x)
                data[stored.index(x, y, z)] =
                    std::uint16_t(100 * (std::abs(x - 6) + std::abs(y - 5) + std::abs(z - 6)));
    const Mesh atStored = extractIsoSurface(stored, 350.0);
    stored.setValueMapping({2.0, -1024.0});
    const Mesh atReal = extractIsoSurface(stored, 350.0 * 2.0 - 1024.0);
    ASSERT_GT(atStored.triangleCount(), 10u);
    expectIdentical(atStored, atReal, "value mapping");
}

// Issue 30: the mesh is counted before it is allocated; over the limit, extraction throws with
// the mesh's size and the limit, and the kernel leaves its output empty.
TEST(MarchingCubes, MeshOverTheLimitIsRefusedBeforeAllocating) {
    const Volume v = spherePhantom({45, 38, 41});
    const Mesh whole = extractIsoSurface(v, 0.0);
    const std::size_t bytes =
        std::size_t(kernels::meshBytes(whole.vertexCount(), whole.triangleCount()));
    IsoSurfaceOptions options;
    options.limits.maxBytes = bytes; // exactly the mesh: made
    expectIdentical(whole, extractIsoSurface(v, 0.0, options), "limit = the mesh's bytes");
    options.limits.maxBytes = bytes - 1;
    for (int cells : {0, 8}) {
        options.brickCells = cells;
        Mesh mesh = whole; // a reused buffer: emptied, not grown
        try {
            extractIsoSurface(v, 0.0, options, mesh);
            ADD_FAILURE() << "a mesh over the limit was made (bricks of " << cells << ")";
        } catch (const core::Error& e) {
            const std::string expected = "the mesh (" + std::to_string(whole.vertexCount()) +
                                         " vertices, " + std::to_string(whole.triangleCount()) +
                                         " triangles) = " + core::byteSizeText(bytes) +
                                         " is more than the limit of " +
                                         core::byteSizeText(bytes - 1) + " (as set)";
            EXPECT_EQ(e.reason(), expected);
        }
        EXPECT_TRUE(mesh.positions.empty() && mesh.indices.empty());
    }
}

// A ball cut by the volume's corner, closed at the border: the cap is counted with the mesh
// against the limit, and marching cubes reserves room for it, so appending it does not
// reallocate (at a 4 GiB volume the old and new positions side by side: hundreds of MiB).
TEST(MarchingCubes, ClosedSurfaceIsCountedWholeAndAppendedInPlace) {
    const Volume v = makeFloatVolume({24, 20, 22}, [](int x, int y, int z) {
        return 14.0f - std::sqrt(float(x * x + y * y + z * z));
    });
    IsoSurfaceOptions options;
    options.closeAtBorder = true;
    const Mesh closed = extractIsoSurface(v, 0.0, options);
    const Mesh open = extractIsoSurface(v, 0.0);
    ASSERT_GT(closed.triangleCount(), open.triangleCount()) << "the corner is capped";
    EXPECT_EQ(closed.positions.capacity(), closed.positions.size());
    EXPECT_EQ(closed.normals.capacity(), closed.normals.size());
    EXPECT_EQ(closed.indices.capacity(), closed.indices.size());

    const std::size_t bytes =
        std::size_t(kernels::meshBytes(closed.vertexCount(), closed.triangleCount()));
    options.limits.maxBytes = bytes;
    expectIdentical(closed, extractIsoSurface(v, 0.0, options), "limit = the closed mesh's bytes");
    options.limits.maxBytes = bytes - 1; // more than the open mesh needs, less than the closed one
    ASSERT_LT(std::size_t(kernels::meshBytes(open.vertexCount(), open.triangleCount())), bytes - 1);
    EXPECT_THROW((void)extractIsoSurface(v, 0.0, options), core::Error);
}

} // namespace
} // namespace lw::render
