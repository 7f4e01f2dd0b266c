// `linework-cli pacs ...` as a user runs it against a real Orthanc: exit codes, messages, JSON.
#include "cli_runner.h"
#include "orthanc_server.h"

namespace lw::pacs::test {
namespace {

using lw::test::compact;
using lw::test::quoted;
using lw::test::runCli;
using CliPacs = OrthancSuite;

std::string address(const PacsNode& node) {
    return node.calledAet + "@" + node.host + ":" + std::to_string(node.port);
}

// The node file the CLI reads: the workstation's AE title and the Orthanc node by name.
std::string nodeFileOption(const lw::test::TempDir& dir, const PacsNode& node) {
    PacsNodeFile file;
    file.workstation.aet = kWorkstationAet;
    file.nodes.push_back(node);
    writeNodeFile(dir / "nodes.json", file);
    return " --nodes " + quoted((dir / "nodes.json").string());
}

TEST_F(CliPacs, EchoByNameAndByAddress) {
    lw::test::TempDir dir;
    const std::string nodes = nodeFileOption(dir, server().node());
    const auto byName = runCli("pacs echo orthanc" + nodes);
    EXPECT_EQ(byName.exitCode, 0) << byName.err;
    EXPECT_NE(byName.out.find("accepted"), std::string::npos) << byName.out;
    const auto byAddress =
        runCli("pacs echo " + address(server().node()) + " --aet " + kWorkstationAet);
    EXPECT_EQ(byAddress.exitCode, 0) << byAddress.err;
}

TEST_F(CliPacs, EchoFailuresExitOneWithTheReason) {
    PacsNode wrongAe = server().node();
    wrongAe.calledAet = "WRONG_AE";
    const auto rejected = runCli("pacs echo " + address(wrongAe) + " --aet " + kWorkstationAet);
    EXPECT_EQ(rejected.exitCode, 1);
    EXPECT_NE(rejected.err.find("does not answer to the called AE title"), std::string::npos)
        << rejected.err;
    PacsNode down = server().node();
    down.port = freeLoopbackPort();
    const auto refused = runCli("pacs echo " + address(down) + " --aet " + kWorkstationAet);
    EXPECT_EQ(refused.exitCode, 1);
    EXPECT_NE(refused.err.find("connection refused"), std::string::npos) << refused.err;
}

TEST_F(CliPacs, UsageErrorsExitTwo) {
    lw::test::TempDir dir;
    const std::string nodes = nodeFileOption(dir, server().node());
    for (const std::string& arguments : std::vector<std::string>{
             "pacs", "pacs frobnicate orthanc", "pacs echo" + nodes, "pacs echo nosuchnode" + nodes,
             "pacs get orthanc" + nodes, "pacs find orthanc --study-date 2020-01" + nodes}) {
        const auto result = runCli(arguments);
        EXPECT_EQ(result.exitCode, 2) << arguments << "\n" << result.err;
    }
}

TEST_F(CliPacs, FindAndGetAsJson) {
    lw::test::TempDir dir;
    const std::string nodes = nodeFileOption(dir, server().node());
    const auto found = runCli("pacs find orthanc --patient 'Test*' --modality CT --json" + nodes);
    ASSERT_EQ(found.exitCode, 0) << found.err;
    EXPECT_NE(compact(found.out).find("\"studyInstanceUid\":\"" + first().studyUid + "\""),
              std::string::npos)
        << found.out;
    const auto series = runCli("pacs find orthanc --study " + first().studyUid + " --json" + nodes);
    ASSERT_EQ(series.exitCode, 0) << series.err;
    EXPECT_NE(compact(series.out).find("\"seriesInstanceUid\":\"" + second().seriesUid + "\""),
              std::string::npos);

    const std::string get = "pacs get orthanc --study " + first().studyUid + " --series " +
                            first().seriesUid + " --store " + quoted((dir / "store").string()) +
                            " --json" + nodes;
    const auto retrieved = runCli(get);
    ASSERT_EQ(retrieved.exitCode, 0) << retrieved.err;
    EXPECT_NE(compact(retrieved.out).find("\"instances\":6,\"transferred\":6,\"skipped\":0"),
              std::string::npos)
        << retrieved.out;
    const auto again = runCli(get);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(compact(again.out).find("\"instances\":6,\"transferred\":0,\"skipped\":6"),
              std::string::npos)
        << again.out;
}

TEST_F(CliPacs, GetFromAStoppedPacsExitsOne) {
    const auto result =
        runCli("pacs get " + address({"down", "X", "127.0.0.1", freeLoopbackPort()}) +
               " --study 1.2.3 --aet " + kWorkstationAet);
    EXPECT_EQ(result.exitCode, 1);
    EXPECT_NE(result.err.find("connection refused"), std::string::npos) << result.err;
}

} // namespace
} // namespace lw::pacs::test
