// gtest main for Linework. Error-level log messages fail the running test (DESIGN.md: errors at
// error level fail tests). With LINEWORK_TEST_REQUIRES_DATA the binary exits with the SKIP code
// when ../shared/data is missing. GL tests use gtest_main_gl.cpp instead.
#include "test_support.h"

#include <gtest/gtest.h>

#include <cstdio>

int main(int argc, char** argv) {
    testing::InitGoogleTest(&argc, argv);
#ifdef LINEWORK_TEST_REQUIRES_DATA
    if (!lw::test::sharedDataDir()) {
        std::puts("SKIP: ../shared/data not found (set LINEWORK_SHARED_DATA)");
        return LINEWORK_SKIP_CODE;
    }
#endif
    lw::test::installFailingLogSink();
    return RUN_ALL_TESTS();
}
