// Method 3: accuracy against analytic contours, chunked == whole, visibility, golden images of the
// silhouette and the shaded panel. The renderer-level tests run on every back-end present
// (backends_under_test.h); the rasterizer and brick-surface tests are the CPU kernels'.
#include "backends_under_test.h"
#include "lw/core/image_compare.h"
#include "lw/core/png_io.h"
#include "lw/evaluation/analytic_shapes.h"
#include "lw/evaluation/contour_score.h"
#include "lw/evaluation/true_contour.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"
#include "lw/kernels/marching_cubes_tables.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/zbuffer_silhouette_renderer.h"
#include "lw/volume/bricks.h"
#include "lw/volume/phantom.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>

namespace {

using namespace lw::render;
using namespace lw::evaluation;

Camera cameraFor(const lw::volume::Volume& volume, double az, double el, Projection projection,
                 int size) {
    CameraSetup setup;
    setup.bounds = volumeBounds(volume);
    setup.azimuthDeg = az;
    setup.elevationDeg = el;
    setup.projection = projection;
    return Camera(setup, size, size);
}

SilhouetteSettings settingsFor(double iso, int brickCells = 0, bool visibility = true) {
    SilhouetteSettings settings;
    settings.isoReal = iso;
    settings.brickCells = brickCells;
    settings.visibility = visibility;
    return settings;
}

class ZBufferBackend : public testing::TestWithParam<Backend> {
protected:
    std::unique_ptr<SilhouetteRenderer> make() const {
        return createSilhouetteRenderer(SilhouetteMethod::ZBuffer, GetParam());
    }
};

TEST_P(ZBufferBackend, SphereContourWithinOnePixelOfTruth) {
    const SphereShape sphere;
    const lw::volume::Volume volume = sampleShape(sphere, 64);
    const auto owned = make();
    SilhouetteRenderer& renderer = *owned;
    renderer.setVolume(volume);
    for (const Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        CameraSetup setup;
        setup.bounds = volumeBounds(volume);
        setup.azimuthDeg = 30;
        setup.elevationDeg = 20;
        setup.projection = projection;
        // About two pixels per voxel, as the accuracy measure of the issue prescribes.
        const double voxel = volume.geometry().spacingI();
        const int size = Camera::squareSizeForVoxelCoverage(setup, voxel, 2.0);
        const Camera camera(setup, size, size);
        for (const int bricks : {0, 16}) {
            const SilhouetteFrame frame = renderer.render(camera, settingsFor(kShapeIso, bricks));
            ASSERT_GT(frame.segments, 100u);
            const ContourScore score =
                scoreContours(frame.lines, trueContourMask(sphere, camera), 1);
            EXPECT_GE(score.recall, 0.99)
                << "bricks " << bricks << " ortho " << camera.isOrthographic();
            EXPECT_GE(score.precision, 0.99)
                << "bricks " << bricks << " ortho " << camera.isOrthographic();
        }
    }
}

TEST_P(ZBufferBackend, ChunkedEqualsWholeAndModesAgree) {
    const lw::volume::Volume phantom =
        lw::volume::makePhantom(glm::ivec3(64), lw::volume::PhantomKind::Ct);
    const auto ownedWhole = make(), ownedChunked = make(), ownedEveryFrame = make();
    SilhouetteRenderer &whole = *ownedWhole, &chunked = *ownedChunked,
                       &everyFrame = *ownedEveryFrame;
    whole.setVolume(phantom);
    chunked.setVolume(phantom);
    everyFrame.setVolume(phantom);
    for (const double az : {0.0, 70.0, 200.0}) {
        for (const bool visibility : {true, false}) {
            const Camera camera = cameraFor(phantom, az, 15.0, Projection::Perspective, 256);
            const SilhouetteFrame a =
                whole.render(camera, settingsFor(lw::volume::kPhantomBoneIso, 0, visibility));
            const SilhouetteFrame b =
                chunked.render(camera, settingsFor(lw::volume::kPhantomBoneIso, 16, visibility));
            SilhouetteSettings modeB = settingsFor(lw::volume::kPhantomBoneIso, 8, visibility);
            modeB.mode = ExtractionMode::EveryFrameB;
            modeB.threads = 1;
            const SilhouetteFrame c = everyFrame.render(camera, modeB);
            ASSERT_GT(a.lines.count(), 200u);
            EXPECT_TRUE(a.lines == b.lines) << "az " << az << " visibility " << visibility;
            EXPECT_TRUE(a.lines == c.lines) << "az " << az << " visibility " << visibility;
            EXPECT_EQ(a.triangles, b.triangles);
            EXPECT_EQ(a.segments, b.segments);
            EXPECT_GT(c.times.extractMs, 0.0) << "mode b re-extracts every frame";
        }
    }
    // Mode a: the second frame reuses the mesh.
    const Camera camera = cameraFor(phantom, 10.0, 0.0, Projection::Orthographic, 128);
    EXPECT_EQ(whole.render(camera, settingsFor(lw::volume::kPhantomBoneIso)).times.extractMs, 0.0);
    EXPECT_GT(
        whole.render(camera, settingsFor(lw::volume::kPhantomBoneIso + 100.0)).times.extractMs, 0.0)
        << "a new iso-value must re-extract";
}

// The L variant draws brick by brick from BrickSurfaceExtractor (marching_cubes_cpu.h); its
// triangles must be the whole mesh's, vertex bits included (positions and normals), on a CT phantom
// (integer voxels) and on a tilted stack with uneven gaps (float voxels, every geometry term of the
// vertex expressions).
using TriangleBits = std::array<std::uint32_t, 18>;

TriangleBits triangleBits(const glm::vec3* positions, const glm::vec3* normals,
                          const std::uint32_t* tri) {
    TriangleBits bits{};
    for (int v = 0; v < 3; ++v) {
        std::memcpy(&bits[std::size_t(v) * 6], &positions[tri[v]], sizeof(glm::vec3));
        std::memcpy(&bits[std::size_t(v) * 6 + 3], &normals[tri[v]], sizeof(glm::vec3));
    }
    return bits;
}

void expectBrickSurfacesEqualWholeMesh(const lw::volume::Volume& volume, double isoReal,
                                       int brickCells) {
    const Mesh whole = extractIsoSurface(volume, isoReal);
    std::vector<TriangleBits> expected, actual;
    for (std::size_t t = 0; t < whole.triangleCount(); ++t)
        expected.push_back(triangleBits(whole.positions.data(), whole.normals.data(),
                                        whole.indices.data() + 3 * t));
    const double storedIso = volume.valueMapping().toStored(isoReal);
    const auto grid = lw::volume::BrickGrid::build(volume, glm::ivec3(brickCells));
    const lw::kernels::cpu::BrickSurfaceExtractor extractor(volume, storedIso);
    lw::kernels::cpu::BrickSurface surface;
    for (const int b : grid.activeBricks(storedIso)) {
        extractor.extract(grid.bricks()[std::size_t(b)], surface);
        for (std::size_t t = 0; t < surface.triangleCount(); ++t)
            actual.push_back(triangleBits(surface.positions.data(), surface.normals.data(),
                                          surface.indices.data() + 3 * t));
    }
    ASSERT_GT(expected.size(), 1000u);
    std::sort(expected.begin(), expected.end());
    std::sort(actual.begin(), actual.end());
    EXPECT_TRUE(expected == actual)
        << expected.size() << " whole, " << actual.size() << " from bricks of " << brickCells;
}

TEST(ZBufferSilhouette, BrickSurfacesEqualWholeMesh) {
    const lw::volume::Volume phantom =
        lw::volume::makePhantom(glm::ivec3(64, 56, 48), lw::volume::PhantomKind::Ct);
    for (const int cells : {7, 16, 64})
        expectBrickSurfacesEqualWholeMesh(phantom, lw::volume::kPhantomBoneIso, cells);

    std::vector<glm::dvec3> slices;
    double zPos = 0.0;
    for (int k = 0; k < 30; ++k) {
        slices.push_back({0.3, 0.47 * zPos, zPos - 5.0});
        zPos += (k % 3 == 0) ? 1.6 : 0.8;
    }
    const auto geometry =
        lw::volume::VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 0.7, 0.9, slices);
    const glm::ivec3 dims(44, 60, 30);
    lw::volume::Volume tilted(dims, lw::volume::VoxelType::Float32, geometry);
    const glm::dvec3 centre = geometry.indexToPatient({21.5, 30.0, 14.5});
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                tilted.dataAs<float>()[tilted.index(x, y, z)] = float(
                    11.0 - glm::length(geometry.indexToPatient({double(x), double(y), double(z)}) -
                                       centre));
    for (const int cells : {5, 13})
        expectBrickSurfacesEqualWholeMesh(tilted, 0.0, cells);
}

