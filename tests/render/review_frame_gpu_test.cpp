// The review's frame on the device path (label gpu: CUDA with NVIDIA's OpenGL): the iso panel
// shaded from the device's mesh equals the host path's picture, and no host mesh is made.
// Every method's panel is lit by CUDA's rasterizer from the surface on the device, compared with
// the CPU's shading, which it repeats; with that switched off, method 1's GL draws it, compared
// with GL on the host path.

#include "lw/core/error.h"
#include "lw/render/contour_triangles.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/visible_polylines.h"
#include "review_frame_test_support.h"

#include <gtest/gtest.h>
#include <string>

namespace lw::render {
namespace {

using namespace lw::render::test;

// The device path: CUDA and an NVIDIA OpenGL context (EGL) on the same machine; empty when
// they are there, else why not.
std::string deviceMissing() {
    if (!cudaAvailability().available)
        return "no CUDA device: " + cudaAvailability().reason;
    if (!reviewIsoOnDevice(Backend::Cuda))
        return "this build has no CUDA-GL interop";
    try {
        EglHeadlessContext probe;
        if (probe.vendor().find("NVIDIA") == std::string::npos)
            return "the GL context is not NVIDIA's: " + probe.description();
    } catch (const core::Error& error) {
        return std::string("no headless OpenGL context: ") + error.what();
    }
    return {};
}

class ReviewFrameOnDevice : public testing::TestWithParam<SilhouetteMethod> {
protected:
    void SetUp() override {
        if (const std::string missing = deviceMissing(); !missing.empty())
            GTEST_SKIP() << missing;
    }
};

class DeviceFrame : public testing::Test {
protected:
    void SetUp() override {
        if (const std::string missing = deviceMissing(); !missing.empty())
            GTEST_SKIP() << missing;
    }
};

TEST_P(ReviewFrameOnDevice, DrawsTheHostPathsPictureWithNoHostMesh) {
    const auto volume = phantom();
    for (const double az : {30.0, 200.0}) {
        ReviewFrameRenderer device(volume);
        ReviewFrameRequest request = requestFor(*volume, GetParam(), Backend::Cuda, az);
        const ReviewFrame onDevice = device.render(request);
        ASSERT_TRUE(onDevice.isoOnDevice) << onDevice.backendNote;
        EXPECT_EQ(device.hostMeshesMade(), 0u) << "the iso panel drew the device's mesh";
        EXPECT_FALSE(onDevice.mesh);

        ReviewFrameRenderer host(volume);
        ReviewFrameRequest onHostRequest = request;
        onHostRequest.backend = Backend::Cpu;
        onHostRequest.isoOnCpu = true;
        const ReviewFrame onHost = host.render(onHostRequest);
        ASSERT_FALSE(onHost.isoOnDevice);
        EXPECT_GE(host.hostMeshesMade(), 1u);

        ASSERT_TRUE(onDevice.surfaceTriangles && onHost.surfaceTriangles);
        EXPECT_EQ(*onDevice.surfaceTriangles, *onHost.surfaceTriangles)
            << "the device's count is the surface's";
        ASSERT_TRUE(onDevice.isoImage && onHost.isoImage);
        EXPECT_GT(drawnPixels(*onDevice.isoImage), 800u);
        EXPECT_GE(agreement(*onDevice.isoImage, *onHost.isoImage, 1), 0.999) << "az " << az;
        ASSERT_EQ(onDevice.isoDepth.size(), onHost.isoDepth.size());
        std::size_t depthDiffers = 0;
        for (std::size_t i = 0; i < onHost.isoDepth.size(); ++i)
            depthDiffers += std::abs(onDevice.isoDepth[i] - onHost.isoDepth[i]) > 1e-5f;
        EXPECT_LE(depthDiffers, onHost.isoDepth.size() / 1000) << "az " << az;
        ASSERT_TRUE(onDevice.silhouette && onHost.silhouette);
        EXPECT_GT(onDevice.silhouette->lines.count(), 200u);

        // A new view reuses the device's surface: still no host mesh.
        request.camera = request.isoCamera = cameraAt(*volume, az + 90.0, 0.0);
        const ReviewFrame turned = device.render(request);
        EXPECT_TRUE(turned.isoOnDevice);
        EXPECT_EQ(turned.meshMs, 0.0) << "no extraction for a new view";
        EXPECT_EQ(device.hostMeshesMade(), 0u);
    }
}

// A display whose OpenGL is software (isoOnCpu: the host would shade on the CPU) still gets the
// panel shaded by CUDA from the device's surface, which needs no GL: no host mesh either.
TEST_P(ReviewFrameOnDevice, ASoftwareGlDisplayStillGetsCudasShading) {
    const auto volume = phantom();
    ReviewFrameRenderer device(volume);
    ReviewFrameRequest request = requestFor(*volume, GetParam(), Backend::Cuda, 30.0);
    request.isoOnCpu = true;
    const ReviewFrame onDevice = device.render(request);
    EXPECT_TRUE(onDevice.isoOnDevice) << onDevice.backendNote;
    EXPECT_EQ(device.hostMeshesMade(), 0u);
    ASSERT_TRUE(onDevice.isoImage);
    EXPECT_GT(drawnPixels(*onDevice.isoImage), 800u);
}

// With CUDA's shading switched off the device path shades with GL (method 1's buffers), as GL
// shades the host's mesh.
TEST_F(DeviceFrame, GlShadesThePanelWhenCudaShadingIsOff) {
    const auto volume = phantom();
    for (const SilhouetteMethod method :
         {SilhouetteMethod::GeometryShader, SilhouetteMethod::ZBuffer}) {
        ReviewFrameRenderer device(volume);
        ReviewFrameRequest request = requestFor(*volume, method, Backend::Cuda, 30.0);
        request.isoShadedByCuda = false;
        const ReviewFrame onDevice = device.render(request);
        ASSERT_TRUE(onDevice.isoOnDevice) << onDevice.backendNote;
        EXPECT_EQ(device.hostMeshesMade(), 0u);
        ReviewFrameRenderer host(volume);
        ReviewFrameRequest onHostRequest = request;
        onHostRequest.backend = Backend::Cpu;
        const ReviewFrame onHost = host.render(onHostRequest);
        ASSERT_TRUE(onDevice.isoImage && onHost.isoImage);
        EXPECT_GT(drawnPixels(*onDevice.isoImage), 800u);
        EXPECT_GE(agreement(*onDevice.isoImage, *onHost.isoImage, 2), 0.999)
            << "method " << int(method);
    }
}

// Where the silhouette keeps no whole surface on the device (method 3 chunked, mode b
// extracting every frame), CUDA still shades the panel, from a surface of its own.
TEST_F(DeviceFrame, ShadesWithCudaWhateverTheSilhouettesSchedule) {
    const auto volume = phantom();
    for (const bool chunked : {true, false}) {
        ReviewFrameRenderer device(volume);
        ReviewFrameRequest request =
            requestFor(*volume, SilhouetteMethod::ZBuffer, Backend::Cuda, 60.0);
        request.settings.brickCells = chunked ? 16 : 0;
        request.settings.mode = chunked ? ExtractionMode::CachedA : ExtractionMode::EveryFrameB;
        request.forceExtract = !chunked;
        ReviewFrameRequest onHostRequest = request;
        onHostRequest.backend = Backend::Cpu;
        onHostRequest.isoOnCpu = true;
        ReviewFrameRenderer host(volume);
        for (int frame = 0; frame < 2; ++frame) {
            const ReviewFrame onDevice = device.render(request);
            ASSERT_TRUE(onDevice.isoOnDevice) << onDevice.backendNote;
            EXPECT_EQ(device.hostMeshesMade(), 0u) << "chunked " << chunked;
            const ReviewFrame onHost = host.render(onHostRequest);
            ASSERT_TRUE(onDevice.isoImage && onHost.isoImage);
            EXPECT_GT(drawnPixels(*onDevice.isoImage), 800u);
            EXPECT_GE(agreement(*onDevice.isoImage, *onHost.isoImage, 1), 0.999)
                << "chunked " << chunked << ", frame " << frame;
            EXPECT_EQ(onDevice.surfaceTriangles, onHost.surfaceTriangles);
            request.camera = request.isoCamera = cameraAt(*volume, 150.0, -10.0);
            onHostRequest.camera = onHostRequest.isoCamera = request.camera;
        }
    }
}

// The same lines, point for point, in the same order.
bool sameLines(const std::vector<Polyline>& a, const std::vector<Polyline>& b) {
    if (a.size() != b.size())
        return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].closed != b[i].closed || a[i].points != b[i].points)
            return false;
    return true;
}

