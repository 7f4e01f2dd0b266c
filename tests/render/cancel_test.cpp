// A cancel token reaches marching cubes and the silhouette renderers: a set token stops the work
// with core::Cancelled (kernels report McStatus::Cancelled), leaves nothing half-made behind, and
// the next request without it gives exactly the result it would have given anyway.
#include "lw/core/error.h"
#include "lw/core/progress.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cpu/raycast_silhouette_cpu.h"
#include "lw/render/iso_surface.h"
#include "lw/render/raycast_silhouette_renderer.h"
#include "lw/render/zbuffer_silhouette_renderer.h"
#include "lw/volume/bricks.h"
#include "lw/volume/phantom.h"

#include <gtest/gtest.h>
#include <memory>

using namespace lw;

namespace {

volume::Volume phantom() {
    return volume::makePhantom(glm::ivec3(48), volume::PhantomKind::Ct);
}

render::Camera camera(const volume::Volume& volume) {
    render::CameraSetup setup;
    setup.bounds = render::volumeBounds(volume);
    setup.azimuthDeg = 30.0;
    setup.elevationDeg = 20.0;
    return render::Camera(setup, 160, 160);
}

} // namespace

TEST(Cancel, MarchingCubesKernelReportsCancelledWithEmptyOutput) {
    const volume::Volume volume = phantom();
    const volume::BrickGrid grid = volume::BrickGrid::build(volume, glm::ivec3(16));
    core::CancelToken token;
    token.cancel();
    kernels::cpu::McOutput out;
    out.indices = {1, 2, 3}; // whatever was there before must not survive
    const kernels::cpu::McResult result =
        kernels::cpu::marchingCubes(volume, grid, volume::kPhantomBoneIso, out, 0, &token);
    EXPECT_EQ(result.status, kernels::cpu::McStatus::Cancelled);
    EXPECT_TRUE(out.indices.empty());
    EXPECT_TRUE(out.positions.empty());
}

TEST(Cancel, ExtractorThrowsAndTheNextExtractionIsUnchanged) {
    const volume::Volume volume = phantom();
    const render::IsoSurfaceExtractor extractor(volume);
    const render::Mesh expected = extractor.extract(volume::kPhantomBoneIso);
    ASSERT_GT(expected.triangleCount(), 1000u);
    core::CancelToken token;
    token.cancel();
    render::Mesh mesh;
    EXPECT_THROW(extractor.extract(volume::kPhantomBoneIso, mesh, nullptr, &token),
                 core::Cancelled);
    EXPECT_TRUE(mesh.isEmpty());
    extractor.extract(volume::kPhantomBoneIso, mesh);
    EXPECT_EQ(mesh.indices, expected.indices);
    EXPECT_EQ(mesh.positions, expected.positions);
}

template <typename Renderer> void expectRendererCancels(int brickCells) {
    const volume::Volume volume = phantom();
    Renderer renderer;
    renderer.setVolume(volume);
    render::SilhouetteSettings settings;
    settings.isoReal = volume::kPhantomBoneIso;
    settings.brickCells = brickCells;
    const render::PixelMask expected = renderer.render(camera(volume), settings).lines;
    ASSERT_GT(expected.count(), 50u);

    Renderer fresh; // nothing cached: the cancelled frame stops inside the extraction
    fresh.setVolume(volume);
    core::CancelToken token;
    token.cancel();
    render::SilhouetteSettings cancelled = settings;
    cancelled.cancel = &token;
    EXPECT_THROW(fresh.render(camera(volume), cancelled), core::Cancelled);
    EXPECT_EQ(fresh.render(camera(volume), settings).lines, expected);
}

TEST(Cancel, ZBufferRendererWholeAndChunked) {
    expectRendererCancels<render::ZBufferSilhouetteRenderer>(0);
    expectRendererCancels<render::ZBufferSilhouetteRenderer>(16);
}

TEST(Cancel, RayCastRenderer) {
    expectRendererCancels<render::RayCastSilhouetteRenderer>(0);
}

TEST(Cancel, MethodTwoCellPreparationStopsAndPreparesNothing) {
    const volume::Volume volume = phantom();
    const volume::BrickGrid grid = volume::BrickGrid::build(volume, glm::ivec3(16));
    core::CancelToken token;
    token.cancel();
    kernels::cpu::RayCastSilhouetteCpu kernel;
    EXPECT_FALSE(kernel.prepare(volume, grid, volume::kPhantomBoneIso, true, 0, &token));
    EXPECT_FALSE(kernel.isPrepared());
    EXPECT_TRUE(kernel.prepare(volume, grid, volume::kPhantomBoneIso));
    EXPECT_GT(kernel.activeCellCount(), 1000u);
}
