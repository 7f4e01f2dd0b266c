// The PACS node file: what the GUI's settings and the CLI share.
#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "lw/pacs/pacs_node.h"
#include "test_support.h"

#include <gtest/gtest.h>

namespace lw::pacs {
namespace {

void writeText(const std::filesystem::path& path, const std::string& text) {
    core::writeFileAtomically(path, text.data(), text.size());
}

std::string errorOf(const std::filesystem::path& path) {
    try {
        readNodeFile(path);
    } catch (const core::Error& error) {
        return error.what();
    }
    return "no error";
}

TEST(PacsNodeFile, WritesAndReadsBackEveryField) {
    test::TempDir dir;
    PacsNodeFile file;
    file.workstation = {"MY_WS", 11113};
    file.nodes = {{"radiology", "ORTHANC", "10.0.0.5", 4242},
                  {"backup", "BKP", "pacs.example", 104, RetrieveMethod::Move}};
    const auto path = dir / "sub" / "pacs-nodes.json";
    writeNodeFile(path, file);
    const PacsNodeFile read = readNodeFile(path);
    EXPECT_EQ(read.workstation.aet, "MY_WS");
    EXPECT_EQ(read.workstation.storagePort, 11113);
    ASSERT_EQ(read.nodes.size(), 2u);
    EXPECT_EQ(read.nodes[1].name, "backup");
    EXPECT_EQ(read.nodes[1].calledAet, "BKP");
    EXPECT_EQ(read.nodes[1].host, "pacs.example");
    EXPECT_EQ(read.nodes[1].port, 104);
    EXPECT_EQ(read.nodes[0].retrieve, RetrieveMethod::Get);
    EXPECT_EQ(read.nodes[1].retrieve, RetrieveMethod::Move);
    // Atomic: nothing but the file itself is left in its folder.
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(path.parent_path()), {}), 1);
}

TEST(PacsNodeFile, MissingFileReadsAsDefaults) {
    test::TempDir dir;
    const PacsNodeFile file = readNodeFileOrDefaults(dir / "none.json");
    EXPECT_TRUE(file.nodes.empty());
    EXPECT_EQ(file.workstation.aet, "LINEWORK");
}

struct BadFile {
    const char* text;
    const char* reason; // a part of the message
};

class PacsNodeFileErrors : public testing::TestWithParam<BadFile> {};

TEST_P(PacsNodeFileErrors, NameTheFileAndTheValue) {
    test::TempDir dir;
    const auto path = dir / "nodes.json";
    writeText(path, GetParam().text);
    const std::string message = errorOf(path);
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(GetParam().reason), std::string::npos) << message;
}

INSTANTIATE_TEST_SUITE_P(
    PacsNodeFile, PacsNodeFileErrors,
    testing::Values(
        BadFile{R"({"nodes": [{"name": "a", "calledAet": "X", "host": "h", "port": 1,
                              "retrieve": "fetch"}]})",
                "nodes[0].retrieve is not \"get\" or \"move\""},
        BadFile{R"({"nodes": [{"name": "a", "calledAet": "X", "host": "h", "port": 70000}]})",
                "nodes[0].port"},
        BadFile{R"({"nodes": [{"name": "a", "calledAet": "X", "host": "h"}]})",
                "\"port\" is missing"},
        BadFile{
            R"({"nodes": [{"name": "a", "calledAet": "ABCDEFGHIJKLMNOPQ", "host": "h", "port": 1}]})",
            "1 to 16 characters"},
        BadFile{R"({"nodes": [{"name": "a", "calledAet": "X", "host": "h", "port": 1},
                              {"name": "a", "calledAet": "Y", "host": "h", "port": 2}]})",
                "two nodes are named"},
        BadFile{R"({"workstation": {"aet": "A\\B", "storagePort": 104}})", "backslash"},
        BadFile{R"({"nodes": {}})", "nodes is not an array"},
        BadFile{R"({"nodes": [}")", "line 1"}));

TEST(PacsNodeAddress, NameOrAetAtHostPort) {
    PacsNodeFile file;
    file.nodes = {{"main", "MAIN_AE", "10.1.1.1", 104}};
    EXPECT_EQ(resolveNode(file, "main").calledAet, "MAIN_AE");
    const PacsNode direct = resolveNode(file, "ORTHANC@127.0.0.1:4242");
    EXPECT_EQ(direct.calledAet, "ORTHANC");
    EXPECT_EQ(direct.host, "127.0.0.1");
    EXPECT_EQ(direct.port, 4242);
    EXPECT_EQ(resolveNode(file, "PACS@[::1]:104").host, "::1");
    EXPECT_THROW(resolveNode(file, "nosuchnode"), core::Error);
    EXPECT_THROW(resolveNode(file, "AE@host:0"), core::Error);
    EXPECT_THROW(resolveNode(file, "AE@host:99999"), core::Error);
}

// Messages name a node of the file by its name and address, an address by itself once.
TEST(PacsNodeAddress, DescribedForMessages) {
    PacsNodeFile file;
    file.nodes = {{"main", "MAIN_AE", "10.1.1.1", 104}};
    EXPECT_EQ(describeNode(resolveNode(file, "main")), "main (MAIN_AE@10.1.1.1:104)");
    EXPECT_EQ(describeNode(resolveNode(file, "ORTHANC@127.0.0.1:4242")), "ORTHANC@127.0.0.1:4242");
    EXPECT_EQ(describeNode(resolveNode(file, "PACS@[::1]:104")), "PACS@[::1]:104");
}

} // namespace
} // namespace lw::pacs
