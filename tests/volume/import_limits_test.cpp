// Issue 10: the volume readers check what a header declares against core::ImportLimits before
// they allocate, and gzip data may inflate only to what the header declares. The hostile
// inputs are made here at run time (a gzip bomb of zeros compresses ~1000:1).
#include "lw/core/error.h"
#include "lw/core/limits.h"
#include "lw/volume/oversampling.h"
#include "lw/volume/phantom.h"
#include "lw/volume/slice_distance.h"
#include "lw/volume/volume_reader.h"
#include "test_support.h"
#include "volume_test_checks.h"
#include "volume_test_files.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <gtest/gtest.h>

namespace lw::volume {
namespace {

using namespace testfiles;

constexpr std::size_t kBomb = std::size_t(64) << 20; // 64 MB of zeros after the header

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

NiftiSpec smallSpec() {
    NiftiSpec spec;
    spec.dims = {64, 64, 64}; // 512 KB of int16 declared
    return spec;
}

TEST(VolumeImportLimits, NiftiGzipBombStopsAtTheDeclaredSize) {
    test::TempDir dir;
    const Bytes file = gzipBytes(concat(niftiHeader(smallSpec()), Bytes(kBomb, 0)));
    ASSERT_LT(file.size(), kBomb / 100);
    writeFile(dir / "bomb.nii.gz", file);
    const auto start = std::chrono::steady_clock::now();
    expectError([&] { (void)readNifti(dir / "bomb.nii.gz"); }, "inflates to more than");
    EXPECT_LT(secondsSince(start), 0.5);
    // The same header with exactly its data still reads.
    writeFile(dir / "ok.nii.gz",
              gzipBytes(concat(niftiHeader(smallSpec()), Bytes(64 * 64 * 64 * 2, 0))));
    EXPECT_EQ(readNifti(dir / "ok.nii.gz").dims(), glm::ivec3(64, 64, 64));
}

TEST(VolumeImportLimits, NrrdGzipBombStopsAtTheDeclaredSize) {
    test::TempDir dir;
    const std::string header =
        "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 64 64 64\nencoding: gzip\n\n";
    writeFile(dir / "bomb.nrrd", concat(toBytes(header), gzipBytes(Bytes(kBomb, 0))));
    const auto start = std::chrono::steady_clock::now();
    expectError([&] { (void)readNrrd(dir / "bomb.nrrd"); }, "inflates to more than");
    EXPECT_LT(secondsSince(start), 0.5);
}

TEST(VolumeImportLimits, DeclaredSizeOverTheLimitIsRefusedFromTheHeader) {
    test::TempDir dir;
    NiftiSpec spec;
    spec.dims = {32767, 32767, 32767};
    spec.datatype = 64; // float64: 281 TB declared, 352 bytes present
    spec.bitpix = 64;
    writeFile(dir / "huge.nii", niftiHeader(spec));
    expectError([&] { (void)readNifti(dir / "huge.nii"); },
                "is more than the limit of " +
                    core::byteSizeText(core::ImportLimits::defaultMaxBytes()) +
                    " (half this machine's memory)");

    // The limit is the caller's: the same small file is refused under a smaller one.
    writeFile(dir / "small.nii", concat(niftiHeader(smallSpec()), Bytes(64 * 64 * 64 * 2, 0)));
    core::ImportLimits limits;
    limits.maxBytes = 100000;
    expectError([&] { (void)readVolumeFile(dir / "small.nii", nullptr, limits); },
                "the volume (64×64×64 int16) = 512.0 KiB is more than the limit of 97.7 KiB "
                "(as set)");
    EXPECT_NO_THROW((void)readNifti(dir / "small.nii"));

    const std::string nrrd =
        "NRRD0004\ntype: double\ndimension: 3\nsizes: 1048576 1048576 1048576\n"
        "encoding: raw\nendian: little\n\n";
    writeFile(dir / "overflow.nrrd", toBytes(nrrd));
    expectError([&] { (void)readNrrd(dir / "overflow.nrrd"); }, "is more than the limit of");
}

TEST(VolumeImportLimits, RawDimensionsAreCheckedBeforeReading) {
    test::TempDir dir;
    writeFile(dir / "data.raw", Bytes(1000, 0));
    RawOptions options;
    options.dims = {1 << 20, 1 << 20, 1 << 20};
    options.type = VoxelType::Float32;
    expectError([&] { (void)readRawVolume(dir / "data.raw", options); },
                "is more than the limit of");
}

// A detached NRRD header whose data file is a folder: reading a folder as a file makes the
// standard library throw std::length_error (its "size" is the largest offset), which must leave
// the reader as core::Error naming the file, never as the library's own type (issue 10).
TEST(VolumeImportLimits, LibraryExceptionsLeaveTheReadersAsCoreError) {
    test::TempDir dir;
    std::filesystem::create_directories(dir / "folder.raw");
    writeFile(dir / "d.nhdr", toBytes("NRRD0004\ntype: uint8\ndimension: 3\nsizes: 2 2 2\n"
                                      "encoding: raw\ndata file: folder.raw\n\n"));
    for (const auto& read : {std::function<void()>([&] { (void)readNrrd(dir / "d.nhdr"); }),
                             std::function<void()>([&] { (void)readVolumeFile(dir / "d.nhdr"); }),
                             std::function<void()>([&] { (void)readNrrd(dir / "folder.raw"); }),
                             std::function<void()>([&] { (void)readPvm(dir / "folder.raw"); }),
                             std::function<void()>([&] { (void)readNifti(dir / "folder.raw"); })}) {
        try {
            read();
            ADD_FAILURE() << "a folder was read as volume data";
        } catch (const core::Error& error) {
            EXPECT_FALSE(error.reason().empty());
        } catch (const std::exception& escaped) {
            ADD_FAILURE() << "escaped: " << escaped.what();
        }
    }
}

// Issue 30: the volumes the engine makes itself -- the phantom, the finer copy, the shape-based
// field -- ask the limits before they allocate. 1 TiB is more than this machine could allocate:
// an attempt would end in std::bad_alloc (or the out-of-memory killer), not in core::Error.
TEST(VolumeImportLimits, VolumesMadeByTheEngineAreRefusedBeforeAllocating) {
    core::ImportLimits limits;
    limits.maxBytes = std::size_t(1) << 20;
    expectError(
        [&] {
            (void)makePhantom({8192, 8192, 8192}, PhantomKind::Ct, 0, limits);
        },
        "the phantom (8192×8192×8192 int16) = 1.0 TiB is more than the limit of 1.0 MiB "
        "(as set)");
    const Volume small({2, 2, 2}, VoxelType::Int16);
    expectError(
        [&] {
            (void)oversampled(small, {8192, 8192, 8192}, 0, SliceInterpolation::Linear, limits);
        },
        "the oversampled volume (8193×8193×8193 int16) = 1.0 TiB is more than the limit "
        "of 1.0 MiB");
    // The default limit (half the physical memory) refuses the same copy.
    expectError(
        [&] {
            (void)oversampled(small, {8192, 8192, 8192});
        },
        "(half this machine's memory)");
    Volume cube({64, 64, 64}, VoxelType::Int16);
    std::fill_n(cube.dataAs<std::int16_t>(), cube.voxelCount(), std::int16_t(0));
    limits.maxBytes = std::size_t(256) << 10;
    expectError([&] { (void)signedSliceDistance(cube, 0.5, 4.0, 0, limits); },
                "the signed-distance copy (64×64×64 int16) = 512.0 KiB is more than the limit of "
                "256.0 KiB");
    limits.maxBytes = std::size_t(512) << 10; // exactly the copy: made
    EXPECT_EQ(signedSliceDistance(cube, 0.5, 4.0, 0, limits).dims(), cube.dims());
    EXPECT_EQ(makePhantom({64, 64, 64}, PhantomKind::Ct, 0, limits).dims(), cube.dims());
}

} // namespace
} // namespace lw::volume
