// Raw and NRRD readers, writeNrrd and format detection, on files the tests write.
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

constexpr double kTolerance = 1e-9;

std::vector<std::int16_t> rampInt16(std::size_t n) {
    std::vector<std::int16_t> v(n);
    for (std::size_t i = 0; i < n; ++i)
        v[i] = std::int16_t(int(i) * 37 - 500);
    return v;
}

template <typename T> void expectVoxels(const Volume& volume, const std::vector<T>& expected) {
    ASSERT_EQ(volume.voxelType(), voxelTypeOf<T>());
    ASSERT_EQ(volume.voxelCount(), expected.size());
    const T* p = volume.dataAs<T>();
    for (std::size_t i = 0; i < expected.size(); ++i)
        ASSERT_EQ(p[i], expected[i]) << "voxel " << i;
}

// ---------------------------------------------------------------- raw

TEST(RawReader, LittleEndianWithHeaderSkipAndSpacing) {
    test::TempDir dir;
    const auto values = rampInt16(5 * 4 * 3);
    writeFile(dir / "v.raw", concat(Bytes(10, 0xAB), encode(values, false)));
    RawOptions o;
    o.dims = {5, 4, 3};
    o.type = VoxelType::Int16;
    o.headerBytes = 10;
    o.spacing = {0.5, 0.6, 2.0};
    const Volume v = readRawVolume(dir / "v.raw", o);
    EXPECT_EQ(v.dims(), glm::ivec3(5, 4, 3));
    expectVoxels(v, values);
    expectNear(v.geometry().spacing(), {0.5, 0.6, 2.0}, kTolerance);
}

TEST(RawReader, BigEndianUInt16AndFloat) {
    test::TempDir dir;
    std::vector<std::uint16_t> u(2 * 3 * 4);
    for (std::size_t i = 0; i < u.size(); ++i)
        u[i] = std::uint16_t(1000 * i + 7);
    writeFile(dir / "u.raw", encode(u, true));
    RawOptions o;
    o.dims = {2, 3, 4};
    o.type = VoxelType::UInt16;
    o.bigEndian = true;
    expectVoxels(readRawVolume(dir / "u.raw", o), u);

    std::vector<float> f = {1.5f, -2.25f, 1e6f, 0.0f, 3.0f, -0.0f, 7.75f, 8.0f};
    writeFile(dir / "f.raw", encode(f, true));
    o.dims = {2, 2, 2};
    o.type = VoxelType::Float32;
    expectVoxels(readRawVolume(dir / "f.raw", o), f);
    o.bigEndian = false;
    writeFile(dir / "f.raw", encode(f, false));
    expectVoxels(readRawVolume(dir / "f.raw", o), f);
}

TEST(RawReader, WrongSizeNamesBothSizes) {
    test::TempDir dir;
    writeFile(dir / "short.raw", Bytes(1000, 0));
    RawOptions o;
    o.dims = {64, 64, 93};
    o.type = VoxelType::Int16;
    expectError([&] { readRawVolume(dir / "short.raw", o); },
                "file has 1000 bytes, expected 761856 for 64x64x93 int16");
    o.dims = {10, 10, 10};
    o.type = VoxelType::UInt8;
    EXPECT_EQ(readRawVolume(dir / "short.raw", o).voxelCount(), 1000u); // exact fit
    o.headerBytes = 1;
    expectError([&] { readRawVolume(dir / "short.raw", o); }, "expected 1001");
    o.dims = {0, 10, 10};
    expectError([&] { readRawVolume(dir / "short.raw", o); }, "implausible size along x 0");
    o.dims = {10, 10, 10};
    expectError([&] { readRawVolume(dir / "missing.raw", o); }, "missing.raw");
}

// ---------------------------------------------------------------- NRRD

std::string nrrdHeader(const std::string& fields) {
    return "NRRD0004\n# test\n" + fields + "\n";
}