// The same bits, not merely equal floats; an empty surface (most cube cases) has no data pointer
// to hand to memcmp.
bool bitwiseEqual(const std::vector<glm::vec3>& a, const std::vector<glm::vec3>& b) {
    return a.size() == b.size() &&
           (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) == 0);
}

// A brick covering the whole volume numbers its edges in marchingCubes()'s global order, so its
// surface is the mesh byte for byte, indices included: every cube case (2x2x2 volumes, which
// also exercise the column-based case lookup) and a phantom.
void expectOneBrickSurfaceIsTheMesh(const lw::volume::Volume& volume, double isoReal,
                                    const std::string& what) {
    const Mesh whole = extractIsoSurface(volume, isoReal);
    const double storedIso = volume.valueMapping().toStored(isoReal);
    const auto grid = lw::volume::BrickGrid::build(volume, volume.dims());
    ASSERT_EQ(grid.bricks().size(), 1u) << what;
    const lw::kernels::cpu::BrickSurfaceExtractor extractor(volume, storedIso);
    lw::kernels::cpu::BrickSurface surface;
    extractor.extract(grid.bricks()[0], surface);
    ASSERT_EQ(surface.positions.size(), whole.positions.size()) << what;
    EXPECT_TRUE(bitwiseEqual(surface.positions, whole.positions)) << what;
    EXPECT_TRUE(bitwiseEqual(surface.normals, whole.normals)) << what;
    EXPECT_TRUE(surface.indices == whole.indices) << what;
}

