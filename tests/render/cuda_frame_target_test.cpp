// Method 3 on CUDA drawing into a GL texture (label gpu: SKIP without a CUDA device). The compose
// kernel writes the texture through CUDA-GL interop; read back from GL it must equal, bit for bit,
// the host mask the same renderer gives for the same frame without the texture. Where the texture
// cannot be used (wrong size, no GL context current) the frame takes
// the host path and says so.

#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/gl_context.h"
#include "lw/render/gl_frame_target.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/zbuffer_silhouette_renderer.h"
#include "lw/volume/phantom.h"

#include <gtest/gtest.h>
#include <memory>
#include <string>
#include <vector>

namespace lw::render {
namespace {

Camera cameraAt(const volume::Volume& volume, double az, double el, int width, int height) {
    CameraSetup setup;
    setup.bounds = volumeBounds(volume);
    setup.azimuthDeg = az;
    setup.elevationDeg = el;
    setup.projection = Projection::Perspective;
    return Camera(setup, width, height);
}

// Warnings of lw.render while alive, passed on to the sink before it.
class WarningLog {
public:
    WarningLog() {
        m_previous = core::setLogSink(
            [this](core::LogLevel level, std::string_view category, const std::string& text) {
                if (level == core::LogLevel::Warning && category == "lw.render")
                    m_lines.push_back(text);
                if (m_previous)
                    m_previous(level, category, text);
            });
    }
    ~WarningLog() { core::setLogSink(m_previous); }
    WarningLog(const WarningLog&) = delete;
    WarningLog& operator=(const WarningLog&) = delete;
    const std::vector<std::string>& lines() const { return m_lines; }

private:
    core::LogSink m_previous;
    std::vector<std::string> m_lines;
};

class CudaFrameTarget : public testing::Test {
protected:
    void SetUp() override {
        try {
            m_context = std::make_unique<EglHeadlessContext>();
        } catch (const core::Error& error) {
            GTEST_SKIP() << "no headless OpenGL context: " << error.what();
        }
        // Interop needs the GL context on the CUDA device: NVIDIA's driver, not Mesa's.
        if (m_context->vendor().find("NVIDIA") == std::string::npos)
            GTEST_SKIP() << "the GL context is not NVIDIA's: " << m_context->description();
        m_volume = volume::makePhantom({128, 120, 96}, volume::PhantomKind::Ct);
        m_renderer = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cuda);
        m_renderer->setVolume(m_volume);
    }
    void TearDown() override {
        if (m_renderer)
            m_renderer->releaseVolume();
    }

    // A frame into `target`, then the same frame into host memory: the texels must be the mask.
    void expectTextureEqualsHostMask(GlFrameTarget& target, const Camera& camera,
                                     SilhouetteSettings settings, const std::string& what) {
        settings.frameTarget = &target;
        const SilhouetteFrame drawn = m_renderer->render(camera, settings);
        ASSERT_TRUE(drawn.drewToTarget) << what;
        EXPECT_EQ(drawn.lines.width(), 0) << what << ": no host mask when it went to the texture";
        settings.frameTarget = nullptr;
        const SilhouetteFrame host = m_renderer->render(camera, settings);
        ASSERT_FALSE(host.drewToTarget);
        EXPECT_EQ(m_renderer->backendName(), "cuda") << what;
        ASSERT_GT(host.lines.count(), 500u) << what;
        const PixelMask texels = target.read();
        EXPECT_TRUE(texels == host.lines) << what << ": " << texels.count() << " texels on, "
                                          << host.lines.count() << " mask pixels on";
        EXPECT_EQ(drawn.segments, host.segments) << what;
        EXPECT_EQ(drawn.triangles, host.triangles) << what;
    }

