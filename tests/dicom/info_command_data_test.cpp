// `linework-cli info` and `bench-import` on real data.
#include "cli_runner.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <regex>

using namespace lw;

#ifdef LINEWORK_CLI_PATH
TEST(CliInfoData, GeHeadTiltVariableSpacing) {
    const auto dir = *test::sharedDataDir() / "dicom/ct_head_ge_hispeed_tilt_varspacing";
    const auto result = test::runCli("info " + test::quoted(dir.string()) + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.out;
    const std::string json = test::compact(result.out);
    EXPECT_NE(json.find("\"dims\":[512,512,28]"), std::string::npos) << result.out;
    std::smatch match;
    ASSERT_TRUE(std::regex_search(json, match, std::regex("\"tilt_deg\":([0-9.eE+-]+)")))
        << result.out;
    EXPECT_NEAR(std::stod(match[1].str()), 18.5, 0.3);
    EXPECT_NE(json.find("\"uneven_gaps\":true"), std::string::npos) << result.out;
    EXPECT_NE(json.find("\"errors\":[]"), std::string::npos) << result.out;
}

TEST(CliInfoData, PhilipsDicomdirListsMissingFiles) {
    const auto dicomdir =
        *test::sharedDataDir() / "dicom/ct_headphantom_philips_dicomdir_export/DICOMDIR";
    const auto result = test::runCli("info " + test::quoted(dicomdir.string()) + " --json");
    ASSERT_EQ(result.exitCode, 0) << result.out;
    const std::string json = test::compact(result.out);
    std::size_t missing = 0;
    for (std::size_t at = json.find("\"reason\":\"referenced by DICOMDIR but missing\"");
         at != std::string::npos;
         at = json.find("\"reason\":\"referenced by DICOMDIR but missing\"", at + 1))
        ++missing;
    EXPECT_EQ(missing, 338u);
}

TEST(CliInfoData, BenchImportReportsSlicesPerSecond) {
    const auto dir = *test::sharedDataDir() / "dicom/ct_head_ge_hispeed_tilt_varspacing";
    const auto result =
        test::runCli("bench-import " + test::quoted(dir.string()) + " --repeat 1 --json");
    ASSERT_EQ(result.exitCode, 0) << result.out;
    const std::string json = test::compact(result.out);
    EXPECT_NE(json.find("\"slices\":28"), std::string::npos) << result.out;
    EXPECT_NE(json.find("\"slices_per_s\":"), std::string::npos) << result.out;
}
#endif
