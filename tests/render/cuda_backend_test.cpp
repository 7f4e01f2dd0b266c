// The CUDA back-end against the CPU reference (label gpu: runs only where a CUDA device is
// present, SKIP elsewhere). Marching cubes must give the CPU's triangles in the CPU's order with
// the same vertices; method 3 must give the CPU's image. The volumes cover every voxel type, sizes
// that are not multiples of the 256-voxel classification tile or the 16-cell skip brick, a
// gantry-tilted stack with uneven gaps, and surfaces cut open by the volume's border.

#include "filled_volume.h"
#include "lw/core/error.h"
#include "lw/evaluation/analytic_shapes.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cpu/voxel_ray.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/cuda/raycast_silhouette_cuda.h"
#include "lw/kernels/cuda/stroke_pruning_cuda.h"
#include "lw/render/gpu_memory_plan.h"
#include "lw/render/iso_surface.h"
#include "lw/render/pixel_mask.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/zbuffer_silhouette_renderer.h"
#include "lw/volume/phantom.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <gtest/gtest.h>
#include <random>
#include <string>

namespace lw::render {
namespace {

using volume::Volume;
using volume::VoxelType;

struct Case {
    std::string name;
    std::function<Volume()> make;
    double iso;
};

Volume tiltedSphere() {
    const double tilt = 25.0 * 3.14159265358979323846 / 180.0;
    std::vector<glm::dvec3> slices;
    double zPos = 0.0;
    for (int k = 0; k < 37; ++k) {
        slices.push_back({0.0, zPos * std::tan(tilt), zPos});
        zPos += (k % 3 == 0) ? 1.6 : 0.8;
    }
    const auto geometry =
        volume::VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 0.7, 0.9, slices);
    const glm::dvec3 centre = geometry.indexToPatient({21.5, 30.0, 18.0});
    return lw::test::makeFilledVolume<float>(
        {45, 61, 37},
        [&](int x, int y, int z) {
            return 11.0 -
                   glm::length(geometry.indexToPatient({double(x), double(y), double(z)}) - centre);
        },
        geometry);
}

Volume noise(glm::ivec3 dims, VoxelType type, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> value(0, 200);
    return volume::dispatchVoxelType(type, [&](auto zero) {
        using T = decltype(zero);
        return lw::test::makeFilledVolume<T>(dims, [&](int, int, int) { return value(random); });
    });
}

std::vector<Case> cases() {
    return {
        {"phantom 64^3 int16",
         [] {
             return volume::makePhantom({64, 64, 64}, volume::PhantomKind::Ct);
         },
         300.5},
        {"phantom 100x67x45 int16 (odd sizes)",
         [] {
             return volume::makePhantom({100, 67, 45}, volume::PhantomKind::Ct);
         },
         300.5},
        {"phantom soft tissue",
         [] {
             return volume::makePhantom({96, 80, 70}, volume::PhantomKind::Ct);
         },
         -500.0},
        {"sphere 33^3",
         [] {
             return volume::makePhantom({33, 33, 33}, volume::PhantomKind::Sphere);
         },
         300.5},
        {"tilted uneven float", tiltedSphere, 0.0},
        {"noise uint8 (open at the border)",
         [] {
             return noise({40, 23, 19}, VoxelType::UInt8, 1);
         },
         100.0},
        {"noise uint16 17x16x257 (brick boundaries)",
         [] {
             return noise({17, 16, 257}, VoxelType::UInt16, 2);
         },
         120.0},
        {"noise int16 fractional iso",
         [] {
             return noise({31, 29, 18}, VoxelType::Int16, 3);
         },
         99.5},
    };
}

class CudaBackend : public testing::TestWithParam<Case> {};

std::string caseName(const testing::TestParamInfo<Case>& info) {
    std::string name;
    for (char c : info.param.name)
        name += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return name;
}

// The extraction's mesh, downloaded.
Mesh downloadedMesh(kernels::cuda::MarchingCubesCuda& cuda) {
    Mesh mesh;
    const auto downloaded = cuda.download(mesh.positions, mesh.normals, mesh.indices);
    EXPECT_TRUE(downloaded.ok()) << downloaded.describe();
    return mesh;
}

// The CPU's triangles in the CPU's order, the vertices the same bits.
void expectCpuMesh(const Mesh& mesh, const Mesh& reference, const std::string& where) {
    ASSERT_EQ(mesh.vertexCount(), reference.vertexCount()) << where;
    ASSERT_EQ(mesh.triangleCount(), reference.triangleCount()) << where;
    EXPECT_TRUE(mesh.indices == reference.indices)
        << where << ": triangles in another order or wired differently";
    double worstPosition = 0.0, worstNormal = 0.0;
    std::size_t identical = 0;
    for (std::size_t i = 0; i < mesh.vertexCount(); ++i) {
        worstPosition = std::max(worstPosition,
                                 double(glm::length(mesh.positions[i] - reference.positions[i])));
        worstNormal =
            std::max(worstNormal, double(glm::length(mesh.normals[i] - reference.normals[i])));
        identical +=
            std::memcmp(&mesh.positions[i], &reference.positions[i], sizeof(glm::vec3)) == 0 &&
            std::memcmp(&mesh.normals[i], &reference.normals[i], sizeof(glm::vec3)) == 0;
    }
    EXPECT_LE(worstPosition, 1e-4) << where << " (mm)";
    EXPECT_LE(worstNormal, 1e-5) << where;
    // Shared expressions and no FMA contraction: the vertices are the same bits.
    EXPECT_EQ(identical, mesh.vertexCount()) << where << ": worst position difference "
                                             << worstPosition << " mm, normal " << worstNormal;
}

void upload(kernels::cuda::MarchingCubesCuda& cuda, const Volume& volume) {
    kernels::VolumeView view;
    view.voxels = volume.data();
    view.kind = kernels::VoxelKind(volume.voxelType());
    view.dims = volume.dims();
    const auto status = cuda.setVolume(view, kernels::cpu::voxelGridSetup(volume));
    ASSERT_TRUE(status.ok()) << status.describe();
}

TEST_P(CudaBackend, MarchingCubesGivesTheCpuTrianglesInTheCpuOrder) {
    const Volume volume = GetParam().make();
    const Mesh reference = extractIsoSurface(volume, GetParam().iso);
    ASSERT_GT(reference.triangleCount(), 0u) << "the case must have a surface";
    kernels::cuda::MarchingCubesCuda cuda;
    ASSERT_NO_FATAL_FAILURE(upload(cuda, volume));
    const auto extracted = cuda.extract(storedIsoValue(volume, GetParam().iso));
    ASSERT_TRUE(extracted.ok()) << extracted.describe();
    expectCpuMesh(downloadedMesh(cuda), reference, "first extraction");

    // A second extraction at another iso-value reuses the buffers and still agrees.
    const double other = GetParam().iso + 1.0;
    const Mesh reference2 = extractIsoSurface(volume, other);
    ASSERT_TRUE(cuda.extract(storedIsoValue(volume, other)).ok());
    expectCpuMesh(downloadedMesh(cuda), reference2, "second extraction");
}

// After a small surface the active list is too short for a large one: the extraction finds out
// from the totals and writes the list again (marching_cubes_cuda.cu, offsetsOfActiveList).
TEST_P(CudaBackend, AGrowingSurfaceWritesTheActiveListAgain) {
    const Volume volume = GetParam().make();
    const Mesh reference = extractIsoSurface(volume, GetParam().iso);
    const volume::ValueRange range = volume.realRange();
    double smallIso = GetParam().iso;
    for (double share : {0.98, 0.95, 0.9, 0.8, 0.7, 0.6}) {
        const double iso = range.min + share * (range.max - range.min);
        const std::size_t triangles = extractIsoSurface(volume, iso).triangleCount();
        if (triangles > 0 && 4 * triangles < reference.triangleCount()) {
            smallIso = iso;
            break;
        }
    }
    if (smallIso == GetParam().iso) // the sphere: two values, one surface for every iso-value
        GTEST_SKIP() << "no iso-value of this volume has a much smaller surface";
    kernels::cuda::MarchingCubesCuda cuda;
    ASSERT_NO_FATAL_FAILURE(upload(cuda, volume));
    ASSERT_TRUE(cuda.extract(storedIsoValue(volume, smallIso)).ok());
    expectCpuMesh(downloadedMesh(cuda), extractIsoSurface(volume, smallIso), "small surface");
    ASSERT_TRUE(cuda.extract(storedIsoValue(volume, GetParam().iso)).ok());
    expectCpuMesh(downloadedMesh(cuda), reference, "large surface after the small one");
}

Camera cameraAt(const Aabb& bounds, double az, double el, Projection projection, int width,
                int height) {
    CameraSetup setup;
    setup.bounds = bounds;
    setup.azimuthDeg = az;
    setup.elevationDeg = el;
    setup.projection = projection;
    return Camera(setup, width, height);
}

// Share of the pixels set in either image that are set in both.
double agreement(const PixelMask& a, const PixelMask& b, std::size_t& differing) {
    std::size_t either = 0, both = 0;
    differing = 0;
    for (std::size_t i = 0; i < a.pixels().size(); ++i) {
        either += a.pixels()[i] || b.pixels()[i];
        both += a.pixels()[i] && b.pixels()[i];
        differing += a.pixels()[i] != b.pixels()[i];
    }
    return either == 0 ? 1.0 : double(both) / double(either);
}

// The CUDA frame against the CPU's: the same counts and (the issue asks >= 99.5 %) the same pixels;
// the shared rules give all of them.
void expectSameFrame(const SilhouetteFrame& frame, const SilhouetteFrame& expected,
                     const std::string& where) {
    EXPECT_EQ(frame.triangles, expected.triangles) << where;
    EXPECT_EQ(frame.segments, expected.segments) << where;
    ASSERT_GT(expected.lines.count(), 0u) << where << ": an empty image tests nothing";
    std::size_t differing = 0;
    const double share = agreement(frame.lines, expected.lines, differing);
    EXPECT_GE(share, 0.995) << where;
    EXPECT_EQ(differing, 0u) << where << ": the same rules should give the same pixels";
}

TEST_P(CudaBackend, Method3GivesTheCpuImage) {
    const Volume volume = GetParam().make();
    auto cuda = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cuda);
    ASSERT_EQ(cuda->backendName(), "cuda");
    ZBufferSilhouetteRenderer cpu;
    cuda->setVolume(volume);
    cpu.setVolume(volume);
    const Aabb bounds = volumeBounds(volume);
    struct View {
        double az, el;
        Projection projection;
        bool visibility;
        int width, height;
    };
    const View views[] = {{30, 20, Projection::Perspective, true, 256, 256},
                          {75, 70, Projection::Perspective, true, 301, 173},
                          {200, -35, Projection::Orthographic, true, 256, 200},
                          {120, 10, Projection::Perspective, false, 256, 256}};
    for (const View& v : views) {
        const Camera camera = cameraAt(bounds, v.az, v.el, v.projection, v.width, v.height);
        for (const ExtractionMode mode : {ExtractionMode::EveryFrameB, ExtractionMode::CachedA}) {
            SilhouetteSettings settings;
            settings.isoReal = GetParam().iso;
            settings.visibility = v.visibility;
            settings.mode = mode;
            const SilhouetteFrame expected = cpu.render(camera, settings);
            const SilhouetteFrame frame = cuda->render(camera, settings);
            const std::string where = "view az " + std::to_string(v.az) + " el " +
                                      std::to_string(v.el) + (v.visibility ? "" : " no visibility");
            expectSameFrame(frame, expected, where);
        }
    }
    // The chunked variant streams slabs (7 cell layers each, so every case has several seams)
    // through the device: still the CPU's image (ZBufferSilhouetteRenderer's L equals its S).
    auto streamed = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cuda);
    streamed->setVolume(volume);
    const Camera camera = cameraAt(bounds, 40, 25, Projection::Perspective, 256, 256);
    SilhouetteSettings settings;
    settings.isoReal = GetParam().iso;
    settings.brickCells = 8;
    settings.gpuSlabLayers = 7;
    const SilhouetteFrame chunked = streamed->render(camera, settings);
    EXPECT_EQ(streamed->backendName(), "cuda");
    settings.brickCells = 0;
    const SilhouetteFrame expected = cpu.render(camera, settings);
    std::size_t differing = 0;
    agreement(chunked.lines, expected.lines, differing);
    EXPECT_EQ(differing, 0u) << "slabs of 7 cell layers";
    EXPECT_EQ(chunked.segments, expected.segments);
    EXPECT_GT(chunked.deviceBytes, 0u);

    // The shaded panel's mesh comes from the device and is the CPU's, closed at the border as
    // the frame was drawn (SilhouetteSettings::closeAtBorder, on by default).
    const Mesh* mesh = cuda->surfaceMesh();
    ASSERT_NE(mesh, nullptr);
    IsoSurfaceOptions closed;
    closed.closeAtBorder = true;
    const Mesh reference = extractIsoSurface(volume, GetParam().iso, closed);
    EXPECT_EQ(mesh->triangleCount(), reference.triangleCount());
    EXPECT_EQ(mesh->positions, reference.positions);
}

