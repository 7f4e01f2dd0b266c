// `linework-cli export` on a real series of the shared data: the tilted, unevenly spaced GE head
// CT as a PDF and a DICOM Secondary Capture that Linework's own import (`info`) reads back as a
// new series of the same study.
#include "cli_runner.h"
#include "lw/core/file_util.h"
#include "test_support.h"

#include <filesystem>
#include <gtest/gtest.h>

using namespace lw;
using test::quoted;
using test::runCli;

namespace {

// The value of the first `"key": "value"` in compact JSON.
std::string firstValue(const std::string& json, const std::string& key) {
    const std::string compact = test::compact(json);
    const std::string marker = "\"" + key + "\":\"";
    const std::size_t at = compact.find(marker);
    if (at == std::string::npos)
        return {};
    const std::size_t start = at + marker.size();
    return compact.substr(start, compact.find('"', start) - start);
}

} // namespace

TEST(ExportCommandData, SecondaryCaptureOfTheTiltedHeadJoinsItsStudy) {
    const std::filesystem::path source =
        *test::sharedDataDir() / "dicom" / "ct_head_ge_hispeed_tilt_varspacing";
    test::TempDir dir;
    const test::CliResult exported = runCli(
        "export " + quoted(source.string()) + " --iso 400 --view 30,10 --size 256x256 --pdf " +
        quoted((dir / "head.pdf").string()) + " --sc " + quoted((dir / "sc").string()));
    ASSERT_EQ(exported.exitCode, 0) << exported.out << exported.err;
    EXPECT_TRUE(std::filesystem::exists(dir / "sc" / "LWSC0001.dcm"));

    const test::CliResult original = runCli("info " + quoted(source.string()) + " --json");
    const test::CliResult capture = runCli("info " + quoted((dir / "sc").string()) + " --json");
    // info lists the series (and exits 1: an RGB picture is no volume to review).
    ASSERT_NE(capture.out.find("\"series\""), std::string::npos) << capture.out << capture.err;
    const std::string studyUid = firstValue(original.out, "study_instance_uid");
    ASSERT_FALSE(studyUid.empty());
    EXPECT_EQ(firstValue(capture.out, "study_instance_uid"), studyUid);
    EXPECT_EQ(firstValue(capture.out, "patient_id"), firstValue(original.out, "patient_id"));
    EXPECT_NE(firstValue(capture.out, "series_instance_uid"),
              firstValue(original.out, "series_instance_uid"));
    EXPECT_EQ(firstValue(capture.out, "modality"), "OT");
}