    std::unique_ptr<EglHeadlessContext> m_context;
    volume::Volume m_volume;
    std::unique_ptr<SilhouetteRenderer> m_renderer;
};

// An odd size (rows not a multiple of 4 bytes), several views through one registration, mode a
// and b, and the streamed slabs.
TEST_F(CudaFrameTarget, TextureEqualsTheHostMaskBitForBit) {
    const int width = 509, height = 383;
    GlFrameTarget target(width, height);
    SilhouetteSettings settings;
    settings.isoReal = 300.5;
    expectTextureEqualsHostMask(target, cameraAt(m_volume, 30, 20, width, height), settings,
                                "mode a, first view");
    expectTextureEqualsHostMask(target, cameraAt(m_volume, -65, 40, width, height), settings,
                                "mode a, second view");
    settings.mode = ExtractionMode::EveryFrameB;
    settings.visibility = false;
    expectTextureEqualsHostMask(target, cameraAt(m_volume, 120, -10, width, height), settings,
                                "mode b, visibility off");
    SilhouetteSettings streamed;
    streamed.isoReal = 300.5;
    streamed.brickCells = 16;
    streamed.gpuSlabLayers = 7;
    expectTextureEqualsHostMask(target, cameraAt(m_volume, 10, 15, width, height), streamed,
                                "streamed slabs");
}

// Stroke pruning runs on the device before the compose: the texture is the pruned mask, which is
// the CPU's pruned mask.
TEST_F(CudaFrameTarget, PrunedStrokesGoToTheTextureToo) {
    const int width = 509, height = 383;
    GlFrameTarget target(width, height);
    SilhouetteSettings settings;
    settings.isoReal = 300.5;
    settings.minStrokePixels = 40;
    const Camera camera = cameraAt(m_volume, 30, 20, width, height);
    expectTextureEqualsHostMask(target, camera, settings, "pruned");
    auto cpu = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Cpu);
    cpu->setVolume(m_volume);
    SilhouetteSettings unpruned = settings;
    unpruned.minStrokePixels = 0;
    const PixelMask all = cpu->render(camera, unpruned).lines;
    const PixelMask pruned = cpu->render(camera, settings).lines;
    EXPECT_LT(pruned.count(), all.count()) << "the view has strokes under 40 pixels to drop";
    EXPECT_TRUE(target.read() == pruned);
}

// A resize the caller has not caught up with keeps the host path; the texture is left as it was.
TEST_F(CudaFrameTarget, HostPathWhereTheTextureDoesNotApply) {
    GlFrameTarget target(256, 200);
    SilhouetteSettings settings;
    settings.isoReal = 300.5;
    settings.frameTarget = &target;
    const SilhouetteFrame resized =
        m_renderer->render(cameraAt(m_volume, 30, 20, 300, 200), settings);
    EXPECT_FALSE(resized.drewToTarget);
    EXPECT_EQ(resized.lines.width(), 300);
    EXPECT_GT(resized.lines.count(), 200u);
    EXPECT_EQ(target.read().count(), 0u);
}

// A target destroyed before the renderer takes its registration with it; a new one is registered.
TEST_F(CudaFrameTarget, ANewTextureAfterTheOldOneWent) {
    SilhouetteSettings settings;
    settings.isoReal = 300.5;
    const Camera camera = cameraAt(m_volume, 30, 20, 320, 240);
    {
        GlFrameTarget first(320, 240);
        expectTextureEqualsHostMask(first, camera, settings, "first texture");
    }
    GlFrameTarget second(320, 240);
    expectTextureEqualsHostMask(second, camera, settings, "second texture");
}

// Without its GL context current the texture cannot be registered: the host path, logged once.
TEST_F(CudaFrameTarget, WithoutTheGlContextFallsBackToTheHostOnce) {
    GlFrameTarget target(320, 240);
    const Camera camera = cameraAt(m_volume, 30, 20, 320, 240);
    SilhouetteSettings settings;
    settings.isoReal = 300.5;
    const PixelMask expected = m_renderer->render(camera, settings).lines;
    settings.frameTarget = &target;
    WarningLog log;
    m_context->doneCurrent();
    const SilhouetteFrame first = m_renderer->render(camera, settings);
    m_context->makeCurrent();
    const SilhouetteFrame second = m_renderer->render(camera, settings);
    EXPECT_FALSE(first.drewToTarget);
    EXPECT_FALSE(second.drewToTarget) << "after a failure the host path stays";
    EXPECT_TRUE(first.lines == expected);
    EXPECT_TRUE(second.lines == expected);
    ASSERT_EQ(log.lines().size(), 1u);
    EXPECT_NE(log.lines()[0].find("host memory"), std::string::npos) << log.lines()[0];
}

} // namespace
} // namespace lw::render