TEST(NrrdReader, AttachedRawWithSpaceDirectionsAndOrigin) {
    test::TempDir dir;
    const auto values = rampInt16(4 * 3 * 2);
    const std::string h =
        nrrdHeader("type: short\ndimension: 3\nspace: left-posterior-superior\n"
                   "sizes: 4 3 2\nspace directions: (0.5,0,0) (0,0.75,0) (0,0,2.5)\n"
                   "space origin: (-10,20.5,30)\nendian: little\nencoding: raw\n"
                   "content: test volume\nkey:=value with: colon\n");
    writeFile(dir / "a.nrrd", concat(toBytes(h), encode(values, false)));
    const Volume v = readNrrd(dir / "a.nrrd");
    expectVoxels(v, values);
    expectNear(v.geometry().spacing(), {0.5, 0.75, 2.5}, kTolerance);
    expectNear(v.geometry().origin(), {-10, 20.5, 30}, kTolerance);
    expectNear(v.geometry().indexToPatient({1, 2, 1}), {-9.5, 22.0, 32.5}, kTolerance);
    EXPECT_EQ(v.description(), "test volume");
    // Same through the dispatcher.
    EXPECT_EQ(detectVolumeFormat(dir / "a.nrrd"), VolumeFormat::Nrrd);
    expectVoxels(readVolumeFile(dir / "a.nrrd"), values);
}

TEST(NrrdReader, RasSpaceIsConvertedToLps) {
    test::TempDir dir;
    const std::string h = nrrdHeader("type: uchar\ndimension: 3\nspace: RAS\nsizes: 2 2 2\n"
                                     "space directions: (2,0,0) (0,3,0) (0,0,4)\n"
                                     "space origin: (1,2,3)\nencoding: raw\n");
    writeFile(dir / "ras.nrrd", concat(toBytes(h), Bytes{0, 1, 2, 3, 4, 5, 6, 7}));
    const Volume v = readNrrd(dir / "ras.nrrd");
    expectNear(v.geometry().origin(), {-1, -2, 3}, kTolerance);
    expectNear(v.geometry().axisI(), {-1, 0, 0}, kTolerance);
    expectNear(v.geometry().axisJ(), {0, -1, 0}, kTolerance);
    expectNear(v.geometry().stackAxis(), {0, 0, 1}, kTolerance);
    expectNear(v.geometry().spacing(), {2, 3, 4}, kTolerance);
    EXPECT_EQ(v.storedValue(1, 1, 1), 7);
}

TEST(NrrdReader, GzipBigEndianFloatAndSpacings) {
    test::TempDir dir;
    std::vector<float> values(3 * 3 * 3);
    for (std::size_t i = 0; i < values.size(); ++i)
        values[i] = float(i) * 0.5f - 3.0f;
    const std::string h =
        nrrdHeader("type: float\ndimension: 3\nsizes: 3 3 3\nspacings: 1.25 NaN 3\n"
                   "endian: big\nencoding: gzip\n");
    writeFile(dir / "g.nrrd", concat(toBytes(h), gzipBytes(encode(values, true))));
    const Volume v = readNrrd(dir / "g.nrrd");
    expectVoxels(v, values);
    expectNear(v.geometry().spacing(), {1.25, 1.0, 3.0}, kTolerance); // NaN: unknown -> 1
}