TEST_P(CudaBackend, Method2GivesTheCpuImage) {
    const Volume volume = GetParam().make();
    auto cuda = createSilhouetteRenderer(SilhouetteMethod::RayCastVisibility, Backend::Cuda);
    ASSERT_EQ(cuda->backendName(), "cuda");
    auto cpu = createSilhouetteRenderer(SilhouetteMethod::RayCastVisibility, Backend::Cpu);
    cuda->setVolume(volume);
    cpu->setVolume(volume);
    const Aabb bounds = volumeBounds(volume);
    struct View {
        double az, el;
        Projection projection;
        bool visibility, along;
    };
    const View views[] = {{30, 20, Projection::Perspective, true, false},
                          {75, 70, Projection::Perspective, true, true},
                          {200, -35, Projection::Orthographic, true, false},
                          {120, 10, Projection::Perspective, false, false}};
    for (const View& v : views) {
        const Camera camera = cameraAt(bounds, v.az, v.el, v.projection, 256, 224);
        for (const ExtractionMode mode : {ExtractionMode::CachedA, ExtractionMode::EveryFrameB}) {
            SilhouetteSettings settings;
            settings.isoReal = GetParam().iso;
            settings.visibility = v.visibility;
            settings.testAlongSegment = v.along;
            settings.mode = mode;
            const SilhouetteFrame expected = cpu->render(camera, settings);
            const SilhouetteFrame frame = cuda->render(camera, settings);
            const std::string where =
                "view az " + std::to_string(v.az) + " el " + std::to_string(v.el) +
                (v.visibility ? "" : " no visibility") + (v.along ? " along segments" : "");
            expectSameFrame(frame, expected, where);
        }
    }
    // Other iso-values on the same volume: the macro cells' occupancy comes from maxima found
    // once per volume, and must still say which cells hold an inside voxel at each of them.
    const Camera camera = cameraAt(bounds, 30, 20, Projection::Perspective, 256, 224);
    const volume::ValueRange range = volume.realRange();
    for (double share : {0.3, 0.7}) {
        SilhouetteSettings settings;
        settings.isoReal = range.min + share * (range.max - range.min);
        expectSameFrame(cuda->render(camera, settings), cpu->render(camera, settings),
                        "iso " + std::to_string(settings.isoReal));
    }
    // The chunked variant reads the volume mapped from host memory: the same kernels, the same
    // image, still on the device.
    SilhouetteSettings settings;
    settings.isoReal = GetParam().iso;
    const SilhouetteFrame expected = cpu->render(camera, settings);
    settings.brickCells = 8;
    const SilhouetteFrame mapped = cuda->render(camera, settings);
    EXPECT_EQ(cuda->backendName(), "cuda");
    expectSameFrame(mapped, expected, "L, the volume mapped from host memory");
}

