// The review's frame (lw/render/review_frame.h) on the host path: a host mesh made once per
// iso-value and the iso panel shaded from it (review_frame_gpu_test.cpp: the device path).

#include "lw/core/error.h"
#include "review_frame_test_support.h"

#include <gtest/gtest.h>

namespace lw::render {
namespace {

using namespace lw::render::test;

TEST(ReviewFrame, HostPathMakesOneMeshPerIsoValue) {
    const auto volume = phantom();
    ReviewFrameRenderer frames(volume);
    ReviewFrameRequest request = requestFor(*volume, SilhouetteMethod::ZBuffer, Backend::Cpu, 30.0);
    request.isoOnCpu = true;
    const ReviewFrame first = frames.render(request);
    ASSERT_TRUE(first.isoImage && first.silhouette && first.surfaceTriangles);
    EXPECT_FALSE(first.isoOnDevice);
    EXPECT_GT(*first.surfaceTriangles, 1000u);
    EXPECT_GT(drawnPixels(*first.isoImage), 800u) << "the iso panel is not empty";
    EXPECT_GT(first.silhouette->lines.count(), 200u);
    EXPECT_EQ(first.isoDepth.size(), std::size_t(160 * 120));
    EXPECT_EQ(frames.hostMeshesMade(), 1u) << "method 3 hands its own mesh on";

    request.camera = request.isoCamera = cameraAt(*volume, 120.0, -10.0);
    const ReviewFrame turned = frames.render(request);
    EXPECT_EQ(frames.hostMeshesMade(), 1u) << "a new view reuses the surface";
    ASSERT_TRUE(turned.isoImage);
    EXPECT_LT(agreement(*first.isoImage, *turned.isoImage, 0), 0.99) << "the view changed";

    request.iso = 700.5;
    const ReviewFrame denser = frames.render(request);
    EXPECT_EQ(frames.hostMeshesMade(), 2u);
    ASSERT_TRUE(denser.surfaceTriangles);
    EXPECT_NE(*denser.surfaceTriangles, *first.surfaceTriangles);
}

TEST(ReviewFrame, MethodTwoKeepsNoMeshSoTheIsoPanelExtractsOne) {
    const auto volume = phantom();
    ReviewFrameRenderer frames(volume);
    ReviewFrameRequest request =
        requestFor(*volume, SilhouetteMethod::RayCastVisibility, Backend::Cpu, 60.0);
    request.isoOnCpu = true;
    const ReviewFrame frame = frames.render(request);
    ASSERT_TRUE(frame.mesh && frame.surfaceTriangles);
    EXPECT_EQ(frame.mesh->triangleCount(), *frame.surfaceTriangles);
    EXPECT_GT(frame.meshMs, 0.0);
    EXPECT_EQ(frames.hostMeshesMade(), 1u);
    frames.render(request);
    EXPECT_EQ(frames.hostMeshesMade(), 1u);
}

TEST(ReviewFrame, ACancelledRequestThrows) {
    const auto volume = phantom();
    ReviewFrameRenderer frames(volume);
    core::CancelToken cancel;
    cancel.cancel();
    ReviewFrameRequest request = requestFor(*volume, SilhouetteMethod::ZBuffer, Backend::Cpu, 0.0);
    request.isoOnCpu = true;
    request.cancel = &cancel;
    EXPECT_THROW(frames.render(request), core::Cancelled);
    EXPECT_EQ(frames.hostMeshesMade(), 0u);
}

} // namespace
} // namespace lw::render