TEST(NrrdReader, TypeSpellingsAndConversions) {
    test::TempDir dir;
    const auto write = [&](const std::string& type, const Bytes& data,
                           const std::string& endian = "little") {
        writeFile(dir / "t.nrrd", concat(toBytes(nrrdHeader("type: " + type +
                                                            "\ndimension: 3\nsizes: 2 1 2\n"
                                                            "endian: " +
                                                            endian + "\nencoding: raw\n")),
                                         data));
        return readNrrd(dir / "t.nrrd");
    };
    for (const char* t : {"uchar", "uint8", "unsigned char", "uint8_t"})
        expectVoxels(write(t, {1, 2, 250, 4}), std::vector<std::uint8_t>{1, 2, 250, 4});
    const std::vector<std::int16_t> s = {-3, 2, 32767, -32768};
    for (const char* t : {"short", "int16", "signed short", "short int"})
        expectVoxels(write(t, encode(s, false)), s);
    const std::vector<std::uint16_t> u = {0, 65535, 1, 4095};
    for (const char* t : {"ushort", "uint16", "unsigned short"})
        expectVoxels(write(t, encode(u, true), "big"), u);
    // int8 widens to int16, double narrows to float.
    expectVoxels(write("signed char", {0xFF, 0x80, 0x7F, 0x00}),
                 std::vector<std::int16_t>{-1, -128, 127, 0});
    expectVoxels(write("double", encode(std::vector<double>{0.5, -1.0, 1e3, 2.25}, false)),
                 std::vector<float>{0.5f, -1.0f, 1e3f, 2.25f});
    expectError([&] { write("complex", {0, 0, 0, 0}); }, "unsupported NRRD type 'complex'");
}

TEST(NrrdReader, DetachedSingleFileWithLineAndByteSkip) {
    test::TempDir dir;
    std::filesystem::create_directories(dir / "data");
    const auto values = rampInt16(3 * 2 * 2);
    writeFile(dir / "data" / "vol.bin",
              concat(toBytes("line one\nline two\nXXXX"), encode(values, false)));
    writeFile(dir / "d.nhdr",
              toBytes(nrrdHeader("type: int16\ndimension: 3\nsizes: 3 2 2\nendian: little\n"
                                 "encoding: raw\nline skip: 2\nbyte skip: 4\n"
                                 "data file: data/vol.bin\n")));
    expectVoxels(readNrrd(dir / "d.nhdr"), values);
    EXPECT_EQ(detectVolumeFormat(dir / "d.nhdr"), VolumeFormat::Nrrd);

    // byte skip -1: the data is the tail of the file.
    writeFile(dir / "data" / "tail.bin", concat(Bytes(13, 0x55), encode(values, false)));
    writeFile(dir / "t.nhdr",
              toBytes(nrrdHeader("type: int16\ndimension: 3\nsizes: 3 2 2\nendian: little\n"
                                 "encoding: raw\nbyte skip: -1\ndatafile: data/tail.bin\n")));
    expectVoxels(readNrrd(dir / "t.nhdr"), values);
}

TEST(NrrdReader, DetachedListOfGzipSlices) {
    test::TempDir dir;
    const auto values = rampInt16(4 * 2 * 3);
    std::string list;
    for (int z = 0; z < 3; ++z) {
        const std::vector<std::int16_t> slice(values.begin() + z * 8, values.begin() + (z + 1) * 8);
        const std::string name = "slice_" + std::to_string(z) + ".raw.gz";
        writeFile(dir / name, gzipBytes(encode(slice, true)));
        list += name + "\n";
    }
    writeFile(dir / "l.nhdr",
              toBytes("NRRD0005\ntype: short\ndimension: 3\nsizes: 4 2 3\nendian: big\n"
                      "encoding: gz\ndata file: LIST\n" +
                      list));
    expectVoxels(readNrrd(dir / "l.nhdr"), values);

    // LIST with subdim 3: each file holds the whole volume, so there must be exactly one.
    writeFile(dir / "l3.nhdr",
              toBytes("NRRD0005\ntype: short\ndimension: 3\nsizes: 4 2 3\nendian: big\n"
                      "encoding: gz\ndata file: LIST 3\n" +
                      list));
    expectError([&] { readNrrd(dir / "l3.nhdr"); }, "names 3 data files, expected 1");
}