// Method 2's phase 1 from the cells' mesh kept on the device (the default), from the voxels
// (what a device without room for the mesh does) and from slabs of 7 cell layers (how a volume of
// more than 2^32 voxels goes, its rays reading host memory): the same segments, the same image,
// for the resident and the mapped volume, at two iso-values.
TEST_P(CudaBackend, Method2SegmentsFromMeshVoxelsAndSlabsAgree) {
    const Volume volume = GetParam().make();
    kernels::VolumeView view;
    view.voxels = volume.data();
    view.kind = kernels::VoxelKind(volume.voxelType());
    view.dims = volume.dims();
    const kernels::cpu::VoxelRayGrid grid(volume);
    kernels::cuda::RayGridSetup rays;
    rays.offsets = grid.offsets();
    rays.view = grid.view();
    rays.cellScale = grid.cellScale();
    rays.neighbourReach = grid.neighbourReach();
    const Camera camera = cameraAt(volumeBounds(volume), 40, 25, Projection::Perspective, 200, 180);
    kernels::PixelCamera pixels;
    pixels.eye = camera.eye();
    pixels.right = camera.right();
    pixels.up = camera.up();
    pixels.forward = camera.forward();
    pixels.halfWidth = camera.halfWidth();
    pixels.halfHeight = camera.halfHeight();
    pixels.width = camera.width();
    pixels.height = camera.height();
    const volume::ValueRange range = volume.realRange();
    enum Way { KeptMesh, Voxels, Slabs };
    const char* names[] = {"kept mesh", "voxels", "slabs"};
    for (const bool mapped : {false, true})
        for (const double iso : {GetParam().iso, range.min + 0.6 * (range.max - range.min)}) {
            std::vector<std::uint8_t> masks[3];
            std::size_t segments[3] = {0, 0, 0};
            for (const Way way : {KeptMesh, Voxels, Slabs}) {
                kernels::cuda::RayCastSilhouetteCuda cuda;
                cuda.setSlabLayers(way == Slabs ? 7 : 0);
                ASSERT_TRUE(
                    cuda.setVolume(view, kernels::cpu::voxelGridSetup(volume), rays, mapped).ok());
                cuda.setKeepCellMesh(way == KeptMesh);
                kernels::cuda::RayCastCudaFrame frame;
                ASSERT_TRUE(cuda.prepare(storedIsoValue(volume, iso), frame).ok());
                masks[way].assign(std::size_t(camera.width()) * camera.height(), 0);
                const auto status =
                    cuda.render(pixels, camera.eye(), false, kernels::cuda::RayCastCudaSettings{},
                                masks[way].data(), frame);
                ASSERT_TRUE(status.ok()) << names[way] << ": " << status.describe();
                segments[way] = frame.segments;
            }
            const std::string where =
                std::string(mapped ? "mapped" : "resident") + ", iso " + std::to_string(iso);
            for (const Way way : {Voxels, Slabs}) {
                EXPECT_EQ(segments[way], segments[KeptMesh]) << names[way] << ", " << where;
                EXPECT_EQ(masks[way], masks[KeptMesh]) << names[way] << ", " << where;
            }
            EXPECT_GT(std::count(masks[0].begin(), masks[0].end(), std::uint8_t(1)), 0) << where;
        }
}

