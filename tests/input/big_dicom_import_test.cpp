// A photon-counting-CT-sized series (issue 30, item 4): 2048 axial slices of 1024x1024 int16,
// 0.2 mm apart -- 4 GiB of voxels -- written with the tests' DICOM writer and imported through
// input::openInput as the CLI and the GUI open a folder. The voxels are checked against what
// was written; slices per second and the peak resident memory (getrusage) are printed for
// docs/BENCHMARKS.md; only the memory is bounded (no second copy of the volume). Label `big`: it
// needs about 4.1 GiB on disk and about 4.2 GiB of memory (see tests/input/CMakeLists.txt), and
// SKIPs below 12 GiB of free disk. LINEWORK_BIG_IMPORT_SLICES (a whole number, default 2048) writes
// fewer slices for a quick look at the test itself.
#include "dicom_test_writer.h"
#include "lw/core/error.h"
#include "lw/input/open_input.h"
#include "test_support.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <thread>

namespace dt = lw::dicom::test;
namespace fs = std::filesystem;
using namespace lw;

namespace {

constexpr int kRows = 1024;
constexpr int kColumns = 1024;
constexpr double kSliceStepMm = 0.2;
constexpr std::uintmax_t kRequiredFreeBytes = std::uintmax_t(12) << 30;

int sliceCount() {
    const char* text = std::getenv("LINEWORK_BIG_IMPORT_SLICES");
    const int count = text ? std::atoi(text) : 2048;
    return count >= 2 ? count : 2048;
}

// Distinct along every axis, so a slice out of order or a transposed row shows.
int storedValue(int x, int y, int z) {
    return (x * 7 + y * 3 + z * 5) % 3000 - 1000;
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

double peakResidentGiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / (1024.0 * 1024.0); // ru_maxrss: KiB
}

void writeSeries(const fs::path& dir, int slices) {
    const std::string studyUid = dt::makeTestUid();
    const std::string seriesUid = dt::makeTestUid();
    dt::TestSlice slice;
    slice.rows = kRows;
    slice.columns = kColumns;
    slice.pixelSpacing = glm::dvec2(kSliceStepMm, kSliceStepMm);
    slice.sliceThickness = kSliceStepMm;
    slice.studyUid = studyUid;
    slice.seriesUid = seriesUid;
    slice.seriesDescription = "photon-counting CT, synthetic";
    slice.pixels.resize(std::size_t(kRows) * std::size_t(kColumns));
    for (int z = 0; z < slices; ++z) {
        for (int y = 0; y < kRows; ++y)
            for (int x = 0; x < kColumns; ++x)
                slice.pixels[std::size_t(y) * kColumns + std::size_t(x)] = storedValue(x, y, z);
        slice.position = glm::dvec3(0.0, 0.0, kSliceStepMm * z);
        slice.instanceNumber = z + 1;
        slice.sopInstanceUid.clear(); // a fresh one per file
        char name[32];
        std::snprintf(name, sizeof name, "ct%05d.dcm", z);
        dt::writeTestSlice(dir / name, slice);
    }
}

} // namespace

TEST(BigDicomImport, PhotonCountingSizedSeriesImportsVoxelForVoxel) {
    const test::TempDir dir;
    const std::uintmax_t freeBytes = fs::space(dir.path()).available;
    if (freeBytes < kRequiredFreeBytes) {
        std::printf("SKIP: %.1f GiB free in %s; the 4 GiB series needs 12 GiB\n",
                    double(freeBytes) / double(1 << 30), dir.path().c_str());
        GTEST_SKIP();
    }
    const int slices = sliceCount();
    auto start = std::chrono::steady_clock::now();
    writeSeries(dir.path(), slices);
    const double writeSeconds = secondsSince(start);

    start = std::chrono::steady_clock::now();
    const input::OpenedVolume opened = input::openInput(dir.path().string());
    const double importSeconds = secondsSince(start);

    const volume::Volume& volume = opened.volume;
    ASSERT_EQ(volume.dims(), glm::ivec3(kColumns, kRows, slices));
    ASSERT_EQ(volume.voxelType(), volume::VoxelType::Int16);
    EXPECT_NEAR(volume.geometry().spacingI(), kSliceStepMm, 1e-9);
    EXPECT_NEAR(volume.geometry().sliceOffset(double(slices - 1)), kSliceStepMm * (slices - 1),
                1e-6);
    const std::int16_t* voxels = volume.dataAs<std::int16_t>();
    // Every slice, on a lattice of rows and columns that changes from slice to slice.
    for (int z = 0; z < slices; ++z)
        for (int y = z % 13; y < kRows; y += 97)
            for (int x = z % 11; x < kColumns; x += 89)
                ASSERT_EQ(voxels[volume.index(x, y, z)], storedValue(x, y, z))
                    << "voxel " << x << "," << y << "," << z;

    // The memory bound of the `big` label: the import holds the volume and a few slices, never
    // a second copy (measured 1.005 x the volume on dev-2c).
    const double volumeGiB = double(volume.byteSize()) / double(1 << 30);
    EXPECT_LT(peakResidentGiB(), 1.15 * volumeGiB + 0.25);
    std::printf("BIG IMPORT %dx%dx%d int16 (%.2f GiB): written in %.1f s, imported in %.1f s = "
                "%.0f slices/s on %u threads; peak resident %.2f GiB\n",
                kColumns, kRows, slices, volumeGiB, writeSeconds, importSeconds,
                double(slices) / importSeconds, std::thread::hardware_concurrency(),
                peakResidentGiB());
}