TEST(ZBufferSilhouette, OneBrickSurfaceIsTheWholeMesh) {
    for (int c = 0; c < 256; ++c) {
        lw::volume::Volume cube(glm::ivec3(2), lw::volume::VoxelType::Float32);
        for (int k = 0; k < 8; ++k) {
            const auto* o = lw::kernels::kMcCornerOffset[k];
            cube.dataAs<float>()[cube.index(o[0], o[1], o[2])] = (c >> k) & 1 ? 1.0f : 0.0f;
        }
        expectOneBrickSurfaceIsTheMesh(cube, 0.5, "case " + std::to_string(c));
    }
    const lw::volume::Volume phantom =
        lw::volume::makePhantom(glm::ivec3(40, 36, 32), lw::volume::PhantomKind::Ct);
    expectOneBrickSurfaceIsTheMesh(phantom, lw::volume::kPhantomBoneIso, "phantom");
}

// A big sphere in front of a small one: seen from the front (az 0 looks along +y), the small
// sphere's whole contour lies behind the big one.
class TwoSpheres final : public AnalyticShape {
public:
    std::string name() const override { return "two spheres"; }
    double value(glm::dvec3 p) const override {
        return std::max(m_front.value(p), m_back.value(p));
    }
    glm::dvec3 gradient(glm::dvec3 p) const override {
        return m_front.value(p) >= m_back.value(p) ? m_front.gradient(p) : m_back.gradient(p);
    }
    Aabb bounds() const override { return Aabb::unite(m_front.bounds(), m_back.bounds()); }
    double lipschitz() const override { return 1.0; }