// The smoothed gradient stencil (voxel_grid.h) on the device: the CPU's normals bit for bit, for
// the whole volume and for streamed slabs (whose boxes must hold the stencil's diagonal
// neighbours), and the CPU's images of methods 3 and 2 drawn from them.
TEST_P(CudaBackend, SmoothedStencilGivesTheCpuNormalsAndImages) {
    const Volume volume = GetParam().make();
    IsoSurfaceOptions smoothed;
    smoothed.gradientStencil = GradientStencil::Smoothed;
    const Mesh reference = extractIsoSurface(volume, GetParam().iso, smoothed);
    ASSERT_NE(reference.normals, extractIsoSurface(volume, GetParam().iso).normals)
        << "the stencil should change the normals";

    kernels::VolumeView view;
    view.voxels = volume.data();
    view.kind = kernels::VoxelKind(volume.voxelType());
    view.dims = volume.dims();
    kernels::cuda::MarchingCubesCuda cuda;
    ASSERT_TRUE(cuda.setVolume(view, kernels::cpu::voxelGridSetup(volume)).ok());
    cuda.setGradientStencil(GradientStencil::Smoothed);
    ASSERT_TRUE(cuda.extract(storedIsoValue(volume, GetParam().iso)).ok());
    Mesh mesh;
    ASSERT_TRUE(cuda.download(mesh.positions, mesh.normals, mesh.indices).ok());
    EXPECT_EQ(mesh.indices, reference.indices);
    EXPECT_EQ(mesh.positions, reference.positions);
    EXPECT_EQ(mesh.normals, reference.normals) << "smoothed normals differ from the CPU's";

    const Aabb bounds = volumeBounds(volume);
    const Camera camera = cameraAt(bounds, 40, 25, Projection::Perspective, 256, 224);
    SilhouetteSettings settings;
    settings.isoReal = GetParam().iso;
    settings.gradientStencil = GradientStencil::Smoothed;
    for (const SilhouetteMethod method :
         {SilhouetteMethod::ZBuffer, SilhouetteMethod::RayCastVisibility}) {
        auto onDevice = createSilhouetteRenderer(method, Backend::Cuda);
        auto onHost = createSilhouetteRenderer(method, Backend::Cpu);
        onDevice->setVolume(volume);
        onHost->setVolume(volume);
        const std::string where = "method " + std::to_string(int(method)) + ", smoothed";
        settings.brickCells = 0;
        const SilhouetteFrame expected = onHost->render(camera, settings);
        expectSameFrame(onDevice->render(camera, settings), expected, where);
        // L: method 3 streams slabs of 5 cell layers, method 2 reads the volume mapped.
        settings.brickCells = 8;
        settings.gpuSlabLayers = 5;
        const SilhouetteFrame chunked = onDevice->render(camera, settings);
        std::size_t differing = 0;
        agreement(chunked.lines, expected.lines, differing);
        EXPECT_EQ(differing, 0u) << where << ", chunked";
        EXPECT_EQ(chunked.segments, expected.segments) << where << ", chunked";
        settings.gpuSlabLayers = 0;
    }
}