TEST(NrrdReader, PrintfPatternWithStepAndSubdim) {
    test::TempDir dir;
    const auto values = rampInt16(2 * 2 * 4);
    // Files 010, 008, 006, 004 hold slices 0..3 (a descending pattern).
    for (int z = 0; z < 4; ++z) {
        const std::vector<std::int16_t> slice(values.begin() + z * 4, values.begin() + (z + 1) * 4);
        char name[32];
        std::snprintf(name, sizeof name, "img.%03d", 10 - 2 * z);
        writeFile(dir / name, encode(slice, false));
    }
    writeFile(dir / "p.nhdr",
              toBytes(nrrdHeader("type: short\ndimension: 3\nsizes: 2 2 4\nendian: little\n"
                                 "encoding: raw\ndata file: img.%03d 10 4 -2 2\n")));
    expectVoxels(readNrrd(dir / "p.nhdr"), values);

    writeFile(dir / "missing.nhdr", toBytes(nrrdHeader("type: short\ndimension: 3\nsizes: 2 2 4\n"
                                                       "endian: little\nencoding: raw\n"
                                                       "data file: img.%03d 10 4 -2\n")));
    std::filesystem::remove(dir / "img.006");
    expectError([&] { readNrrd(dir / "missing.nhdr"); }, "img.006");
}

TEST(NrrdReader, MalformedHeadersAndDataAreErrors) {
    test::TempDir dir;
    const auto check = [&](const std::string& text, const std::string& needle,
                           const Bytes& data = {}) {
        writeFile(dir / "bad.nrrd", concat(toBytes(text), data));
        expectError([&] { readNrrd(dir / "bad.nrrd"); }, needle);
    };
    const std::string ok = "type: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n";
    check("PNG\nfoo\n", "not a NRRD file");
    check(nrrdHeader("type: uchar\ndimension: 3\nsizes 2 2 2\nencoding: raw\n"),
          "bad header line 5");
    check(nrrdHeader("type: uchar\ndimension: 3\nencoding: raw\n"), "no 'sizes:'");
    check(nrrdHeader("type: uchar\ndimension: 4\nsizes: 2 2 2 2\nencoding: raw\n"), "dimension");
    check(nrrdHeader("type: uchar\ndimension: 3\nsizes: 2 2\nencoding: raw\n"),
          "'sizes' has 2 entries");
    check(nrrdHeader("type: uchar\ndimension: 3\nsizes: 2 -2 2\nencoding: raw\n"), "bad size '-2'");
    check(nrrdHeader(
              "type: uchar\ndimension: 3\nsizes: 100000000 100000000 100000000\nencoding: raw\n"),
          "implausible size along x 100000000");
    // 10 TB declared: refused from the header, before the data is looked at.
    check(nrrdHeader("type: uchar\ndimension: 3\nsizes: 100000 100000 1000\nencoding: raw\n"),
          "is more than the limit of");
    check(nrrdHeader(ok), "truncated data: 7 bytes, expected 8", Bytes(7, 1));
    check(nrrdHeader("type: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: bzip2\n"),
          "unsupported NRRD encoding");
    check(nrrdHeader("type: short\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n"), "no 'endian:'",
          Bytes(16, 0));
    check(nrrdHeader("type: uchar\ndimension: 3\nsizes: 2 2 2\nencoding: gzip\n"), "bad.nrrd",
          Bytes{0x1f, 0x8b, 8, 0, 1, 2, 3, 4, 5, 6, 7, 8});
    check(nrrdHeader(ok + "space directions: (1,0,0) (0,1,0)\n"),
          "'space directions' has 2 entries", Bytes(8, 0));
    check(nrrdHeader(ok + "space directions: (1,0) (0,1,0) (0,0,1)\n"), "3 components",
          Bytes(8, 0));
    check(nrrdHeader(ok + "space directions: (1,0,0) (0,x,0) (0,0,1)\n"), "not a number",
          Bytes(8, 0));
    check(nrrdHeader(ok + "space directions: (1,0,0) (0,0,0) (0,0,1)\n"), "zero vector",
          Bytes(8, 0));
    check(nrrdHeader(ok + "space origin: (1,0,0\n"), "missing ')'", Bytes(8, 0));
    check(nrrdHeader(ok + "data file: nothere.raw\n"), "nothere.raw");
    check(nrrdHeader(ok + "data file: LIST\n"), "no file names");
    check(nrrdHeader(ok + "data file: f.%d 1 x 1\n"), "bad data file pattern");
    check(nrrdHeader(ok + "data file: f.%s 1 2 1\n"), "must use %d");
    check(nrrdHeader(ok + "line skip: 50\ndata file: bad.nrrd\n"), "lines to skip");
    writeFile(dir / "nodata.nhdr", toBytes(nrrdHeader(ok)));
    expectError([&] { readNrrd(dir / "nodata.nhdr"); }, "without a 'data file:'");
}

