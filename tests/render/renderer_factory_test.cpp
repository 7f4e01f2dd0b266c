// The renderer factory and its option parsers: the right implementation per method, and errors
// that name the option and the reason (CUDA not built, unknown values, no GL).
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/silhouette_methods.h"

#include <gtest/gtest.h>
#include <string>

namespace lw::render {
namespace {

std::string errorOf(auto&& call) {
    try {
        call();
    } catch (const core::Error& error) {
        return error.what();
    }
    return {};
}

TEST(RendererFactory, ParsesMethodsAndBackends) {
    EXPECT_EQ(parseSilhouetteMethod("1"), SilhouetteMethod::GeometryShader);
    EXPECT_EQ(parseSilhouetteMethod("2"), SilhouetteMethod::RayCastVisibility);
    EXPECT_EQ(parseSilhouetteMethod("3"), SilhouetteMethod::ZBuffer);
    EXPECT_EQ(parseBackend("cpu"), Backend::Cpu);
    EXPECT_EQ(parseBackend("cuda"), Backend::Cuda);
    EXPECT_EQ(parseBackend("auto"), Backend::Auto);
    EXPECT_EQ(backendName(Backend::Cuda), "cuda");
}

// The method registry: every method once, in number order, its key parsing back to it, the
// capabilities the callers ask for; a value that is no method throws instead of being clamped.
TEST(SilhouetteMethods, OneDescriptorPerMethod) {
    int expected = 1;
    for (const SilhouetteMethodInfo& info : silhouetteMethods()) {
        EXPECT_EQ(info.number, expected++);
        EXPECT_EQ(parseSilhouetteMethod(info.key), info.method);
        EXPECT_EQ(&silhouetteMethodInfo(info.method), &info);
        EXPECT_EQ(findSilhouetteMethod(info.key), &info);
        EXPECT_FALSE(info.name.empty());
        EXPECT_NE(info.label.find(std::to_string(info.number)), std::string_view::npos);
    }
    EXPECT_EQ(silhouetteMethods().size(), 3u);
    EXPECT_EQ(silhouetteMethodKeys(), "1, 2 or 3");
    EXPECT_TRUE(silhouetteMethodInfo(SilhouetteMethod::GeometryShader).needsOpenGl);
    EXPECT_FALSE(silhouetteMethodInfo(SilhouetteMethod::RayCastVisibility).keepsMesh);
    EXPECT_TRUE(silhouetteMethodInfo(SilhouetteMethod::ZBuffer).drawsToTexture);
    EXPECT_EQ(findSilhouetteMethod("4"), nullptr);
    EXPECT_THROW(silhouetteMethodInfo(SilhouetteMethod(4)), lw::core::Error);
}

TEST(RendererFactory, BadValuesNameTheOption) {
    const std::string method = errorOf([] { parseSilhouetteMethod("4", "--methods"); });
    EXPECT_NE(method.find("--methods 4"), std::string::npos) << method;
    EXPECT_NE(method.find("1, 2 or 3"), std::string::npos) << method;
    EXPECT_FALSE(errorOf([] { parseSilhouetteMethod(""); }).empty());
    EXPECT_FALSE(errorOf([] { parseSilhouetteMethod("12"); }).empty());
    const std::string backend = errorOf([] { parseBackend("gpu"); });
    EXPECT_NE(backend.find("--backend gpu"), std::string::npos) << backend;
    EXPECT_NE(backend.find("cpu, cuda or auto"), std::string::npos) << backend;
}

TEST(RendererFactory, CudaWithoutADeviceSaysWhy) {
    const CudaAvailability cuda = cudaAvailability();
    if (cuda.available)
        GTEST_SKIP() << "a CUDA device is present: " << cuda.deviceName;
    EXPECT_FALSE(cuda.reason.empty());
    for (const SilhouetteMethod method :
         {SilhouetteMethod::RayCastVisibility, SilhouetteMethod::ZBuffer}) {
        const std::string message =
            errorOf([&] { createSilhouetteRenderer(method, Backend::Cuda); });
        EXPECT_NE(message.find("--backend cuda"), std::string::npos) << message;
        EXPECT_NE(message.find(cuda.reason), std::string::npos) << message;
    }
}

TEST(RendererFactory, CudaOnlyWhereTheMethodHasKernels) {
    const CudaAvailability cuda = cudaAvailability();
    if (!cuda.available)
        GTEST_SKIP() << "no CUDA device: " << cuda.reason;
    std::string note;
#if LINEWORK_GL
    // Method 1: CUDA extraction into the GL buffers (where a GL context can be made).
    try {
        auto m1 = createSilhouetteRenderer(SilhouetteMethod::GeometryShader, Backend::Auto, &note);
        EXPECT_EQ(m1->backendName(), "cuda+gl");
    } catch (const lw::core::Error& error) {
        EXPECT_NE(std::string(error.what()).find("OpenGL"), std::string::npos) << error.what();
    }
#endif
    for (const SilhouetteMethod method :
         {SilhouetteMethod::RayCastVisibility, SilhouetteMethod::ZBuffer}) {
        auto renderer = createSilhouetteRenderer(method, Backend::Auto, &note);
        EXPECT_EQ(renderer->backendName(), "cuda");
        EXPECT_EQ(note, "auto: CUDA on " + cuda.deviceName);
    }
}

TEST(RendererFactory, CpuMethodsAndTheAutoNote) {
    std::string note = "stale";
    auto m2 = createSilhouetteRenderer(SilhouetteMethod::RayCastVisibility, Backend::Cpu, &note);
    ASSERT_NE(m2, nullptr);
    EXPECT_EQ(m2->method(), SilhouetteMethod::RayCastVisibility);
    EXPECT_EQ(m2->backendName(), "cpu");
    EXPECT_TRUE(note.empty()) << "an explicit backend needs no note";

    const CudaAvailability cuda = cudaAvailability();
    if (cuda.available)
        return; // auto picks CUDA there (CudaOnlyWhereTheMethodHasKernels)
    auto m3 = createSilhouetteRenderer(SilhouetteMethod::ZBuffer, Backend::Auto, &note);
    ASSERT_NE(m3, nullptr);
    EXPECT_EQ(m3->method(), SilhouetteMethod::ZBuffer);
    EXPECT_EQ(m3->backendName(), "cpu");
    EXPECT_EQ(note, "auto: " + cuda.reason + ", using CPU");
}

#if !LINEWORK_GL
TEST(RendererFactory, Method1WithoutGlSaysWhy) {
    const std::string message =
        errorOf([] { createSilhouetteRenderer(SilhouetteMethod::GeometryShader, Backend::Cpu); });
    EXPECT_NE(message.find("no OpenGL context"), std::string::npos) << message;
}
#endif

} // namespace
} // namespace lw::render