    SphereShape m_front{{0.0, -20.0, 0.0}, 30.0};
    SphereShape m_back{{0.0, 35.0, 0.0}, 12.0};
};

TEST_P(ZBufferBackend, VisibilityHidesContourBehindFrontSphere) {
    const TwoSpheres shape;
    const lw::volume::Volume volume = sampleShape(shape, 64);
    const Camera camera = cameraFor(volume, 0.0, 0.0, Projection::Perspective, 200);
    const auto owned = make();
    SilhouetteRenderer& renderer = *owned;
    renderer.setVolume(volume);
    // Pixels within the back sphere's projected contour (plus 2 px) and well inside the front
    // sphere's disc: only the hidden contour can put lines there.
    const glm::dvec2 centre = camera.project({0.0, 35.0, 0.0}).pixel;
    const double backRadius = glm::distance(camera.project({12.0, 35.0, 0.0}).pixel, centre);
    const double frontRadius = glm::distance(camera.project({30.0, -20.0, 0.0}).pixel, centre);
    ASSERT_LT(backRadius + 4.0, frontRadius - 4.0);
    auto countNearBack = [&](const PixelMask& mask) {
        std::size_t n = 0;
        for (int y = 0; y < mask.height(); ++y)
            for (int x = 0; x < mask.width(); ++x)
                if (mask.get(x, y) &&
                    glm::distance(glm::dvec2(x + 0.5, y + 0.5), centre) < backRadius + 2.0)
                    ++n;
        return n;
    };
    for (const int bricks : {0, 16}) {
        const SilhouetteFrame on = renderer.render(camera, settingsFor(kShapeIso, bricks, true));
        const SilhouetteFrame off = renderer.render(camera, settingsFor(kShapeIso, bricks, false));
        EXPECT_EQ(countNearBack(on.lines), 0u);
        EXPECT_GT(countNearBack(off.lines), std::size_t(4.0 * backRadius))
            << "the back contour, drawn";
        // The front sphere's outline is there either way.
        EXPECT_GT(on.lines.count(), std::size_t(4.0 * frontRadius));
        EXPECT_GT(off.lines.count(), on.lines.count());
    }
}

TEST(ZBufferSilhouette, BackFaceCullingLeavesClosedSurfaceDepthUnchanged) {
    // The renderer culls back faces when the surface does not reach the volume's border; on a
    // closed mesh that must not change a single depth value.
    const TorusShape torus({0, 0, 0}, glm::normalize(glm::dvec3(0.3, -0.5, 1.0)));
    const lw::volume::Volume volume = sampleShape(torus, 56);
    const Mesh mesh = extractIsoSurface(volume, kShapeIso);
    ASSERT_GT(mesh.triangleCount(), 1000u);
    for (const Projection projection : {Projection::Perspective, Projection::Orthographic}) {
        const Camera camera = cameraFor(volume, 40.0, 25.0, projection, 160);
        lw::kernels::cpu::ViewTransform view;
        view.viewProjection = camera.viewProjectionMatrix();
        view.width = camera.width();
        view.height = camera.height();
        view.orthographic = camera.isOrthographic();
        view.eye = camera.eye();
        view.toViewer = -camera.forward();
        lw::kernels::cpu::ScreenVertices screen;
        lw::kernels::cpu::projectVertices(mesh.positions.data(), mesh.normals.data(),
                                          mesh.vertexCount(), view, screen);
        lw::kernels::cpu::DepthBuffer all, culled;
        all.reset(160, 160);
        culled.reset(160, 160);
        lw::kernels::cpu::drawTrianglesDepth(screen, mesh.indices.data(), mesh.triangleCount(), all,
                                             2, false);
        lw::kernels::cpu::drawTrianglesDepth(screen, mesh.indices.data(), mesh.triangleCount(),
                                             culled, 2, true);
        std::size_t covered = 0, differ = 0;
        for (std::size_t i = 0; i < 160u * 160u; ++i) {
            covered += all.bits()[i] != 0;
            differ += all.bits()[i] != culled.bits()[i];
        }
        EXPECT_GT(covered, 2000u);
        EXPECT_EQ(differ, 0u) << "ortho " << camera.isOrthographic();
    }
}

