// ImportLimits and checked arithmetic: the one place every reader asks before it allocates.
#include "lw/core/error.h"
#include "lw/core/limits.h"

#include <gtest/gtest.h>
#include <limits>

using namespace lw::core;

TEST(ImportLimits, DefaultIsAFractionOfPhysicalMemory) {
    const ImportLimits limits;
    EXPECT_GT(limits.maxBytes, std::size_t(64) << 20);
    EXPECT_EQ(limits.maxBytes, ImportLimits::defaultMaxBytes()); // computed once, the same
}

TEST(ImportLimits, CheckedProductReportsOverflowWithTheShape) {
    EXPECT_EQ(checkedProduct({512, 512, 300, 2}, "f", "volume"), std::size_t(512) * 512 * 300 * 2);
    const std::size_t huge = std::numeric_limits<std::size_t>::max() / 2;
    try {
        (void)checkedProduct({huge, 3}, "f.nrrd", "volume");
        FAIL() << "overflow not detected";
    } catch (const Error& error) {
        EXPECT_EQ(error.subject(), "f.nrrd");
        EXPECT_NE(error.reason().find("overflows"), std::string::npos) << error.reason();
    }
}

TEST(ImportLimits, BytesFramesAndDimensionsAreCheckedWithTheReason) {
    ImportLimits limits;
    limits.maxBytes = 1 << 20;
    EXPECT_EQ(limits.checkedBytes({512, 512, 2}, "f", "volume"), std::size_t(512) * 1024);
    try {
        (void)limits.checkedBytes({1024, 1024, 2}, "f.dcm", "pixel data");
        FAIL() << "limit not enforced";
    } catch (const Error& error) {
        EXPECT_NE(error.reason().find("pixel data needs 2 MB, more than the import limit of 1 MB"),
                  std::string::npos)
            << error.reason();
    }
    EXPECT_THROW(limits.checkFrames(2147483647, "f.dcm"), Error);
    EXPECT_THROW(limits.checkFrames(0, "f.dcm"), Error);
    EXPECT_NO_THROW(limits.checkFrames(1000, "f.dcm"));
    EXPECT_THROW(limits.checkDimension(-5, "f.nii", "dim[1]"), Error);
    EXPECT_THROW(limits.checkDimension(1 << 20, "f.nii", "dim[1]"), Error);
    EXPECT_NO_THROW(limits.checkDimension(512, "f.nii", "dim[1]"));
}

TEST(ImportLimits, InflateBoundIsTheExpectedSizePlusASmallMargin) {
    EXPECT_EQ(inflateBound(0), std::size_t(1) << 20);
    EXPECT_EQ(inflateBound(std::size_t(1) << 30), (std::size_t(1) << 30) + (std::size_t(1) << 24));
    EXPECT_EQ(inflateBound(std::numeric_limits<std::size_t>::max() - 5),
              std::numeric_limits<std::size_t>::max());
}