TEST(NrrdReader, TruncatedAndCorruptedFilesNeverCrash) {
    test::TempDir dir;
    const auto values = rampInt16(4 * 4 * 4);
    const Bytes good = concat(toBytes(nrrdHeader("type: short\ndimension: 3\nsizes: 4 4 4\n"
                                                 "space directions: (1,0,0) (0,1,0) (0,0,1)\n"
                                                 "endian: little\nencoding: gzip\n")),
                              gzipBytes(encode(values, false)));
    writeFile(dir / "ok.nrrd", good);
    expectVoxels(readNrrd(dir / "ok.nrrd"), values);
    int errors = 0;
    for (std::size_t cut = 0; cut < good.size(); ++cut) {
        writeFile(dir / "cut.nrrd", Bytes(good.begin(), good.begin() + std::ptrdiff_t(cut)));
        try {
            readNrrd(dir / "cut.nrrd");
        } catch (const core::Error&) {
            ++errors;
        }
    }
    EXPECT_EQ(errors, int(good.size())) << "every truncation must be reported";
    std::mt19937 rng(5);
    for (int trial = 0; trial < 150; ++trial) {
        Bytes bad = good;
        for (int flips = 0; flips < 3; ++flips)
            bad[rng() % bad.size()] ^= std::uint8_t(1u << (rng() % 8));
        writeFile(dir / "flip.nrrd", bad);
        try {
            readNrrd(dir / "flip.nrrd");
        } catch (const core::Error&) {
        }
    }
}

// ---------------------------------------------------------------- writeNrrd

TEST(WriteNrrd, RoundTripKeepsVoxelsGeometryAndMapping) {
    test::TempDir dir;
    for (VoxelType type :
         {VoxelType::UInt8, VoxelType::Int16, VoxelType::UInt16, VoxelType::Float32}) {
        const double t = 0.3;
        Volume v({5, 4, 3}, type,
                 VolumeGeometry::regular({-12.5, 40.25, 7}, {0.7, 0.8, 2.5},
                                         {std::cos(t), std::sin(t), 0},
                                         {-std::sin(t), std::cos(t), 0}, {0, 0, 1}));
        dispatchVoxelType(type, [&](auto tag) {
            using T = decltype(tag);
            T* p = v.dataAs<T>();
            for (std::size_t i = 0; i < v.voxelCount(); ++i)
                p[i] = T(int(i * 3) % 120 + (std::is_signed_v<T> ? -40 : 0));
        });
        v.setValueMapping({0.5, -1024});
        v.setDescription("round\ntrip");
        writeNrrd(dir / "rt.nrrd", v);
        const Volume r = readNrrd(dir / "rt.nrrd");
        ASSERT_EQ(r.voxelType(), type);
        ASSERT_EQ(r.dims(), v.dims());
        EXPECT_EQ(std::memcmp(r.data(), v.data(), v.byteSize()), 0);
        for (double i : {0.0, 4.0})
            for (double k : {0.0, 2.0})
                expectNear(r.geometry().indexToPatient({i, 3, k}),
                           v.geometry().indexToPatient({i, 3, k}), 1e-12);
        EXPECT_DOUBLE_EQ(r.valueMapping().slope, 0.5);
        EXPECT_DOUBLE_EQ(r.valueMapping().intercept, -1024);
        EXPECT_EQ(r.description(), "round trip");
    }
    // Nothing left behind but the target.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
    EXPECT_THROW(writeNrrd(dir / "no" / "such" / "dir.nrrd", Volume({1, 1, 1}, VoxelType::UInt8)),
                 core::Error);
}