INSTANTIATE_TEST_SUITE_P(Volumes, CudaBackend, testing::ValuesIn(cases()), caseName);

// One method's frame of the 512 x 512 x 1024 CT phantom (512 MiB of voxels) with the whole volume
// resident, and the same frame under a 256 MiB budget (a renderer of its own).
constexpr std::size_t kStreamingBudget = std::size_t(256) << 20;

struct FramesUnderBudget {
    SilhouetteFrame resident, underBudget;
    std::string backend; // of the renderer under the budget
};

FramesUnderBudget framesUnderBudget(SilhouetteMethod method) {
    const Volume volume = volume::makePhantom({512, 512, 1024}, volume::PhantomKind::Ct);
    auto whole = createSilhouetteRenderer(method, Backend::Cuda);
    auto budgeted = createSilhouetteRenderer(method, Backend::Cuda);
    whole->setVolume(volume);
    budgeted->setVolume(volume);
    const Camera camera =
        cameraAt(volumeBounds(volume), 30, 20, Projection::Perspective, 1024, 1024);
    SilhouetteSettings settings;
    settings.isoReal = 300.5;
    FramesUnderBudget frames;
    frames.resident = whole->render(camera, settings);
    settings.gpuMemoryBudget = kStreamingBudget;
    frames.underBudget = budgeted->render(camera, settings);
    frames.backend = std::string(budgeted->backendName());
    return frames;
}

// Method 2 over the budget: the rays need the whole volume, so it stays in host memory, mapped.
TEST(CudaBackendStreaming, Method2OverTheBudgetReadsTheVolumeFromHostMemory) {
    const FramesUnderBudget frames = framesUnderBudget(SilhouetteMethod::RayCastVisibility);
    const SilhouetteFrame& expected = frames.resident;
    const SilhouetteFrame& frame = frames.underBudget;
    ASSERT_GT(expected.lines.count(), 1000u);
    EXPECT_EQ(frames.backend, "cuda");
    expectSameFrame(frame, expected, "512 x 512 x 1024 under 256 MiB");
}

// The GPU-run goal's case: a 512 x 512 x 1024 CT phantom (512 MiB of voxels) under a 256 MiB
// budget streams in slabs and gives the image of the resident whole volume.
TEST(CudaBackendStreaming, VolumeLargerThanTheBudgetGivesTheSameImage) {
    const FramesUnderBudget frames = framesUnderBudget(SilhouetteMethod::ZBuffer);
    const SilhouetteFrame& expected = frames.resident;
    const SilhouetteFrame& frame = frames.underBudget;
    ASSERT_GT(expected.lines.count(), 1000u);
    std::size_t differing = 0;
    agreement(frame.lines, expected.lines, differing);
    EXPECT_EQ(differing, 0u);
    EXPECT_EQ(frame.segments, expected.segments);
    EXPECT_EQ(frame.triangles, expected.triangles);
    EXPECT_LE(frame.deviceBytes, kStreamingBudget)
        << "held " << (frame.deviceBytes >> 20) << " MiB";
    std::printf("512x512x1024 under 256 MiB: %zu MiB held at the most, whole volume %zu MiB\n",
                frame.deviceBytes >> 20, expected.deviceBytes >> 20);
}

