// PVM reader: raw PVM/PVM2/PVM3 and DDS-compressed streams written by an independent encoder
// (volume_test_files.h), including the interleave (16-bit) and row-predictor paths.
#include "lw/core/error.h"
#include "lw/volume/volume_reader.h"
#include "test_support.h"
#include "volume_test_checks.h"
#include "volume_test_files.h"

#include <gtest/gtest.h>
#include <random>

namespace lw::volume {
namespace {

using namespace testfiles;
using namespace std::string_literals;

// Smooth-ish data with plateaus (zero residual runs) and noise (full-width runs).
Bytes pattern(std::size_t n, unsigned seed) {
    Bytes b(n);
    std::mt19937 rng(seed);
    for (std::size_t i = 0; i < n; ++i)
        b[i] = (i / 50) % 3 == 0 ? std::uint8_t(100) : std::uint8_t((i * 7 + rng() % 5) & 0xff);
    return b;
}

TEST(PvmReader, PlainPvmWithCommentsAndPvm2Scale) {
    test::TempDir dir;
    const Bytes voxels = pattern(5 * 4 * 3, 1);
    writeFile(dir / "a.pvm", concat(toBytes("PVM\n# a comment\n# another\n5 4 3\n1\n"), voxels));
    const Volume a = readPvm(dir / "a.pvm");
    ASSERT_EQ(a.dims(), glm::ivec3(5, 4, 3));
    ASSERT_EQ(a.voxelType(), VoxelType::UInt8);
    EXPECT_EQ(std::memcmp(a.data(), voxels.data(), voxels.size()), 0);
    EXPECT_EQ(a.geometry().spacing(), glm::dvec3(1.0));

    writeFile(dir / "b.pvm", concat(toBytes("PVM2\n5 4 3\n0.5 0.75 1.4\n1\n"), voxels));
    const Volume b = readVolumeFile(dir / "b.pvm");
    EXPECT_NEAR(b.geometry().spacing().x, 0.5, 1e-12);
    EXPECT_NEAR(b.geometry().spacing().y, 0.75, 1e-12);
    EXPECT_NEAR(b.geometry().spacing().z, 1.4, 1e-12);
}

TEST(PvmReader, Pvm3SixteenBitIsBigEndianAndKeepsDescription) {
    test::TempDir dir;
    std::vector<std::uint16_t> values(3 * 3 * 2);
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = std::uint16_t(i * 3001 + 5);
    Bytes file = concat(toBytes("PVM3\n3 3 2\n1 1 2\n2\n"), encode(values, true));
    for (const char* s : {"A description", "courtesy", "params", "comment"})
        file = concat(file, concat(toBytes(s), Bytes{0}));
    writeFile(dir / "c.pvm", file);
    const Volume v = readPvm(dir / "c.pvm");
    ASSERT_EQ(v.voxelType(), VoxelType::UInt16);
    for (std::size_t i = 0; i < values.size(); ++i)
        ASSERT_EQ(v.dataAs<std::uint16_t>()[i], values[i]);
    EXPECT_EQ(v.description(), "A description");
}

TEST(PvmReader, DdsCompressedMatchesRawForAllStreamVariants) {
    test::TempDir dir;
    const glm::ivec3 dims(17, 13, 9);
    const Bytes voxels = pattern(std::size_t(dims.x) * dims.y * dims.z, 2);
    const Bytes pvm = concat(toBytes("PVM2\n17 13 9\n1 1 1.4\n1\n"), voxels);
    for (unsigned strip : {1u, 17u, 221u, 65536u}) {
        for (const char* magic : {"DDS v3d\n", "DDS v3e\n"}) {
            SCOPED_TRACE(std::string(magic, 7) + " strip " + std::to_string(strip));
            writeFile(dir / "dds.pvm", concat(toBytes(magic), ddsEncode(pvm, 1, strip)));
            EXPECT_EQ(detectVolumeFormat(dir / "dds.pvm"), VolumeFormat::Pvm);
            const Volume v = readPvm(dir / "dds.pvm");
            ASSERT_EQ(v.dims(), dims);
            ASSERT_EQ(std::memcmp(v.data(), voxels.data(), voxels.size()), 0);
            EXPECT_NEAR(v.geometry().spacing().z, 1.4, 1e-12);
        }
    }
    // 16-bit data is interleaved with skip 2 (high bytes first, then low bytes).
    std::vector<std::uint16_t> values(6 * 5 * 4);
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = std::uint16_t(i * i * 13 + i);
    const Bytes pvm16 = concat(concat(toBytes("PVM3\n6 5 4\n1 1 1\n2\n"), encode(values, true)),
                               toBytes("hello\0\0\0\0"s));
    for (unsigned skip : {2u, 3u, 4u}) {
        writeFile(dir / "dds16.pvm", concat(toBytes("DDS v3d\n"), ddsEncode(pvm16, skip, 12)));
        const Volume v = readPvm(dir / "dds16.pvm");
        ASSERT_EQ(v.voxelType(), VoxelType::UInt16);
        for (std::size_t i = 0; i < values.size(); ++i)
            ASSERT_EQ(v.dataAs<std::uint16_t>()[i], values[i]) << "skip " << skip << " voxel " << i;
        EXPECT_EQ(v.description(), "hello");
    }
}

TEST(PvmReader, MalformedFilesAreErrors) {
    test::TempDir dir;
    const auto check = [&](const Bytes& bytes, const std::string& needle) {
        writeFile(dir / "bad.pvm", bytes);
        expectError([&] { readPvm(dir / "bad.pvm"); }, needle);
    };
    check(toBytes("PVX\n1 1 1\n1\nx"), "not a PVM file");
    check(toBytes("PVM\n2 2 2\n1\nabc"), "truncated volume data: 3 bytes, expected 8");
    check(toBytes("PVM\n2 2\n1\nabcdefgh"), "bad header line");
    check(toBytes("PVM\n2 0 2\n1\nabcdefgh"), "bad dimension");
    check(toBytes("PVM2\n2 2 2\n1 -1 1\n1\nabcdefgh"), "bad scale");
    check(toBytes("PVM2\n2 2 2\n1 1 1\n3\n" + std::string(24, 'x')), "3-component");
    check(toBytes("PVM2\n2 2 2\n1 1 1\nzero\n"), "bad component count");
    check(toBytes("PVM2\n2 2 2"), "header ends before");
    check(toBytes("PVM\n99999999 99999999 99999999\n1\n"), "bad dimension");
    check(toBytes("DDS v3d\n"), "DDS stream decodes to no data");
    check(toBytes("DDS v3d\n\xff\xff\xff\xff\xff\xff"), "not a PVM file");
}

TEST(PvmReader, CorruptDdsStreamsNeverCrash) {
    test::TempDir dir;
    const Bytes pvm = concat(toBytes("PVM2\n8 8 8\n1 1 1\n1\n"), pattern(512, 3));
    const Bytes good = concat(toBytes("DDS v3d\n"), ddsEncode(pvm, 1, 8));
    writeFile(dir / "ok.pvm", good);
    EXPECT_EQ(readPvm(dir / "ok.pvm").dims(), glm::ivec3(8));
    std::mt19937 rng(4);
    int errors = 0;
    for (int trial = 0; trial < 200; ++trial) {
        Bytes bad = good;
        if (trial % 2 == 0)
            bad.resize(8 + rng() % (good.size() - 8));
        else
            bad[8 + rng() % (good.size() - 8)] ^= std::uint8_t(1u << (rng() % 8));
        writeFile(dir / "bad.pvm", bad);
        try {
            readPvm(dir / "bad.pvm");
        } catch (const core::Error&) {
            ++errors;
        }
    }
    EXPECT_GT(errors, 0);
}

} // namespace
} // namespace lw::volume