TEST(WriteNrrd, UnevenSlicesAreWrittenWithTheMeanStep) {
    test::TempDir dir;
    Volume v({2, 2, 3}, VoxelType::UInt8,
             VolumeGeometry::fromSlicePositions({1, 0, 0}, {0, 1, 0}, 1, 1,
                                                {{0, 0, 0}, {0, 0, 1}, {0, 0, 5}}));
    std::memset(v.data(), 9, v.byteSize());
    writeNrrd(dir / "u.nrrd", v);
    const Volume r = readNrrd(dir / "u.nrrd");
    EXPECT_NEAR(r.geometry().sliceStep(), 2.5, 1e-12);
}

// ---------------------------------------------------------------- dispatch

TEST(VolumeReader, DetectionByMagicAndExtension) {
    test::TempDir dir;
    writeFile(dir / "renamed.dat",
              toBytes(nrrdHeader("type: uchar\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n")));
    EXPECT_EQ(detectVolumeFormat(dir / "renamed.dat"), VolumeFormat::Nrrd);
    writeFile(dir / "p.dat", toBytes("PVM2\n1 1 1\n1 1 1\n1\nx"));
    EXPECT_EQ(detectVolumeFormat(dir / "p.dat"), VolumeFormat::Pvm);
    writeFile(dir / "d.dat", toBytes("DDS v3e\n"));
    EXPECT_EQ(detectVolumeFormat(dir / "d.dat"), VolumeFormat::Pvm);
    EXPECT_EQ(detectVolumeFormat(dir / "x.nii.gz"), VolumeFormat::Nifti);
    EXPECT_EQ(detectVolumeFormat(dir / "x.HDR"), VolumeFormat::Nifti);
    EXPECT_EQ(detectVolumeFormat(dir / "x.pvm"), VolumeFormat::Pvm);
    EXPECT_EQ(detectVolumeFormat(dir / "x.nhdr"), VolumeFormat::Nrrd);
    writeFile(dir / "x.raw", Bytes(100, 0));
    EXPECT_EQ(detectVolumeFormat(dir / "x.raw"), VolumeFormat::Unknown); // raw is never guessed
    expectError([&] { readVolumeFile(dir / "x.raw"); }, "unknown volume format");
    expectError([&] { readVolumeFile(dir / "absent.nrrd"); }, "does not exist");
    expectError([&] { readVolumeFile(dir.path()); }, "folder");
}

TEST(VolumeReader, ProgressAndCancellation) {
    test::TempDir dir;
    writeFile(
        dir / "one.nrrd",
        concat(toBytes(nrrdHeader("type: uchar\ndimension: 3\nsizes: 1 1 1\nencoding: raw\n")),
               Bytes{42}));
    double last = -1;
    core::Progress progress([&](double f, const std::string&) { last = f; });
    const Volume v = readVolumeFile(dir / "one.nrrd", &progress);
    EXPECT_EQ(v.storedValue(0, 0, 0), 42);
    EXPECT_DOUBLE_EQ(last, 1.0);
    auto token = std::make_shared<core::CancelToken>();
    token->cancel();
    core::Progress cancelled([](double, const std::string&) {}, token);
    EXPECT_THROW(readVolumeFile(dir / "one.nrrd", &cancelled), core::Cancelled);
}

} // namespace
} // namespace lw::volume
