// NIfTI-1 reader on files the tests write: byte orders, gzip, pairs, datatypes, scaling,
// sform/qform/pixdim geometry (RAS -> LPS) and malformed headers.
#include "lw/core/error.h"
#include "lw/volume/volume_reader.h"
#include "test_support.h"
#include "volume_test_checks.h"
#include "volume_test_files.h"

#include <cmath>
#include <gtest/gtest.h>
#include <random>

namespace lw::volume {
namespace {

using namespace testfiles;

constexpr double kTolerance = 1e-6;


std::vector<std::int16_t> ct(std::size_t n) {
    std::vector<std::int16_t> v(n);
    for (std::size_t i = 0; i < n; ++i)
        v[i] = std::int16_t(int(i % 50) * 60 - 1024);
    return v;
}

NiftiSpec sformSpec() {
    NiftiSpec spec;
    spec.dims = {4, 3, 2};
    spec.pixdim = {0.5f, 0.5f, 2.0f};
    spec.sformCode = 1;
    // RAS: i runs to the patient's left (-x), j anterior (+y), k superior, with offsets.
    const float rows[3][4] = {{-0.5f, 0, 0, 90}, {0, 0.5f, 0, -126}, {0, 0, 2.0f, -72}};
    std::memcpy(spec.srow, rows, sizeof rows);
    spec.sclSlope = 2.0f;
    spec.sclInter = -10.0f;
    return spec;
}

TEST(NiftiReader, SingleFileWithSformAndScaling) {
    test::TempDir dir;
    const NiftiSpec spec = sformSpec();
    const auto values = ct(24);
    writeFile(dir / "ct.nii", concat(niftiHeader(spec), encode(values, false)));
    const Volume v = readNifti(dir / "ct.nii");
    ASSERT_EQ(v.voxelType(), VoxelType::Int16);
    ASSERT_EQ(v.dims(), glm::ivec3(4, 3, 2));
    EXPECT_EQ(std::memcmp(v.data(), encode(values, false).data(), v.byteSize()), 0);
    expectNear(v.geometry().spacing(), {0.5, 0.5, 2.0}, kTolerance);
    // LPS = (-x, -y, z) of RAS.
    expectNear(v.geometry().origin(), {-90, 126, -72}, kTolerance);
    expectNear(v.geometry().axisI(), {1, 0, 0}, kTolerance);
    expectNear(v.geometry().axisJ(), {0, -1, 0}, kTolerance);
    expectNear(v.geometry().stackAxis(), {0, 0, 1}, kTolerance);
    expectNear(v.geometry().indexToPatient({2, 2, 1}), {-89, 125, -70}, kTolerance);
    EXPECT_DOUBLE_EQ(v.valueMapping().slope, 2.0);
    EXPECT_DOUBLE_EQ(v.valueMapping().intercept, -10.0);
    EXPECT_DOUBLE_EQ(v.realRange().min, 2.0 * -1024 - 10);
    EXPECT_EQ(v.description(), "synthetic");
    EXPECT_EQ(detectVolumeFormat(dir / "ct.nii"), VolumeFormat::Nifti);

    // The same bytes gzipped (.nii.gz) give the same volume.
    writeFile(dir / "ct.nii.gz", gzipBytes(concat(niftiHeader(spec), encode(values, false))));
    const Volume g = readVolumeFile(dir / "ct.nii.gz");
    EXPECT_EQ(std::memcmp(g.data(), v.data(), v.byteSize()), 0);
    expectNear(g.geometry().origin(), v.geometry().origin(), kTolerance);
}

TEST(NiftiReader, BigEndianUInt16WithQform) {
    test::TempDir dir;
    NiftiSpec spec;
    spec.bigEndian = true;
    spec.datatype = 512;
    spec.dims = {3, 2, 2};
    spec.pixdim = {0.8f, 0.9f, 3.0f};
    spec.qformCode = 1;
    spec.qfac = -1.0f;           // left-handed: k flips
    spec.quatern = {0, 0, 1.0f}; // 180 degrees about z: (x,y) -> (-x,-y)
    spec.qoffset = {10, 20, 30};
    spec.sclSlope = 0.0f; // 0: no scaling
    std::vector<std::uint16_t> values(12);
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = std::uint16_t(5000 * i + 1);
    writeFile(dir / "be.nii", concat(niftiHeader(spec), encode(values, true)));
    const Volume v = readNifti(dir / "be.nii");
    ASSERT_EQ(v.voxelType(), VoxelType::UInt16);
    for (std::size_t i = 0; i < values.size(); ++i)
        ASSERT_EQ(v.dataAs<std::uint16_t>()[i], values[i]);
    EXPECT_TRUE(v.valueMapping().isIdentity());
    expectNear(v.geometry().spacing(), {0.8, 0.9, 3.0}, kTolerance);
    // RAS axes (-1,0,0), (0,-1,0), (0,0,-1) -> LPS (1,0,0), (0,1,0), (0,0,-1).
    expectNear(v.geometry().axisI(), {1, 0, 0}, kTolerance);
    expectNear(v.geometry().axisJ(), {0, 1, 0}, kTolerance);
    expectNear(v.geometry().stackAxis(), {0, 0, -1}, kTolerance);
    expectNear(v.geometry().origin(), {-10, -20, 30}, kTolerance);
}

TEST(NiftiReader, PixdimOnlyGeometry) {
    test::TempDir dir;
    NiftiSpec spec;
    spec.datatype = 2;
    spec.bitpix = 8;
    spec.dims = {2, 2, 2};
    spec.pixdim = {1.5f, -2.0f, 4.0f}; // sign ignored for spacing
    writeFile(dir / "p.nii", concat(niftiHeader(spec), Bytes{1, 2, 3, 4, 5, 6, 7, 8}));
    const Volume v = readNifti(dir / "p.nii");
    expectNear(v.geometry().spacing(), {1.5, 2.0, 4.0}, kTolerance);
    expectNear(v.geometry().axisI(), {-1, 0, 0}, kTolerance);
    EXPECT_EQ(v.storedValue(1, 1, 1), 8);
}

TEST(NiftiReader, HdrImgPairAndGzippedImage) {
    test::TempDir dir;
    NiftiSpec spec = sformSpec();
    spec.pair = true;
    spec.datatype = 16;
    spec.bitpix = 32;
    std::vector<float> values(24);
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = float(i) * 1.5f - 7.0f;
    writeFile(dir / "pair.hdr", niftiHeader(spec));
    writeFile(dir / "pair.img", encode(values, false));
    for (const char* name : {"pair.hdr", "pair.img"}) {
        const Volume v = readVolumeFile(dir / name);
        ASSERT_EQ(v.voxelType(), VoxelType::Float32);
        for (std::size_t i = 0; i < values.size(); ++i)
            ASSERT_EQ(v.dataAs<float>()[i], values[i]);
        expectNear(v.geometry().origin(), {-90, 126, -72}, kTolerance);
    }
    std::filesystem::remove(dir / "pair.img");
    expectError([&] { readNifti(dir / "pair.hdr"); }, "pair.img");
    writeFile(dir / "pair.img.gz", gzipBytes(encode(values, false)));
    EXPECT_EQ(readNifti(dir / "pair.hdr").dataAs<float>()[3], values[3]);
}

TEST(NiftiReader, DatatypeConversions) {
    test::TempDir dir;
    NiftiSpec spec;
    spec.dims = {4, 1, 1};
    const auto read = [&](int datatype, const Bytes& data) {
        spec.datatype = datatype;
        writeFile(dir / "t.nii", concat(niftiHeader(spec), data));
        return readNifti(dir / "t.nii");
    };
    const Volume i8 = read(256, {0xFF, 0x80, 0x7F, 0x01});
    ASSERT_EQ(i8.voxelType(), VoxelType::Int16);
    EXPECT_EQ(i8.storedValue(0, 0, 0), -1);
    EXPECT_EQ(i8.storedValue(1, 0, 0), -128);
    const Volume f64 = read(64, encode(std::vector<double>{0.25, -3.5, 1e5, 2.0}, false));
    ASSERT_EQ(f64.voxelType(), VoxelType::Float32);
    EXPECT_EQ(f64.storedValue(1, 0, 0), -3.5);
    const Volume i32 = read(8, encode(std::vector<std::int32_t>{-1024, 70000, 0, 5}, false));
    ASSERT_EQ(i32.voxelType(), VoxelType::Float32);
    EXPECT_EQ(i32.storedValue(1, 0, 0), 70000.0);
    expectError([&] { read(128, Bytes(12, 0)); }, "unsupported NIfTI datatype 128");
    expectError([&] { read(1024, Bytes(32, 0)); }, "unsupported NIfTI datatype 1024");
}

TEST(NiftiReader, MalformedFilesAreErrors) {
    test::TempDir dir;
    const auto values = ct(24);
    const auto check = [&](const NiftiSpec& spec, const Bytes& data, const std::string& needle) {
        writeFile(dir / "bad.nii", concat(niftiHeader(spec), data));
        expectError([&] { readNifti(dir / "bad.nii"); }, needle);
    };
    const Bytes data = encode(values, false);
    NiftiSpec spec = sformSpec();
    check(spec, Bytes(data.begin(), data.end() - 1), "truncated image data: 47 bytes, expected 48");
    NiftiSpec s2 = spec;
    s2.sizeofHdr = 1234;
    check(s2, data, "not a NIfTI-1 file");
    s2 = spec;
    s2.sizeofHdr = 540;
    check(s2, data, "NIfTI-2");
    s2 = spec;
    s2.rank = 0;
    check(s2, data, "bad dim[0]");
    s2 = spec;
    s2.dims.y = -3;
    check(s2, data, "bad dim[2]");
    s2 = spec;
    s2.rank = 4;
    s2.extraDim = 2;
    check(s2, concat(data, data), "only single 3D volumes");
    s2 = spec;
    s2.voxOffset = 1e9f;
    check(s2, data, "bad vox_offset");
    s2 = spec;
    s2.voxOffset = 100.0f;
    check(s2, data, "bad vox_offset");
    writeFile(dir / "tiny.nii", Bytes(100, 0));
    expectError([&] { readNifti(dir / "tiny.nii"); }, "truncated NIfTI header");
    writeFile(dir / "junk.nii.gz", Bytes{0x1f, 0x8b, 8, 0, 9, 9, 9, 9, 9, 9, 9});
    expectError([&] { readNifti(dir / "junk.nii.gz"); }, "junk.nii.gz");
}

TEST(NiftiReader, TruncatedAndCorruptedFilesNeverCrash) {
    test::TempDir dir;
    const Bytes good = concat(niftiHeader(sformSpec()), encode(ct(24), false));
    int errors = 0;
    for (std::size_t cut = 0; cut < good.size(); ++cut) {
        writeFile(dir / "cut.nii", Bytes(good.begin(), good.begin() + std::ptrdiff_t(cut)));
        try {
            readNifti(dir / "cut.nii");
        } catch (const core::Error&) {
            ++errors;
        }
    }
    EXPECT_EQ(errors, int(good.size()));
    std::mt19937 rng(9);
    for (int trial = 0; trial < 300; ++trial) {
        Bytes bad = good;
        // Hit the header most of the time: that is where the decisions are made.
        for (int flips = 0; flips < 2; ++flips)
            bad[rng() % 352] ^= std::uint8_t(1u << (rng() % 8));
        writeFile(dir / "flip.nii", bad);
        try {
            readNifti(dir / "flip.nii");
        } catch (const core::Error&) {
        }
    }
}

} // namespace
} // namespace lw::volume
