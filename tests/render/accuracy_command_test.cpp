// `linework-cli accuracy` end to end: JSON rows for every requested method x variant, scores that
// are real numbers in [0, 1] and meet the goal on an easy case, the sweep over views (rows carry
// their view, the summary's worst and median), --view as before, and usage errors rejected.
#include "cli_runner.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <map>
#include <memory>
#include <cstdlib>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace {

using lw::test::CliResult;
using lw::test::runCli;

// The rows checked here are the CPU's, so the CLI sees no CUDA device even on the GPU machine
// (CUDA accuracy: render_cuda_backend_tests compares its images with the CPU's).
const bool kNoCudaDeviceForTheCli = [] {
    ::setenv("CUDA_VISIBLE_DEVICES", "", 1);
    return true;
}();

TEST(AccuracyCommand, JsonRowsForMethod2SAndLOnTheSphere) {
    const CliResult r =
        runCli("accuracy --methods 2 --sizes 32 --shapes sphere,torus --view 30,20 --json");
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
    // One view: the fields of the command before the sweep are still there.
    EXPECT_NE(r.out.find(R"("azimuth": 30)"), std::string::npos);
    EXPECT_NE(r.out.find(R"("elevation": 20)"), std::string::npos);
}

using View = std::pair<double, double>;

// The per-view rows of a JSON run: variant, view and scores.
struct ViewRow {
    std::string variant;
    std::string visibility;
    View view;
    double recall = 0.0;
    double precision = 0.0;
};

std::vector<ViewRow> viewRows(const std::string& json) {
    const std::regex row(
        R"re("variant": "([SL])",\s*"visibility": "(\w+)",[^{}]*?"recall": ([0-9.e+-]+),\s*"precision": ([0-9.e+-]+),[^{}]*?"view": \[\s*([0-9.e+-]+),\s*([0-9.e+-]+)\s*\])re");
    std::vector<ViewRow> rows;
    for (auto it = std::sregex_iterator(json.begin(), json.end(), row);
         it != std::sregex_iterator(); ++it)
        rows.push_back({(*it)[1],
                        (*it)[2],
                        {std::stod((*it)[5]), std::stod((*it)[6])},
                        std::stod((*it)[3]),
                        std::stod((*it)[4])});
    return rows;
}

TEST(AccuracyCommand, SweepRowsCarryTheirViewsAllFacesAndPolesIncluded) {
    const CliResult r = runCli("accuracy --methods 3 --sizes 16 --shapes torus --json");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const std::vector<ViewRow> rows = viewRows(r.out);
    std::set<View> views;
    for (const ViewRow& row : rows)
        views.insert(row.view);
    EXPECT_GE(views.size(), 26u);
    EXPECT_EQ(rows.size(), 2 * views.size()) << "one row per view and variant";
    for (const View& face :
         {View{0, 0}, View{90, 0}, View{180, 0}, View{-90, 0}, View{0, 90}, View{0, -90}})
        EXPECT_EQ(views.count(face), 1u) << face.first << "," << face.second;
    EXPECT_EQ(r.out.find(R"("azimuth")"), std::string::npos) << "a sweep has no single view";
}

TEST(AccuracyCommand, SummaryNamesTheWorstViewAndItIsAtMostTheMedian) {
    const CliResult r = runCli("accuracy --methods 2 --sizes 16 --shapes torus --views 12 --json");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const std::vector<ViewRow> rows = viewRows(r.out);
    const std::regex summary(
        R"re("variant": "([SL])",\s*"visibility": "(\w+)",[^{}]*?"views": (\d+),\s*"recall_worst": ([0-9.e+-]+),\s*"recall_median": ([0-9.e+-]+),\s*"recall_worst_view": \[[^\]]*\],\s*"precision_worst": ([0-9.e+-]+),\s*"precision_median": ([0-9.e+-]+),\s*"precision_worst_view": \[\s*([0-9.e+-]+),\s*([0-9.e+-]+)\s*\])re");
    int summaries = 0;
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), summary);
         it != std::sregex_iterator(); ++it) {
        ++summaries;
        EXPECT_EQ(std::stoi((*it)[3]), 12);
        EXPECT_LE(std::stod((*it)[4]), std::stod((*it)[5]));
        EXPECT_LE(std::stod((*it)[6]), std::stod((*it)[7]));
        // The worst precision is the lowest of the variant's rows, at the view it names.
        auto inGroup = [&](const ViewRow& row) {
            return row.variant == (*it)[1] && row.visibility == (*it)[2];
        };
        double lowest = 1.0;
        for (const ViewRow& row : rows)
            if (inGroup(row))
                lowest = std::min(lowest, row.precision);
        EXPECT_NEAR(std::stod((*it)[6]), lowest, 1e-9);
        const View worst{std::stod((*it)[8]), std::stod((*it)[9])};
        EXPECT_TRUE(std::any_of(rows.begin(), rows.end(),
                                [&](const ViewRow& row) {
                                    return inGroup(row) && row.view == worst &&
                                           std::abs(row.precision - lowest) < 1e-9;
                                }))
            << worst.first << "," << worst.second;
    }
    EXPECT_EQ(summaries, 4) << "S and L x endpoints and along";
}

TEST(AccuracyCommand, OneViewScoresAsTheSweepDoesAtThatView) {
    const std::string common = "accuracy --methods 3 --sizes 16 --shapes torus,sphere --json ";
    const std::vector<ViewRow> sweep = viewRows(runCli(common + "--views 26").out);
    const std::vector<ViewRow> single = viewRows(runCli(common + "--view 45,35.3").out);
    ASSERT_EQ(single.size(), 4u);
    for (const ViewRow& one : single) {
        EXPECT_EQ(one.view, (View{45, 35.3}));
        const auto same = std::find_if(sweep.begin(), sweep.end(), [&](const ViewRow& row) {
            return row.view == one.view && row.variant == one.variant &&
                   row.visibility == one.visibility && row.recall == one.recall &&
                   row.precision == one.precision;
        });
        EXPECT_TRUE(same != sweep.end()) << "a corner view of the sweep, " << one.variant;
    }
}

TEST(AccuracyCommand, SweepTable) {
    const CliResult r = runCli("accuracy --methods 3 --sizes 16 --shapes superquadric --views 8");
    ASSERT_EQ(r.exitCode, 0);
    EXPECT_NE(r.out.find("8 views"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("worst"), std::string::npos);
    EXPECT_NE(r.out.find("median"), std::string::npos);
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
    EXPECT_EQ(runCli("accuracy --view 10,95").exitCode, 2);
    EXPECT_EQ(runCli("accuracy --views 0").exitCode, 2);
    EXPECT_EQ(runCli("accuracy --views all").exitCode, 2);
    EXPECT_EQ(runCli("accuracy --views 3,4").exitCode, 2);
    EXPECT_EQ(runCli("accuracy --view 30,20 --views 6").exitCode, 2);
    EXPECT_EQ(runCli("accuracy --backend opencl").exitCode, 2);
}

} // namespace
