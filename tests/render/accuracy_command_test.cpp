// `linework-cli accuracy` end to end: JSON rows for every requested method x variant, scores that
// are real numbers in [0, 1] and meet the goal on an easy case, and usage errors rejected.
#include "cli_runner.h"

#include <gtest/gtest.h>
#include <memory>
#include <regex>
#include <string>

namespace {

using lw::test::CliResult;
using lw::test::runCli;

TEST(AccuracyCommand, JsonRowsForMethod2SAndLOnTheSphere) {
    const CliResult r = runCli("accuracy --methods 2 --sizes 32 --shapes sphere,torus --json");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    // One row per variant (S, L) x visibility rule (endpoints, along) x shape.
    const std::regex row(
        R"re(\{\s*"method": 2,\s*"variant": "([SL])",\s*"visibility": "(endpoints|along)",\s*"backend": "cpu",\s*"shape": "(sphere|torus)",\s*"size": 32,\s*"image": (\d+),\s*"recall": ([0-9.e+-]+),\s*"precision": ([0-9.e+-]+))re");
    int rows = 0;
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), row);
         it != std::sregex_iterator(); ++it) {
        ++rows;
        const double recall = std::stod((*it)[5]);
        const double precision = std::stod((*it)[6]);
        EXPECT_GE(recall, 0.0);
        EXPECT_LE(recall, 1.0);
        EXPECT_LE(precision, 1.0);
        EXPECT_GT(std::stoi((*it)[4]), 50) << "a voxel covers about two pixels";
        if ((*it)[3] == "sphere") {
            EXPECT_GE(recall, 0.99) << (*it)[0];
            EXPECT_GE(precision, 0.99) << (*it)[0];
        }
    }
    EXPECT_EQ(rows, 8) << r.out;
}

TEST(AccuracyCommand, HumanReadableTable) {
    const CliResult r =
        runCli("accuracy --methods 2 --sizes 16 --shapes superquadric --view -40,30");
    ASSERT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("az -40 el 30"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("superquadric"), std::string::npos);
    EXPECT_NE(r.out.find("recall"), std::string::npos);
}

TEST(AccuracyCommand, RejectsBadArguments) {
    // Usage errors: exit 2.
    EXPECT_EQ(runCli("accuracy --methods 4").exitCode, 2);
    EXPECT_EQ(runCli("accuracy --sizes 4").exitCode, 2);
    EXPECT_EQ(runCli("accuracy --shapes cube --sizes 16").exitCode, 2);
    EXPECT_EQ(runCli("accuracy --view 10").exitCode, 2);
    EXPECT_EQ(runCli("accuracy --backend opencl").exitCode, 2);
}

} // namespace