// A streamed (L) frame keeps its slabs' meshes on the device while the budget holds them, and a
// new view of the same surface draws the kept ones and streams only the rest. Every view, and the
// frame after the iso-value changed (the kept meshes go), is the resident whole volume's image:
// with every slab kept (no budget) and with the first ones kept (a budget that holds a few).
TEST(CudaBackendStreaming, KeptSlabMeshesDrawTheResidentImageAtEveryView) {
    const Volume volume = volume::makePhantom({256, 256, 300}, volume::PhantomKind::Ct);
    auto whole = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cuda);
    whole->setVolume(volume);
    struct Step {
        double azimuth, elevation, iso;
        ExtractionMode mode = ExtractionMode::CachedA;
    };
    // Mode b extracts every frame and keeps nothing; the mode a frame after it keeps again.
    const Step steps[] = {{30, 20, 300.5},
                          {75, -10, 300.5},
                          {200, 40, 300.5, ExtractionMode::EveryFrameB},
                          {250, 30, 300.5},
                          {120, 15, 900.5}};
    for (const std::size_t budget : {std::size_t(0), std::size_t(24) << 20}) {
        auto streamed = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cuda);
        streamed->setVolume(volume);
        for (const Step& step : steps) {
            const Camera camera = cameraAt(volumeBounds(volume), step.azimuth, step.elevation,
                                           Projection::Perspective, 512, 512);
            SilhouetteSettings settings;
            settings.isoReal = step.iso;
            const SilhouetteFrame expected = whole->render(camera, settings);
            settings.brickCells = 8;
            settings.gpuSlabLayers = 9;
            settings.gpuMemoryBudget = budget;
            settings.mode = step.mode;
            const SilhouetteFrame frame = streamed->render(camera, settings);
            const std::string where = "budget " + std::to_string(budget >> 20) + " MiB, view " +
                                      std::to_string(int(step.azimuth)) + ", iso " +
                                      std::to_string(int(step.iso));
            ASSERT_EQ(streamed->backendName(), "cuda") << where;
            ASSERT_GT(expected.lines.count(), 500u) << where;
            std::size_t differing = 0;
            agreement(frame.lines, expected.lines, differing);
            EXPECT_EQ(differing, 0u) << where;
            EXPECT_EQ(frame.segments, expected.segments) << where;
            EXPECT_EQ(frame.triangles, expected.triangles) << where;
            if (budget > 0) {
                EXPECT_LE(frame.deviceBytes, budget) << where;
            } else if (step.mode ==
                       ExtractionMode::CachedA) { // the whole surface kept: its indices
                EXPECT_GT(frame.deviceBytes, frame.triangles * 3 * sizeof(std::uint32_t)) << where;
            }
        }
    }
}

// Method 1 with the CUDA extraction writing the GL buffers (interop) draws exactly what it draws
// from the CPU's mesh: same triangles, same segments, same pixels.
TEST(CudaBackendMethod1, CudaExtractionDrawsTheCpuImage) {
    std::unique_ptr<SilhouetteRenderer> cpu, cuda;
    try {
        cpu = createSilhouetteRenderer(SilhouetteMethod::GeometryShader, Backend::Cpu);
        cuda = createSilhouetteRenderer(SilhouetteMethod::GeometryShader, Backend::Cuda);
    } catch (const core::Error& error) {
        GTEST_SKIP() << "no OpenGL for method 1: " << error.what();
    }
    ASSERT_EQ(cuda->backendName(), "cuda+gl");
    const Volume volume = volume::makePhantom({128, 120, 96}, volume::PhantomKind::Ct);
    cpu->setVolume(volume);
    cuda->setVolume(volume);
    const Camera camera = cameraAt(volumeBounds(volume), 30, 20, Projection::Perspective, 512, 512);
    for (const ExtractionMode mode : {ExtractionMode::EveryFrameB, ExtractionMode::CachedA}) {
        SilhouetteSettings settings;
        settings.isoReal = 300.5;
        settings.mode = mode;
        const SilhouetteFrame expected = cpu->render(camera, settings);
        const SilhouetteFrame frame = cuda->render(camera, settings);
        ASSERT_GT(expected.lines.count(), 500u);
        EXPECT_EQ(frame.triangles, expected.triangles);
        EXPECT_EQ(frame.segments, expected.segments);
        std::size_t differing = 0;
        agreement(frame.lines, expected.lines, differing);
        EXPECT_EQ(differing, 0u);
    }
    // The iso panel's mesh, downloaded on demand, is the CPU's.
    ASSERT_NE(cuda->surfaceMesh(), nullptr);
    EXPECT_EQ(cuda->surfaceMesh()->triangleCount(), cpu->surfaceMesh()->triangleCount());
    // The chunked (L) variant streams slabs of 7 cell layers through the device into the GL
    // buffers: still the CPU's whole-volume image.
    SilhouetteSettings chunked;
    chunked.isoReal = 300.5;
    chunked.brickCells = 16;
    chunked.gpuSlabLayers = 7;
    const SilhouetteFrame streamed = cuda->render(camera, chunked);
    EXPECT_EQ(cuda->backendName(), "cuda+gl");
    SilhouetteSettings whole = chunked;
    whole.brickCells = 0;
    const SilhouetteFrame expected = cpu->render(camera, whole);
    std::size_t differing = 0;
    agreement(streamed.lines, expected.lines, differing);
    EXPECT_EQ(differing, 0u) << "method 1 L streamed on the GPU";
    EXPECT_EQ(streamed.triangles, expected.triangles);

    // The mask thresholded by GL's compute shader, read back and pruned on the CUDA device
    // against the CPU back-end's, pruned on the host, at a new size that is no multiple of the
    // kernels' blocks nor of the mask shader's four pixels a word. Noise at a low iso-value
    // gives many small blobs, so strokes of every length.
    const Volume blobs = noise({48, 40, 36}, VoxelType::UInt8, 5);
    cpu->setVolume(blobs);
    cuda->setVolume(blobs);
    const Camera odd = cameraAt(volumeBounds(blobs), 60, -25, Projection::Perspective, 509, 383);
    SilhouetteSettings pruned;
    pruned.isoReal = 150.0;
    const std::size_t unpruned = cpu->render(odd, pruned).lines.count();
    pruned.minStrokePixels = 40;
    const SilhouetteFrame hostPruned = cpu->render(odd, pruned);
    const SilhouetteFrame devicePruned = cuda->render(odd, pruned);
    ASSERT_LT(hostPruned.lines.count(), unpruned) << "nothing to prune tests nothing";
    ASSERT_GT(hostPruned.lines.count(), 0u) << "nothing left tests nothing";
    EXPECT_TRUE(devicePruned.strokesPruned);
    agreement(devicePruned.lines, hostPruned.lines, differing);
    EXPECT_EQ(differing, 0u) << "pruned on the device";
}

