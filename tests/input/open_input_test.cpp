// openInput on what every build reads: phantoms and volume files the test writes itself.
#include "lw/core/error.h"
#include "lw/core/progress.h"
#include "lw/input/open_input.h"
#include "lw/volume/volume_reader.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <memory>
#include <string>

using namespace lw;

namespace {

// Runs `action`, which must throw a core::Error whose message contains `text`.
template <typename Action> void expectErrorMentions(Action&& action, const std::string& text) {
    try {
        action();
        ADD_FAILURE() << "expected an error mentioning " << text;
    } catch (const core::Error& e) {
        EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
}

core::Progress cancelledProgress() {
    auto token = std::make_shared<core::CancelToken>();
    token->cancel();
    return core::Progress([](double, const std::string&) {}, token);
}

} // namespace

TEST(OpenInput, PhantomWithProgress) {
    double last = -1.0;
    core::Progress progress([&](double fraction, const std::string&) { last = fraction; });
    const input::OpenedVolume opened = input::openInput("phantom:24", {}, &progress);
    EXPECT_EQ(opened.volume.dims(), glm::ivec3(24));
    EXPECT_EQ(opened.source, "phantom:24");
    EXPECT_TRUE(opened.seriesUid.empty());
    EXPECT_TRUE(opened.warnings.empty());
    EXPECT_NE(opened.description.find("24x24x24"), std::string::npos) << opened.description;
    EXPECT_DOUBLE_EQ(last, 1.0);

    const input::OpenedVolume box = input::openInput("phantom:8x12x16:sphere");
    EXPECT_EQ(box.volume.dims(), glm::ivec3(8, 12, 16));
    EXPECT_NE(box.description.find("sphere"), std::string::npos) << box.description;
}

TEST(OpenInput, BadPhantomSpecsNameTheSpec) {
    for (const std::string spec : {"phantom:1", "phantom:8x8", "phantom:abc", "phantom:9000"})
        expectErrorMentions([&] { input::openInput(spec); }, spec);
    EXPECT_THROW(input::openInput("phantom:16:cube"), core::Error);
}

// Issue 30: the caller's limit reaches the phantom; a 128 GiB one (more than a workstation could
// allocate) is refused before allocating, with its size and the limit in the message.
TEST(OpenInput, PhantomOverTheLimitIsRefusedWithBothSizes) {
    input::OpenOptions options;
    options.limits.maxBytes = std::size_t(1) << 20;
    options.limits.raiseHint = "--max-volume-gib raises it";
    expectErrorMentions([&] { input::openInput("phantom:4096", options); },
                        "(4096×4096×4096 int16) = 128.0 GiB is more than the limit of 1.0 MiB "
                        "(as set; --max-volume-gib raises it)");
    EXPECT_EQ(input::openInput("phantom:64", options).volume.dims(), glm::ivec3(64));
}

TEST(OpenInput, NrrdWrittenByTheVolumeModule) {
    test::TempDir dir;
    const volume::Volume phantom = input::openInput("phantom:16").volume;
    const auto path = dir / "phantom.nrrd";
    volume::writeNrrd(path, phantom);

    const input::OpenedVolume opened = input::openInput(path.string());
    ASSERT_EQ(opened.volume.dims(), phantom.dims());
    EXPECT_EQ(opened.volume.voxelType(), phantom.voxelType());
    for (const glm::ivec3 p : {glm::ivec3(0), glm::ivec3(8, 7, 9), glm::ivec3(15)})
        EXPECT_EQ(opened.volume.storedValue(p.x, p.y, p.z), phantom.storedValue(p.x, p.y, p.z));
    EXPECT_EQ(opened.source, path.string());
    EXPECT_NE(opened.description.find("phantom.nrrd"), std::string::npos) << opened.description;
}

TEST(OpenInput, CancelledBeforeItStartsReadsNothing) {
    test::TempDir dir;
    const auto path = dir / "v.nrrd";
    volume::writeNrrd(path, input::openInput("phantom:8").volume);
    for (const std::string& input : {std::string("phantom:64"), path.string()}) {
        core::Progress cancelled = cancelledProgress();
        EXPECT_THROW(input::openInput(input, {}, &cancelled), core::Cancelled) << input;
    }
}

TEST(OpenInput, UnreadablePathsNameThePath) {
    test::TempDir dir;
    const auto missing = (dir / "nowhere.nrrd").string();
    expectErrorMentions([&] { input::openInput(missing); }, "nowhere.nrrd");
    const auto folder = dir / "empty folder";
    std::filesystem::create_directories(folder);
    expectErrorMentions([&] { input::openInput(folder.string()); }, "empty folder");
}

TEST(OpenInput, DicomOnlyInADicomBuild) {
    if (input::isDicomBuild()) {
        expectErrorMentions([] { input::openDicomFiles({"/no/such/file.dcm"}); }, "file.dcm");
        return;
    }
    expectErrorMentions([] { input::openDicomFiles({"/no/such/file.dcm"}); }, "reads no DICOM");
    input::OpenOptions options;
    options.seriesUid = "1.2.3";
    test::TempDir dir;
    volume::writeNrrd(dir / "v.nrrd", input::openInput("phantom:8").volume);
    expectErrorMentions([&] { input::openInput((dir / "v.nrrd").string(), options); },
                        "reads no DICOM");
}
