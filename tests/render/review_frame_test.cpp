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

// Thick slices: a new iso-value makes a new shape-based copy of the same grid, and the renderers
// kept from the last one are rebound to it. They must draw what renderers made for it draw.
class ReviewFrameThickSlices : public testing::TestWithParam<SilhouetteMethod> {};

TEST_P(ReviewFrameThickSlices, ANewIsoValueDrawsWhatAFreshFrameDraws) {
    const auto volume = thickPhantom();
    ReviewFrameRequest request = requestFor(*volume, GetParam(), Backend::Cpu, 40.0);
    request.sampling = {Oversampling::Auto, ThickSlices::Smooth};
    request.isoOnCpu = true;
    ASSERT_TRUE(samplingPlan(volume->dims(), volume->geometry(), request.sampling).dependsOnIso());
    ReviewFrameRenderer kept(volume);
    const ReviewFrame first = kept.render(request);
    for (const double iso : {700.5, -400.0, 300.5}) {
        request.iso = iso;
        const ReviewFrame rebound = kept.render(request);
        ReviewFrameRenderer fresh(volume);
        const ReviewFrame reference = fresh.render(request);
        expectSameDrawing(rebound, reference, iso);
        if (HasFatalFailure())
            return;
        EXPECT_EQ(*rebound.surfaceTriangles, *reference.surfaceTriangles) << iso;
    }
    EXPECT_TRUE(kept.render(request).silhouette->lines == first.silhouette->lines)
        << "back at the first iso-value, the first drawing";
}

INSTANTIATE_TEST_SUITE_P(HostMethods, ReviewFrameThickSlices,
                         testing::Values(SilhouetteMethod::ZBuffer,
                                         SilhouetteMethod::RayCastVisibility));

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
