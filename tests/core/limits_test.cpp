// ImportLimits and checked arithmetic: the one place every reader asks before it allocates.
#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "lw/core/limits.h"

#include <algorithm>
#include <chrono>
#include <gtest/gtest.h>
#include <limits>
#include <vector>
#include <zlib.h>

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
    EXPECT_THROW(limits.checkDimension(1 << 21, "f.nii", "dim[1]"), Error);
    EXPECT_NO_THROW(limits.checkDimension(512, "f.nii", "dim[1]"));
}

TEST(ImportLimits, ByteSizesReadInBinaryUnits) {
    EXPECT_EQ(byteSizeText(12), "12 bytes");
    EXPECT_EQ(byteSizeText(3584), "3.5 KiB");
    EXPECT_EQ(byteSizeText(std::size_t(1) << 20), "1.0 MiB");
    EXPECT_EQ(byteSizeText(std::size_t(8) << 30), "8.0 GiB");
    EXPECT_EQ(byteSizeText(std::size_t(1) << 40), "1.0 TiB");
}

// Issue 30: a refused volume names its shape, its size and the limit with where it comes from.
TEST(ImportLimits, VolumeRefusalNamesTheSizeAndTheLimit) {
    ImportLimits limits;
    EXPECT_EQ(limits.describeLimit(), "the limit of " +
                                          byteSizeText(ImportLimits::defaultMaxBytes()) +
                                          " (half this machine's memory)");
    limits.maxBytes = std::size_t(1) << 20;
    limits.raiseHint = "--max-volume-gib raises it";
    EXPECT_EQ(limits.checkedVolumeBytes(512, 512, 2, 2, "int16", "f", "the volume"), std::size_t(1)
                                                                                         << 20);
    try {
        (void)limits.checkedVolumeBytes(1024, 1024, 4096, 2, "int16", "ct.nrrd", "the volume");
        FAIL() << "limit not enforced";
    } catch (const Error& error) {
        EXPECT_EQ(error.subject(), "ct.nrrd");
        EXPECT_EQ(error.reason(), "the volume (1024×1024×4096 int16) = 8.0 GiB is more than the "
                                  "limit of 1.0 MiB (as set; --max-volume-gib raises it)");
    }
    EXPECT_NO_THROW(limits.checkAllocation(std::size_t(1) << 20, "a mesh", "f", "the mesh"));
    EXPECT_THROW(limits.checkAllocation((std::size_t(1) << 20) + 1, "a mesh", "f", "the mesh"),
                 Error);
}

TEST(ImportLimits, InflateBoundIsTheExpectedSizePlusASmallMargin) {
    EXPECT_EQ(inflateBound(0), std::size_t(1) << 20);
    EXPECT_EQ(inflateBound(std::size_t(1) << 30), (std::size_t(1) << 30) + (std::size_t(1) << 24));
    EXPECT_EQ(inflateBound(std::numeric_limits<std::size_t>::max() - 5),
              std::numeric_limits<std::size_t>::max());
}

namespace {

// `inflated` zero bytes as one gzip member, compressed piecewise (a bomb: ~1000:1).
std::vector<std::byte> gzipZeros(std::size_t inflated) {
    z_stream stream{};
    EXPECT_EQ(deflateInit2(&stream, Z_BEST_SPEED, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY),
              Z_OK);
    const std::vector<unsigned char> zeros(1 << 20, 0);
    std::vector<std::byte> out;
    std::vector<unsigned char> buffer(1 << 16);
    std::size_t left = inflated;
    int flush = Z_NO_FLUSH;
    do {
        const std::size_t piece = std::min(left, zeros.size());
        stream.next_in = const_cast<unsigned char*>(zeros.data());
        stream.avail_in = uInt(piece);
        left -= piece;
        flush = left == 0 ? Z_FINISH : Z_NO_FLUSH;
        do {
            stream.next_out = buffer.data();
            stream.avail_out = uInt(buffer.size());
            deflate(&stream, flush);
            const std::size_t have = buffer.size() - stream.avail_out;
            const auto* bytes = reinterpret_cast<const std::byte*>(buffer.data());
            out.insert(out.end(), bytes, bytes + have);
        } while (stream.avail_out == 0);
    } while (flush != Z_FINISH);
    deflateEnd(&stream);
    return out;
}

} // namespace

TEST(BoundedGunzip, StopsAGzipBombRightAfterTheDeclaredSize) {
    const std::vector<std::byte> bomb = gzipZeros(std::size_t(64) << 20); // 64 MB of zeros
    ASSERT_LT(bomb.size(), std::size_t(1) << 20);
    const std::size_t declared = std::size_t(1) << 20;
    const auto start = std::chrono::steady_clock::now();
    try {
        (void)gunzip(bomb.data(), bomb.size(), "bomb.nii.gz", inflateBound(declared));
        FAIL() << "the bomb was inflated";
    } catch (const Error& error) {
        EXPECT_EQ(error.subject(), "bomb.nii.gz");
        EXPECT_NE(error.reason().find("inflates to more than"), std::string::npos)
            << error.reason();
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 0.5); // only ~2 MB are inflated, not 64 MB

    const auto prefix = gunzipPrefix(bomb.data(), bomb.size(), "bomb.nii.gz", 348);
    EXPECT_EQ(prefix.size(), 348u);
    const auto exact = gunzip(bomb.data(), bomb.size(), "bomb.nii.gz", std::size_t(64) << 20);
    EXPECT_EQ(exact.size(), std::size_t(64) << 20);
}