// The device memory budget is a limit: a frame that would hold more falls back (whole volume ->
// slabs -> CPU) and still gives the CPU's image; where it stays on the GPU it holds no more than
// the budget.
struct BudgetCase {
    std::string name;
    std::function<Volume()> make;
    double iso;
    std::size_t budget; // 0: just above the whole-volume estimate for a 256 x 256 image
};

class CudaBudget : public testing::TestWithParam<BudgetCase> {};

TEST_P(CudaBudget, OverTheBudgetFallsBackAndKeepsTheImage) {
    const Volume volume = GetParam().make();
    const Camera camera = cameraAt(volumeBounds(volume), 35, 25, Projection::Perspective, 256, 256);
    std::size_t budget = GetParam().budget;
    if (budget == 0) {
        // The residency plan picks the whole volume (its estimate fits), but a noisy surface's
        // mesh is far larger than the estimate: the frame runs over and must fall back.
        const double voxels = double(volume.dims().x) * volume.dims().y * volume.dims().z *
                              double(volume::voxelSize(volume.voxelType()));
        budget = std::size_t(voxels * (1.0 + kWholeVolumeOverhead)) + 256 * 256 * 9 + 4096;
    }
    auto cuda = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cuda);
    ZBufferSilhouetteRenderer cpu;
    cuda->setVolume(volume);
    cpu.setVolume(volume);
    SilhouetteSettings settings;
    settings.isoReal = GetParam().iso;
    settings.gpuMemoryBudget = budget;
    for (int frame = 0; frame < 2; ++frame) { // the second frame starts where the first ended
        const SilhouetteFrame got = cuda->render(camera, settings);
        const SilhouetteFrame expected = cpu.render(camera, settings);
        std::size_t differing = 0;
        agreement(got.lines, expected.lines, differing);
        EXPECT_EQ(differing, 0u) << "frame " << frame << " on " << cuda->backendName();
        if (cuda->backendName() == "cuda") {
            EXPECT_LE(got.deviceBytes, budget);
        }
    }
}

INSTANTIATE_TEST_SUITE_P(
    Budgets, CudaBudget,
    testing::Values(
        BudgetCase{"TinyBudgetEndsOnTheCpu",
                   [] {
                       return volume::makePhantom({96, 80, 70}, volume::PhantomKind::Ct);
                   },
                   300.5, std::size_t(1) << 20},
        BudgetCase{"NoisyMeshOverflowsTheEstimate",
                   [] {
                       return noise({64, 64, 64}, VoxelType::UInt8, 4);
                   },
                   100.0, 0}),
    [](const testing::TestParamInfo<BudgetCase>& info) { return info.param.name; });