// An export's vector lines on the device come from the triangles that may hold the contour,
// selected there and downloaded alone: exactly the host's selection from the whole surface, the
// same lines as from the whole surface, and no host mesh made -- closed at the border (the cap
// from the host appended) and open; method 3's surface, method 1's (in GL buffers) and, for
// method 2, the iso panel's CUDA renderer's.
class ExportLinesOnDevice : public ReviewFrameOnDevice {};

TEST_P(ExportLinesOnDevice, ComeFromTheContourTrianglesAlone) {
    const auto volume = phantom();
    for (const bool closed : {true, false}) {
        ReviewFrameRenderer device(volume);
        ReviewFrameRequest request = requestFor(*volume, GetParam(), Backend::Cuda, 30.0);
        request.settings.closeAtBorder = closed;
        request.wantPolylines = true;
        request.hiddenLines = true;
        const ReviewFrame onDevice = device.render(request);
        EXPECT_EQ(device.hostMeshesMade(), 0u) << "closed " << closed;
        ASSERT_TRUE(onDevice.silhouette);
        ASSERT_GT(onDevice.polylines.visible.size(), 5u) << "closed " << closed;

        // Method 2 keeps no surface: its lines come from the iso panel's CUDA renderer's.
        const SilhouetteMethod surfaceMethod = GetParam() == SilhouetteMethod::RayCastVisibility
                                                   ? SilhouetteMethod::ZBuffer
                                                   : GetParam();
        auto renderer = createSilhouetteRenderer(surfaceMethod, Backend::Cuda);
        renderer->setVolume(*volume);
        SilhouetteSettings settings = request.settings;
        settings.isoReal = kIso;
        const SilhouetteFrame frame = renderer->render(request.camera, settings);
        const std::optional<Mesh> part = renderer->contourTriangles(request.camera);
        ASSERT_TRUE(part) << "the surface is on the device";
        const Mesh whole = *renderer->surfaceMesh();
        const Mesh expected = contourTriangles(whole, request.camera);
        EXPECT_GT(part->triangleCount(), 20u);
        EXPECT_LT(part->triangleCount(), whole.triangleCount() / 2);
        EXPECT_TRUE(part->positions == expected.positions) << "closed " << closed;
        EXPECT_TRUE(part->normals == expected.normals) << "closed " << closed;
        EXPECT_EQ(part->indices, expected.indices);
        const PolylineSplit fromPart =
            splitPolylines(*part, request.camera, frame.lines, request.polylineOptions, true);
        const PolylineSplit fromWhole =
            splitPolylines(whole, request.camera, frame.lines, request.polylineOptions, true);
        ASSERT_FALSE(fromWhole.visible.empty());
        EXPECT_TRUE(sameLines(fromPart.visible, fromWhole.visible)) << "closed " << closed;
        EXPECT_TRUE(sameLines(fromPart.hidden, fromWhole.hidden)) << "closed " << closed;
        const PolylineSplit framesFromWhole = splitPolylines(
            whole, request.camera, onDevice.silhouette->lines, request.polylineOptions, true);
        EXPECT_TRUE(sameLines(onDevice.polylines.visible, framesFromWhole.visible))
            << "the review frame's lines, closed " << closed;
        EXPECT_TRUE(sameLines(onDevice.polylines.hidden, framesFromWhole.hidden));
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, ExportLinesOnDevice,
                         testing::Values(SilhouetteMethod::ZBuffer,
                                         SilhouetteMethod::RayCastVisibility,
                                         SilhouetteMethod::GeometryShader),
                         [](const testing::TestParamInfo<SilhouetteMethod>& info) {
                             return "Method" + std::to_string(int(info.param));
                         });

// Thick slices on the device: the field of a new iso-value is made on the device, and the
// renderers kept from the last one (method 1's interop buffers, method 3's device surface) are
// rebound to it. They must draw what renderers made for it draw.
TEST_P(ReviewFrameOnDevice, ThickSlicesAtANewIsoValueDrawWhatAFreshFrameDraws) {
    const auto volume = thickPhantom();
    ReviewFrameRequest request = requestFor(*volume, GetParam(), Backend::Cuda, 40.0);
    request.sampling = {Oversampling::Auto, ThickSlices::Smooth};
    ReviewFrameRenderer kept(volume);
    kept.render(request);
    for (const double iso : {700.5, -400.0, 300.5}) {
        request.iso = iso;
        const ReviewFrame rebound = kept.render(request);
        ReviewFrameRenderer fresh(volume);
        const ReviewFrame reference = fresh.render(request);
        expectSameDrawing(rebound, reference, iso);
        if (HasFatalFailure())
            return;
        EXPECT_TRUE(rebound.isoOnDevice) << rebound.backendNote;
    }
}

INSTANTIATE_TEST_SUITE_P(Methods, ReviewFrameOnDevice,
                         testing::Values(SilhouetteMethod::GeometryShader,
                                         SilhouetteMethod::RayCastVisibility,
                                         SilhouetteMethod::ZBuffer),
                         [](const testing::TestParamInfo<SilhouetteMethod>& info) {
                             return "Method" + std::to_string(int(info.param));
                         });

} // namespace
} // namespace lw::render