TEST(ZBufferSilhouette, LazyDepthPassIsExactWhereTheColourPassReads) {
    // drawClustersDepth skips clusters and triangles that cannot reach a pixel next to a segment;
    // at those pixels the depth must equal the full pass bit for bit.
    const TorusShape torus({0, 0, 0}, glm::normalize(glm::dvec3(0.6, -0.2, 1.0)));
    const lw::volume::Volume volume = sampleShape(torus, 64);
    const Mesh mesh = extractIsoSurface(volume, kShapeIso);
    const Camera camera = cameraFor(volume, 20.0, 35.0, Projection::Perspective, 200);
    lw::kernels::cpu::ViewTransform view;
    view.viewProjection = camera.viewProjectionMatrix();
    view.width = view.height = 200;
    view.eye = camera.eye();
    view.toViewer = -camera.forward();
    lw::kernels::cpu::ScreenVertices screen;
    lw::kernels::cpu::projectVertices(mesh.positions.data(), mesh.normals.data(),
                                      mesh.vertexCount(), view, screen);
    lw::kernels::cpu::SegmentScratch scratch;
    std::vector<lw::kernels::cpu::ScreenSegment> segments;
    lw::kernels::cpu::findSilhouetteSegments(mesh.positions.data(), screen, mesh.indices.data(),
                                             mesh.triangleCount(), view, scratch, segments);
    lw::kernels::cpu::DepthBuffer lines, full, lazy;
    lines.reset(200, 200);
    full.reset(200, 200);
    lazy.reset(200, 200);
    lw::kernels::cpu::drawSegmentsDepth(segments.data(), segments.size(), lines);
    lw::kernels::cpu::TileMask needed;
    needed.markAroundLines(lines);
    std::vector<lw::kernels::cpu::TriangleCluster> clusters;
    lw::kernels::cpu::buildClusters(mesh.positions.data(), mesh.indices.data(), 0,
                                    std::uint32_t(mesh.triangleCount()), clusters);
    lw::kernels::cpu::drawTrianglesDepth(screen, mesh.indices.data(), mesh.triangleCount(), full);
    lw::kernels::cpu::drawClustersDepth(screen, mesh.indices.data(), clusters.data(),
                                        clusters.size(), view, needed, lazy);
    std::size_t neededPixels = 0, mismatches = 0, skipped = 0;
    for (std::size_t i = 0; i < 200u * 200u; ++i) {
        if (needed.pixels()[i]) {
            ++neededPixels;
            mismatches += full.bits()[i] != lazy.bits()[i];
        } else {
            skipped += full.bits()[i] != 0 && lazy.bits()[i] == 0;
        }
    }
    EXPECT_GT(neededPixels, 500u);
    EXPECT_EQ(mismatches, 0u);
    EXPECT_GT(skipped, 1000u) << "the lazy pass should leave most of the surface undrawn";
}

std::filesystem::path outputDir() {
    const std::filesystem::path dir = std::filesystem::path(LINEWORK_TEST_OUTPUT_DIR) / "zbuffer";
    std::filesystem::create_directories(dir);
    return dir;
}

void expectMatchesBaseline(const lw::core::ImageRgba8& image, const std::string& name,
                           lw::core::ContentTolerance tolerance) {
    const std::filesystem::path baseline =
        std::filesystem::path(LINEWORK_RENDER_BASELINES) / (name + ".png");
    const std::filesystem::path diff = outputDir() / (name + ".diff.png");
    const lw::core::ImageComparison result =
        lw::core::compareWithBaseline(image, baseline, tolerance, diff);
    EXPECT_TRUE(result.matches) << name << ": " << result.describe() << " (diff: " << diff << ")";
}