// The accuracy command's pattern: one renderer per method, bound to one analytic shape after the
// other, each sampled at 256^3 (64 MiB of floats: the allocator tends to hand the next shape the
// freed block of the last, at the same address), S frames and a streamed L frame, then unbound.
// Every method's CUDA frame is the CPU's for every shape, so nothing of the previous volume
// survives (before releaseVolume, a streamed frame's page-locked registration made the next
// shape's uploads read the last shape's pages: the accuracy sweep at 256 failed so).
TEST(CudaBackendRebinding, EachShapeInTurnGivesTheCpuImage) {
    const SilhouetteMethod methods[3] = {SilhouetteMethod::GeometryShader,
                                         SilhouetteMethod::RayCastVisibility,
                                         SilhouetteMethod::ZBuffer};
    std::unique_ptr<SilhouetteRenderer> cuda[3], cpu[3];
    for (int m = 0; m < 3; ++m) {
        try {
            cuda[m] = createSilhouetteRenderer(methods[m], Backend::Cuda);
            cpu[m] = createSilhouetteRenderer(methods[m], Backend::Cpu);
        } catch (const core::Error& error) {
            ASSERT_EQ(m, 0) << error.what(); // only method 1 may lack its GL context
            std::printf("method 1 left out: %s\n", error.what());
            cuda[m].reset();
        }
    }
    for (const std::string shapeName : {"sphere", "torus", "tori"}) {
        const auto shape = evaluation::makeAnalyticShape(shapeName);
        const Volume volume = evaluation::sampleShape(*shape, 256);
        const Camera camera = cameraAt(shape->bounds(), 30, -45, Projection::Perspective, 512, 512);
        SilhouetteSettings settings;
        settings.isoReal = evaluation::kShapeIso;
        for (int m = 0; m < 3; ++m) {
            if (!cuda[m])
                continue;
            cuda[m]->setVolume(volume);
            cpu[m]->setVolume(volume);
            const SilhouetteFrame expected = cpu[m]->render(camera, settings);
            const SilhouetteFrame frame = cuda[m]->render(camera, settings);
            expectSameFrame(frame, expected, shapeName + ", method " + std::to_string(m + 1));
        }
        // An L frame of method 3 streams the volume from page-locked host memory ...
        SilhouetteSettings chunked = settings;
        chunked.brickCells = 64;
        cuda[2]->render(camera, chunked);
        // ... and method 2's L frame maps the volume that method 3 has page-locked already.
        const SilhouetteFrame mapped = cuda[1]->render(camera, chunked);
        EXPECT_EQ(cuda[1]->backendName(), "cuda");
        expectSameFrame(mapped, cpu[1]->render(camera, settings),
                        shapeName + ", method 2 L, the volume mapped");
        // ... which must not outlive the volume: the next shape may be allocated at its address.
        for (auto& renderer : cuda)
            if (renderer)
                renderer->releaseVolume();
    }
}

TEST(CudaBackendMethod2, RenderWithoutAVolumeNamesTheError) {
    auto cuda = createSilhouetteRenderer(SilhouetteMethod::RayCastVisibility, Backend::Cuda);
    const Camera camera =
        cameraAt(Aabb{{-1, -1, -1}, {1, 1, 1}}, 0, 0, Projection::Perspective, 64, 64);
    try {
        cuda->render(camera, SilhouetteSettings{});
        ADD_FAILURE() << "rendered without a volume";
    } catch (const core::Error& error) {
        EXPECT_NE(std::string(error.what()).find("method 2 (CUDA)"), std::string::npos)
            << error.what();
    }
}

// Stroke pruning's kernels against the host's search and bridges, bit for bit: sizes at and
// beside the pixel blocks (32 x 8) and the 256-thread label blocks, groups across block edges,
// gaps (with gap 1 the stroke ends' bridges too; the sparse masks have many).
TEST(CudaBackendStrokePruning, EqualsTheHostSearch) {
    std::mt19937 random(5);
    for (const glm::ivec2 size :
         {glm::ivec2(1, 1), glm::ivec2(31, 7), glm::ivec2(32, 8), glm::ivec2(33, 9),
          glm::ivec2(256, 1), glm::ivec2(257, 65), glm::ivec2(509, 383), glm::ivec2(1024, 1024)})
        for (const int gap : {0, 1})
            for (const int minPixels : {2, 10, 60}) {
                PixelMask mask(size.x, size.y);
                const double density = 0.02 + 0.1 * double(random() % 4);
                for (std::uint8_t& p : mask.pixels())
                    p = (double(random()) / double(std::mt19937::max())) < density ? 1 : 0;
                PixelMask expected = mask;
                expected.pruneStrokes(minPixels, gap);
                const kernels::cuda::CudaStatus status = kernels::cuda::pruneStrokesOnDevice(
                    mask.pixels().data(), size.x, size.y, minPixels, gap);
                ASSERT_TRUE(status.ok()) << status.describe();
                EXPECT_TRUE(mask == expected)
                    << size.x << "x" << size.y << " gap " << gap << " min " << minPixels << ": "
                    << mask.count() << " pixels kept, the host keeps " << expected.count();
            }
}

TEST(CudaBackendStatus, ErrorsNameTheCall) {
    kernels::cuda::MarchingCubesCuda cuda;
    const auto status = cuda.extract(0.0);
    EXPECT_FALSE(status.ok());
    EXPECT_NE(status.describe().find("setVolume"), std::string::npos) << status.describe();
}

} // namespace
} // namespace lw::render
