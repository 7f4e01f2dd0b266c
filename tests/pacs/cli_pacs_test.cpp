// `linework-cli pacs ...` as a user runs it against a real Orthanc: exit codes, messages, JSON.
#include "cli_runner.h"
#include "orthanc_server.h"

#include <csignal>
#include <cstdio>
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

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
std::string nodeFileOption(const lw::test::TempDir& dir, const PacsNode& node,
                           std::uint16_t storagePort = 11112) {
    PacsNodeFile file;
    file.workstation.aet = kWorkstationAet;
    file.workstation.storagePort = storagePort;
    file.nodes.push_back(node);
    writeNodeFile(dir / "nodes.json", file);
    return " --nodes " + quoted((dir / "nodes.json").string());
}

// The test's own study database where the build has one; never the user's.
std::string databaseOption(const lw::test::TempDir& dir) {
#ifdef LINEWORK_HAVE_STUDYDB
    return " --database " + quoted((dir / "studies.sqlite").string());
#else
    (void)dir;
    return " --no-database";
#endif
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
                            " --json" + nodes + databaseOption(dir);
    const auto retrieved = runCli(get);
    ASSERT_EQ(retrieved.exitCode, 0) << retrieved.err;
    EXPECT_NE(compact(retrieved.out).find("\"instances\":6,\"transferred\":6,\"skipped\":0"),
              std::string::npos)
        << retrieved.out;
#ifdef LINEWORK_HAVE_STUDYDB
    // Registered in the study database, in place in the store: the series is new there.
    EXPECT_NE(compact(retrieved.out).find("\"seriesAdded\":1"), std::string::npos) << retrieved.out;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "studies.sqlite"));
#endif
    const auto again = runCli(get);
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(compact(again.out).find("\"instances\":6,\"transferred\":0,\"skipped\":6"),
              std::string::npos)
        << again.out;
}

TEST_F(CliPacs, GetByMoveToTheNodeFilesStoragePort) {
    lw::test::TempDir dir;
    const std::string nodes = nodeFileOption(dir, server().node(), storagePort());
    const auto moved = runCli("pacs get orthanc --move --study " + first().studyUid + " --series " +
                              second().seriesUid + " --store " + quoted((dir / "store").string()) +
                              " --json --no-database" + nodes);
    ASSERT_EQ(moved.exitCode, 0) << moved.err;
    EXPECT_NE(compact(moved.out).find("\"instances\":3,\"transferred\":3,\"skipped\":0"),
              std::string::npos)
        << moved.out;
}

TEST_F(CliPacs, GetFromAStoppedPacsExitsOne) {
    const auto result =
        runCli("pacs get " + address({"down", "X", "127.0.0.1", freeLoopbackPort()}) +
               " --study 1.2.3 --no-database --aet " + kWorkstationAet);
    EXPECT_EQ(result.exitCode, 1);
    EXPECT_NE(result.err.find("connection refused"), std::string::npos) << result.err;
}

std::size_t countDicomFiles(const std::filesystem::path& folder) {
    std::size_t count = 0;
    std::error_code error;
    for (std::filesystem::recursive_directory_iterator it(folder, error), end; !error && it != end;
         it.increment(error))
        count += it->path().extension() == ".dcm";
    return count;
}

// The client killed (SIGKILL) halfway through a retrieve: every file it left is whole, and the
// next retrieve transfers only the others.
TEST_F(CliPacs, KilledClientThenRetrieveAgainFetchesOnlyTheMissing) {
    lw::test::TempDir dir;
    const SyntheticSeries big = writeCtSeries(dir / "big", 80, 256);
    for (const std::filesystem::path& file : big.files)
        server().upload(file);
    const std::string store = (dir / "store").string();
    const pid_t client = ::fork();
    ASSERT_GE(client, 0);
    if (client == 0) {
        ::execl(LINEWORK_CLI_PATH, "linework-cli", "pacs", "get",
                (std::string(kOrthancAet) + "@127.0.0.1:" + std::to_string(server().dicomPort()))
                    .c_str(),
                "--aet", kWorkstationAet, "--study", big.studyUid.c_str(), "--series",
                big.seriesUid.c_str(), "--store", store.c_str(), "--no-database",
                static_cast<char*>(nullptr));
        ::_exit(127);
    }
    // Kill it once the first instance has arrived (polling for that event; bounded).
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    while (countDicomFiles(store) == 0 && std::chrono::steady_clock::now() < deadline &&
           ::waitpid(client, nullptr, WNOHANG) == 0)
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
    ::kill(client, SIGKILL);
    ::waitpid(client, nullptr, 0);
    const std::size_t left = countDicomFiles(store);
    ASSERT_GT(left, 0u) << "no instance arrived before the deadline";
    std::printf("the killed client left %zu of 80 instances\n", left);
    for (const auto& entry : std::filesystem::recursive_directory_iterator(store))
        if (entry.path().extension() == ".dcm") {
            DcmFileFormat file;
            EXPECT_TRUE(file.loadFile(entry.path().c_str()).good())
                << entry.path() << " is not whole";
        }

    const auto again = runCli("pacs get " + address(server().node()) + " --aet " + kWorkstationAet +
                              " --study " + big.studyUid + " --series " + big.seriesUid +
                              " --store " + quoted(store) + " --json --no-database");
    ASSERT_EQ(again.exitCode, 0) << again.err;
    EXPECT_NE(
        compact(again.out).find("\"instances\":80,\"transferred\":" + std::to_string(80 - left) +
                                ",\"skipped\":" + std::to_string(left) + ","),
        std::string::npos)
        << "left by the killed client: " << left << "\n"
        << again.out;
    EXPECT_EQ(countDicomFiles(store), 80u);
}

} // namespace
} // namespace lw::pacs::test
