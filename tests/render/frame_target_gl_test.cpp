// The GL frame target on any OpenGL (label gl; SKIP without a headless context): a texture of
// any size reads back as an all-off mask, and a back-end that cannot write it (the CPU) fills the
// host mask and says it did not draw there, leaving the texture as it was.

#include "gl_test_context.h"
#include "lw/render/gl_frame_target.h"
#include "lw/render/zbuffer_silhouette_renderer.h"
#include "lw/volume/phantom.h"

#include <gtest/gtest.h>

namespace lw::render {
namespace {

class GlFrameTargetTest : public testing::Test {
protected:
    void SetUp() override { lw::test::glContext().makeCurrent(); }
};

TEST_F(GlFrameTargetTest, ANewTargetIsAllOff) {
    GlFrameTarget target(37, 11); // rows not a multiple of 4 bytes
    EXPECT_NE(target.texture(), 0u);
    const PixelMask texels = target.read();
    EXPECT_EQ(texels.width(), 37);
    EXPECT_EQ(texels.height(), 11);
    EXPECT_EQ(texels.count(), 0u);
}

TEST_F(GlFrameTargetTest, TheCpuFillsTheHostMask) {
    const volume::Volume volume = volume::makePhantom({48, 40, 36}, volume::PhantomKind::Ct);
    CameraSetup setup;
    setup.bounds = volumeBounds(volume);
    setup.azimuthDeg = 30;
    setup.elevationDeg = 20;
    const Camera camera(setup, 160, 120);
    ZBufferSilhouetteRenderer cpu(Backend::Cpu);
    cpu.setVolume(volume);
    SilhouetteSettings settings;
    settings.isoReal = 300.5;
    const SilhouetteFrame expected = cpu.render(camera, settings);
    GlFrameTarget target(160, 120);
    settings.frameTarget = &target;
    ASSERT_EQ(frameTargetUse(settings, camera), FrameTargetUse::Texture);
    const SilhouetteFrame frame = cpu.render(camera, settings);
    EXPECT_FALSE(frame.drewToTarget);
    ASSERT_GT(expected.lines.count(), 50u);
    EXPECT_TRUE(frame.lines == expected.lines);
    EXPECT_EQ(target.read().count(), 0u);
}

} // namespace
} // namespace lw::render
