// gtest main for the GL tests (lw_gtest_main_gl): the failing log sink of gtest_main.cpp, plus a
// headless OpenGL 4.x context for the whole run. Without one the binary prints "SKIP: ..." and
// exits with the SKIP code, so a machine without GL reports SKIP rather than a PASS that tested
// nothing.
#include "gl_test_context.h"
#include "lw/core/error.h"
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>

namespace {

std::unique_ptr<lw::render::EglHeadlessContext> g_context;

} // namespace

lw::render::EglHeadlessContext& lw::test::glContext() {
    if (!g_context) {
        std::fputs("lw::test::glContext() called outside RUN_ALL_TESTS\n", stderr);
        std::abort();
    }
    return *g_context;
}

int main(int argc, char** argv) {
    testing::InitGoogleTest(&argc, argv);
    lw::test::installFailingLogSink();
    try {
        g_context = std::make_unique<lw::render::EglHeadlessContext>();
    } catch (const lw::core::Error& error) {
        std::printf("SKIP: no headless OpenGL context: %s\n", error.what());
        return LINEWORK_SKIP_CODE;
    }
    const int result = RUN_ALL_TESTS();
    g_context.reset();
    return result;
}
