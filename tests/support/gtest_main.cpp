// gtest main for Linework. Error-level log messages fail the running test (an error logged is a
// failure, even where the code goes on). With LINEWORK_TEST_REQUIRES_DATA the binary exits with the SKIP code
// when ../shared/data is missing, with LINEWORK_TEST_REQUIRES_CUDA when no CUDA device is present.
// GL tests use gtest_main_gl.cpp instead. Any of them exits with the SKIP code when a program named
// in the environment variable LINEWORK_TEST_REQUIRES_TOOLS (space separated, e.g. "pdftotext
// pdftoppm") is not on PATH.
#include "test_support.h"

#include <cstdio>
#include <cstdlib>
#include <gtest/gtest.h>
#include <string>

#ifdef LINEWORK_TEST_REQUIRES_CUDA
#include "lw/render/renderer_factory.h"
#endif

int main(int argc, char** argv) {
    testing::InitGoogleTest(&argc, argv);
#ifdef LINEWORK_TEST_REQUIRES_DATA
    if (!lw::test::sharedDataDir()) {
        std::puts("SKIP: ../shared/data not found (set LINEWORK_SHARED_DATA)");
        return LINEWORK_SKIP_CODE;
    }
#endif
#ifdef LINEWORK_TEST_REQUIRES_CUDA
    const lw::render::CudaAvailability cuda = lw::render::cudaAvailability();
    if (!cuda.available) {
        std::printf("SKIP: %s\n", cuda.reason.c_str());
        return LINEWORK_SKIP_CODE;
    }
    std::printf("CUDA device: %s\n", cuda.deviceName.c_str());
#endif
    if (const char* tools = std::getenv("LINEWORK_TEST_REQUIRES_TOOLS")) {
        const std::string missing = lw::test::firstMissingProgram(tools);
        if (!missing.empty()) {
            std::printf("SKIP: %s is not installed\n", missing.c_str());
            return LINEWORK_SKIP_CODE;
        }
    }
    lw::test::installFailingLogSink();
    return RUN_ALL_TESTS();
}