TEST_P(ZBufferBackend, GoldenPhantomSilhouetteAndShadedPanel) {
    const lw::volume::Volume phantom =
        lw::volume::makePhantom(glm::ivec3(64), lw::volume::PhantomKind::Ct);
    const Camera camera = cameraFor(phantom, 30.0, 20.0, Projection::Perspective, 192);
    const auto owned = make();
    SilhouetteRenderer& renderer = *owned;
    renderer.setVolume(phantom);
    const SilhouetteFrame frame = renderer.render(camera, settingsFor(lw::volume::kPhantomBoneIso));
    // A few pixels may flip where a segment grazes a pixel border (float rounding differs
    // between compilers); a real regression moves hundreds.
    expectMatchesBaseline(frame.lines.toImage({0, 0, 0, 255}, {255, 255, 255, 255}),
                          "zbuffer_phantom64_silhouette", {0, 0.025, 0.5});
    ASSERT_NE(renderer.surfaceMesh(), nullptr);
    expectMatchesBaseline(shadeSurfaceCpu(*renderer.surfaceMesh(), camera),
                          "zbuffer_phantom64_shaded", {6, 0.02, 0.5});
}

TEST(ZBufferSilhouette, ShadedPanelLightsFacingSurfaceBrightest) {
    const SphereShape sphere;
    const lw::volume::Volume volume = sampleShape(sphere, 48);
    const Camera camera = cameraFor(volume, 0.0, 0.0, Projection::Orthographic, 128);
    ZBufferSilhouetteRenderer renderer;
    renderer.setVolume(volume);
    renderer.render(camera, settingsFor(kShapeIso));
    SurfaceShading shading;
    shading.background = {0, 0, 0, 255};
    const lw::core::ImageRgba8 image = shadeSurfaceCpu(renderer.mesh(), camera, shading);
    const glm::dvec2 centre = camera.project({0, 0, 0}).pixel;
    const lw::core::Rgba8 middle = image.at(int(centre.x), int(centre.y));
    const double radius = glm::distance(camera.project({40.0, 0, 0}).pixel, centre);
    const lw::core::Rgba8 rim = image.at(int(centre.x + 0.9 * radius), int(centre.y));
    EXPECT_EQ(image.at(0, 0), (lw::core::Rgba8{0, 0, 0, 255})) << "background";
    EXPECT_GT(int(middle.r), 200) << "head-on: ambient + diffuse + highlight";
    EXPECT_LT(int(rim.r), int(middle.r) - 60) << "grazing light near the rim is darker";
    EXPECT_GT(int(rim.r), 20);
}

INSTANTIATE_TEST_SUITE_P(Backends, ZBufferBackend, testing::ValuesIn(lw::test::backendsUnderTest()),
                         lw::test::backendTestName);

} // namespace

// Found by the accuracy sweep: volumes of the same size bound in turn to one renderer must not
// share the chunked path's brick grid (the second one was culled with the first one's ranges).
TEST(ZBufferSilhouette, AnotherVolumeOfTheSameSizeDropsTheBrickGrid) {
    const lw::volume::Volume ct =
        lw::volume::makePhantom(glm::ivec3(48), lw::volume::PhantomKind::Ct);
    const lw::volume::Volume sphere =
        lw::volume::makePhantom(glm::ivec3(48), lw::volume::PhantomKind::Sphere);
    lw::render::SilhouetteSettings settings;
    settings.isoReal = 0.0;
    settings.brickCells = 8; // small enough that the sphere's bricks miss the skin's
    lw::render::CameraSetup setup;
    setup.bounds = lw::render::volumeBounds(ct);
    const lw::render::Camera camera(setup, 128, 128);

    lw::render::ZBufferSilhouetteRenderer fresh;
    fresh.setVolume(ct);
    const lw::render::PixelMask expected = fresh.render(camera, settings).lines;
    ASSERT_GT(expected.count(), 50u);

    lw::render::ZBufferSilhouetteRenderer reused;
    // The sphere's active bricks hold none of the CT phantom's outer skin.
    reused.setVolume(sphere);
    reused.render(camera, settings);
    reused.setVolume(ct);
    EXPECT_EQ(reused.render(camera, settings).lines, expected);
}
