// The `linework-cli info --json` contract: key names other tools and the docs rely on.
#include "cli_runner.h"
#include "dicom_test_writer.h"
#include "test_support.h"

#include <fstream>
#include <gtest/gtest.h>

using namespace lw;

namespace {

void writeSeries(const std::filesystem::path& dir, int slices, double gap) {
    std::filesystem::create_directories(dir);
    const std::string series = dicom::test::makeTestUid();
    const std::string study = dicom::test::makeTestUid();
    for (int i = 0; i < slices; ++i) {
        dicom::test::TestSlice s;
        s.rows = 6;
        s.columns = 5;
        s.pixelSpacing = glm::dvec2(0.5, 0.75); // (row, column): x spacing is 0.75
        s.seriesUid = series;
        s.studyUid = study;
        s.seriesNumber = 4;
        s.instanceNumber = i + 1;
        s.position = glm::dvec3(0.0, 0.0, gap * i);
        dicom::test::writeTestSlice(dir / ("IM" + std::to_string(i + 1) + ".dcm"), s);
    }
}

} // namespace

TEST(CliInfo, JsonOnAWrittenSeries) {
    test::TempDir dir;
    writeSeries(dir / "series", 3, 2.0);
    std::ofstream(dir / "series" / "notes.txt") << "not DICOM";

    const auto result = test::runCli("info " + test::quoted((dir / "series").string()) + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.out;
    const std::string json = test::compact(result.out);
    for (const char* key : {"\"patients\":[", "\"studies\":[", "\"series\":[", "\"volumes\":[",
                            "\"tilt_deg\":", "\"errors\":[", "\"uneven_gaps\":false",
                            "\"missing_slices\":0", "\"transfer_syntaxes\":["})
        EXPECT_NE(json.find(key), std::string::npos) << key << "\n" << result.out;
    EXPECT_NE(json.find("\"dims\":[5,6,3]"), std::string::npos) << result.out;
    EXPECT_NE(json.find("\"spacing\":[0.75,0.5,2]"), std::string::npos) << result.out;
    EXPECT_NE(json.find("\"instances\":3"), std::string::npos) << result.out;
    EXPECT_NE(json.find("\"uid\":\"1.2.840.10008.1.2.1\""), std::string::npos) << result.out;
    // The junk file is listed with the file and the reason.
    EXPECT_NE(json.find("notes.txt\",\"reason\":\""), std::string::npos) << result.out;
    EXPECT_NE(json.find("\"file\":\""), std::string::npos) << result.out;
}

TEST(CliInfo, HumanReadableOutput) {
    test::TempDir dir;
    writeSeries(dir.path(), 2, 3.0);
    const auto result = test::runCli("info " + test::quoted(dir.path().string()));
    ASSERT_EQ(result.exitCode, 0) << result.out;
    EXPECT_NE(result.out.find("series 4"), std::string::npos) << result.out;
    EXPECT_NE(result.out.find("volume 5 x 6 x 2"), std::string::npos) << result.out;
}

TEST(CliInfo, NothingUsableExitsWithOne) {
    test::TempDir dir;
    std::ofstream(dir / "a.txt") << "nothing";
    const auto result = test::runCli("info " + test::quoted(dir.path().string()) + " --json");
    EXPECT_EQ(result.exitCode, 1) << result.out;
    // Still machine-readable, with the reason per file.
    EXPECT_NE(test::compact(result.out).find("a.txt\",\"reason\""), std::string::npos)
        << result.out;
}

TEST(CliInfo, BundledDemoStudyLoadsOnAFreshClone) {
    // The main job's input ships in resources/: it must work without ../shared/data.
    const auto demo = test::sourceDir() / "resources/demo/ct_head_ge_tilt";
    const auto result = test::runCli("info " + test::quoted(demo.string()) + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.out;
    const std::string json = test::compact(result.out);
    EXPECT_NE(json.find("\"dims\":[512,512,28]"), std::string::npos) << result.out;
    EXPECT_NE(json.find("\"uneven_gaps\":true"), std::string::npos) << result.out;
    EXPECT_NE(json.find("\"errors\":[]"), std::string::npos) << result.out;
    const auto tilt = json.find("\"tilt_deg\":");
    ASSERT_NE(tilt, std::string::npos);
    EXPECT_NEAR(std::stod(json.substr(tilt + 11, 12)), 18.5, 0.5) << result.out;
}
