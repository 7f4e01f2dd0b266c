// openInput / openDicomFiles on DICOM series written by the test (DICOM builds only).
#include "dicom_test_writer.h"
#include "lw/core/error.h"
#include "lw/core/progress.h"
#include "lw/input/open_input.h"
#include "test_support.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <memory>

namespace dt = lw::dicom::test;
namespace fs = std::filesystem;
using namespace lw;

namespace {

// `count` axial 8x8 slices 2 mm apart into `dir`, tilted by `tiltDegrees` about x.
std::vector<fs::path> writeSeries(const fs::path& dir, const std::string& seriesUid, int count,
                                  double tiltDegrees = 0.0, int seriesNumber = 1) {
    fs::create_directories(dir);
    const double rad = tiltDegrees * M_PI / 180.0;
    std::vector<fs::path> files;
    for (int k = 0; k < count; ++k) {
        dt::TestSlice s;
        s.rows = 8;
        s.columns = 8;
        s.seriesUid = seriesUid;
        s.studyUid = "1.2.826.0.1.3680043.2.1143.7";
        s.seriesNumber = seriesNumber;
        s.seriesDescription = "Head " + std::to_string(seriesNumber);
        s.instanceNumber = k + 1;
        s.orientation = std::array<double, 6>{1, 0, 0, 0, std::cos(rad), -std::sin(rad)};
        s.position = glm::dvec3(0.0, 0.0, 2.0 * k);
        s.pixels = dt::rampPixels(8, 8, 100 * k);
        files.push_back(dir / (seriesUid + "_" + std::to_string(k) + ".dcm"));
        dt::writeTestSlice(files.back(), s);
    }
    return files;
}

bool anyContains(const std::vector<std::string>& lines, const std::string& text) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& line) {
        return line.find(text) != std::string::npos;
    });
}

} // namespace

TEST(OpenDicomInput, FolderPicksTheLongestSeriesAndReportsWarnings) {
    ASSERT_TRUE(input::isDicomBuild());
    test::TempDir dir;
    const std::string tilted = dt::makeTestUid();
    const std::string scout = dt::makeTestUid();
    writeSeries(dir / "a", tilted, 6, 12.0, 2);
    writeSeries(dir / "b", scout, 2, 0.0, 1);
    std::ofstream(dir / "b" / "junk.dcm") << "not DICOM";

    std::vector<double> fractions;
    core::Progress progress([&](double f, const std::string&) { fractions.push_back(f); });
    const input::OpenedVolume opened = input::openInput(dir.path().string(), {}, &progress);
    EXPECT_EQ(opened.seriesUid, tilted);
    EXPECT_EQ(opened.volume.dims(), glm::ivec3(8, 8, 6));
    EXPECT_EQ(opened.source, dir.path().string());
    EXPECT_NE(opened.description.find("Head 2"), std::string::npos) << opened.description;
    EXPECT_NE(opened.description.find("8x8x6"), std::string::npos) << opened.description;
    EXPECT_TRUE(anyContains(opened.warnings, "gantry tilt 12"))
        << ::testing::PrintToString(opened.warnings);
    EXPECT_TRUE(anyContains(opened.warnings, "junk.dcm: "))
        << ::testing::PrintToString(opened.warnings);
    ASSERT_FALSE(fractions.empty());
    EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
    EXPECT_DOUBLE_EQ(fractions.back(), 1.0);

    input::OpenOptions options;
    options.seriesUid = scout;
    const input::OpenedVolume second = input::openInput(dir.path().string(), options);
    EXPECT_EQ(second.seriesUid, scout);
    EXPECT_EQ(second.volume.dims(), glm::ivec3(8, 8, 2));
    EXPECT_FALSE(anyContains(second.warnings, "gantry tilt"));

    options.seriesUid = "1.2.3.404";
    try {
        input::openInput(dir.path().string(), options);
        FAIL() << "expected an error for an unknown series";
    } catch (const core::Error& e) {
        EXPECT_NE(std::string(e.what()).find(dir.path().string()), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("1.2.3.404"), std::string::npos) << e.what();
    }
}

TEST(OpenDicomInput, CancelledWhileDecoding) {
    test::TempDir dir;
    writeSeries(dir.path(), dt::makeTestUid(), 24);
    auto token = std::make_shared<core::CancelToken>();
    double reached = 0.0;
    core::Progress progress(
        [&](double f, const std::string&) {
            reached = std::max(reached, f);
            if (f > 0.3) // past the scan: cancel the decode
                token->cancel();
        },
        token);
    EXPECT_THROW(input::openInput(dir.path().string(), {}, &progress), core::Cancelled);
    EXPECT_LT(reached, 1.0);

    auto early = std::make_shared<core::CancelToken>();
    core::Progress scanning(
        [&](double f, const std::string&) {
            if (f > 0.0)
                early->cancel();
        },
        early);
    EXPECT_THROW(input::openInput(dir.path().string(), {}, &scanning), core::Cancelled);
}

TEST(OpenDicomInput, StoredFileListAndMissingFiles) {
    test::TempDir dir;
    const std::string uid = dt::makeTestUid();
    const auto files = writeSeries(dir.path(), uid, 5);
    writeSeries(dir.path(), dt::makeTestUid(), 7); // same folder, not in the list

    input::OpenOptions options;
    options.seriesUid = uid;
    const input::OpenedVolume opened = input::openDicomFiles(files, options);
    EXPECT_EQ(opened.seriesUid, uid);
    EXPECT_EQ(opened.volume.dims(), glm::ivec3(8, 8, 5));

    fs::remove(files[1]);
    fs::remove(files[3]);
    try {
        input::openDicomFiles(files, options);
        FAIL() << "expected an error for missing files";
    } catch (const core::Error& e) {
        const std::string what = e.what();
        EXPECT_NE(what.find("2 of 5 files are missing"), std::string::npos) << what;
        EXPECT_NE(what.find(files[1].filename().string()), std::string::npos) << what;
        EXPECT_NE(what.find(uid), std::string::npos) << what;
    }
    EXPECT_THROW(input::openDicomFiles({}, options), core::Error);
}
