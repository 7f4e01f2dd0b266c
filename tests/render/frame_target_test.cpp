// The frame target's host side (label unit): when a frame may go into a GL texture and when it
// must take the host path.

#include "lw/render/silhouette_renderer.h"

#include <gtest/gtest.h>

namespace lw::render {
namespace {

// Stroke pruning no longer keeps a frame on the host: the CUDA back-end prunes on the device.
TEST(FrameTargetUse, OnlyATextureOfTheFramesSize) {
    const glm::ivec2 frame(640, 480);
    EXPECT_EQ(frameTargetUse({640, 480}, frame), FrameTargetUse::Texture);
    EXPECT_EQ(frameTargetUse({0, 0}, frame), FrameTargetUse::NoTarget);
    EXPECT_EQ(frameTargetUse({640, 0}, frame), FrameTargetUse::NoTarget);
    EXPECT_EQ(frameTargetUse({641, 480}, frame), FrameTargetUse::SizeDiffers);
    EXPECT_EQ(frameTargetUse({640, 479}, frame), FrameTargetUse::SizeDiffers);
}

TEST(FrameTargetUse, FromSettingsWithoutATarget) {
    SilhouetteSettings settings;
    CameraSetup setup;
    setup.bounds = {{0, 0, 0}, {10, 10, 10}};
    EXPECT_EQ(frameTargetUse(settings, Camera(setup, 64, 48)), FrameTargetUse::NoTarget);
}

} // namespace
} // namespace lw::render
