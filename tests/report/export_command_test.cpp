// `linework-cli export` as a user runs it: every output at once, existing files refused without
// --force (and kept byte for byte), bad annotation files named, usage errors, and on the shared
// data (label data) a Secondary Capture of the tilted GE head that dciodvfy passes.
#include "cli_runner.h"
#include "link_trap.h"
#include "lw/core/file_util.h"
#include "lw/core/png_io.h"
#include "test_support.h"

#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>

using namespace lw;
using test::quoted;
using test::runCli;

namespace {

constexpr const char* kAnnotations = R"({"version": 1, "annotations": [
  {"type": "ruler", "points": [[-20, 0, 0], [20, 0, 0]]},
  {"type": "label", "points": [[0, -10, 15]], "text": "Finding B"},
  {"type": "angle", "points": [[-20, 0, -10], [0, 0, -20], [20, 0, -10]]}
]})";

std::filesystem::path writeText(const std::filesystem::path& path, const std::string& text) {
    core::writeFileAtomically(path, text.data(), text.size());
    return path;
}

std::string exportArguments(const test::TempDir& dir, const std::string& outputs) {
    return "export phantom:48:sphere --iso 300 --size 300x200 --view 20,10 --annotations " +
           quoted((dir / "notes.json").string()) + " --comment 'CLI comment' " + outputs;
}

std::size_t entries(const std::filesystem::path& folder) {
    return std::size_t(std::distance(std::filesystem::directory_iterator(folder), {}));
}

} // namespace

TEST(ExportCommand, WritesEveryOutputAndRefusesToOverwrite) {
    test::TempDir dir;
    writeText(dir / "notes.json", kAnnotations);
    const std::string outputs = "--png " + quoted((dir / "a.png").string()) + " --pdf " +
                                quoted((dir / "a.pdf").string()) + " --svg " +
                                quoted((dir / "a.svg").string());
    const test::CliResult first = runCli(exportArguments(dir, outputs));
    ASSERT_EQ(first.exitCode, 0) << first.out << first.err;
    for (const char* name : {"a.png", "a.pdf", "a.svg"})
        EXPECT_NE(first.out.find(std::string("wrote ") + (dir / name).string()), std::string::npos)
            << first.out;
    const core::ImageRgba8 png = core::readPng(dir / "a.png");
    EXPECT_EQ(png.width(), 600); // two 300 x 200 panels side by side
    EXPECT_EQ(png.height(), 200);
    EXPECT_EQ(core::readFileText(dir / "a.pdf").rfind("%PDF", 0), 0u);
    EXPECT_NE(core::readFileText(dir / "a.svg").find(">Finding B</text>"), std::string::npos);

    const auto before = core::readFileBytes(dir / "a.png");
    const test::CliResult again = runCli(exportArguments(dir, outputs));
    EXPECT_EQ(again.exitCode, 1);
    EXPECT_NE(again.err.find("exists already"), std::string::npos) << again.err;
    EXPECT_EQ(core::readFileBytes(dir / "a.png"), before);
    EXPECT_EQ(entries(dir.path()), 4u); // notes.json and the three outputs, no temporaries
    EXPECT_EQ(runCli(exportArguments(dir, outputs + " --force")).exitCode, 0);
}

TEST(ExportCommand, RefusedExportsWriteNothing) {
    test::TempDir dir;
    writeText(dir / "notes.json", R"({"annotations": [{"type": "ruler", "points": [[0,0,0]]}]})");
    const test::CliResult bad =
        runCli(exportArguments(dir, "--png " + quoted((dir / "a.png").string())));
    EXPECT_EQ(bad.exitCode, 1);
    EXPECT_NE(bad.err.find((dir / "notes.json").string()), std::string::npos) << bad.err;
    EXPECT_NE(bad.err.find("annotations[0]: a ruler needs 2 points"), std::string::npos) << bad.err;
    writeText(dir / "notes.json", kAnnotations);
    const test::CliResult missingFolder =
        runCli(exportArguments(dir, "--pdf " + quoted((dir / "no" / "a.pdf").string())));
    EXPECT_EQ(missingFolder.exitCode, 1);
    EXPECT_NE(missingFolder.err.find("does not exist"), std::string::npos) << missingFolder.err;
    // A phantom has no study for a Secondary Capture to join: refused before the PNG is written.
    const test::CliResult notDicom =
        runCli(exportArguments(dir, "--png " + quoted((dir / "a.png").string()) + " --sc " +
                                        quoted((dir / "sc").string())));
    EXPECT_EQ(notDicom.exitCode, 1);
    EXPECT_NE(notDicom.err.find("must be DICOM"), std::string::npos) << notDicom.err;
    EXPECT_EQ(entries(dir.path()), 1u); // only notes.json
}

// --hidden-lines: the hidden parts go into the SVG as a dashed group and into the PNG as grey
// dashes; --line-width and --line-colour style the visible strokes.
TEST(ExportCommand, HiddenLinesAndLineStyle) {
    test::TempDir dir;
    const std::string common = "export phantom:64 --iso 300.5 --size 300x200 --view 30,10 "
                               "--panel silhouette --line-width 3 --line-colour '#c00000' ";
    ASSERT_EQ(runCli(common + "--hidden-lines --png " + quoted((dir / "h.png").string()) +
                     " --svg " + quoted((dir / "h.svg").string()) + " --pdf " +
                     quoted((dir / "h.pdf").string()))
                  .exitCode,
              0);
    const std::string svg = core::readFileText(dir / "h.svg");
    EXPECT_NE(svg.find("stroke-dasharray=\"12.000 9.000\""), std::string::npos);
    EXPECT_NE(svg.find("stroke=\"#c00000\""), std::string::npos);
    const core::ImageRgba8 png = core::readPng(dir / "h.png");
    std::size_t red = 0, grey = 0;
    for (int y = 0; y < png.height(); ++y)
        for (int x = 0; x < png.width(); ++x) {
            const core::Rgba8 p = png.row(y)[x];
            const int r = p.r, g = p.g, b = p.b;
            red += r > 150 && g < 80 && b < 80 ? 1 : 0;
            grey += std::abs(r - g) < 8 && std::abs(g - b) < 8 && r > 100 && r < 200 ? 1 : 0;
        }
    EXPECT_GT(red, 300u) << "the visible lines in their colour";
    EXPECT_GT(grey, 20u) << "the hidden lines' grey dashes";
    EXPECT_EQ(core::readFileText(dir / "h.pdf").rfind("%PDF", 0), 0u);
    EXPECT_EQ(
        runCli(common + "--hidden-lines --visibility off --png " + quoted((dir / "x.png").string()))
            .exitCode,
        2);
    EXPECT_FALSE(std::filesystem::exists(dir / "x.png"));
}

// An annotation file of version 2 with a ruler on an axial slice: its caption names the plane.
// A file from a newer Linework is refused, naming the file and its version.
TEST(ExportCommand, SliceAnnotationsAndNewerFiles) {
    test::TempDir dir;
    writeText(dir / "notes.json", R"({"version": 2, "annotations": [
  {"type": "ruler", "points": [[-20, 0, 2.5], [20, 0, 2.5]],
   "slice": {"plane": "axial", "position": 2.5, "spacing": 1.25}}]})");
    const test::CliResult slice =
        runCli(exportArguments(dir, "--svg " + quoted((dir / "a.svg").string())));
    ASSERT_EQ(slice.exitCode, 0) << slice.out << slice.err;
    EXPECT_NE(core::readFileText(dir / "a.svg").find(">40.0 mm \u00b7 axial 2.5 mm</text>"),
              std::string::npos);
    writeText(dir / "notes.json", R"({"version": 3, "annotations": []})");
    const test::CliResult newer =
        runCli(exportArguments(dir, "--svg " + quoted((dir / "b.svg").string())));
    EXPECT_EQ(newer.exitCode, 1);
    EXPECT_NE(newer.err.find((dir / "notes.json").string() +
                             ": version 3 is not supported: a newer Linework wrote it"),
              std::string::npos)
        << newer.err;
    EXPECT_FALSE(std::filesystem::exists(dir / "b.svg"));
}

TEST(ExportCommand, UsageErrors) {
    EXPECT_EQ(runCli("export phantom:32:sphere --iso 300").exitCode, 2);   // no output
    EXPECT_EQ(runCli("export --png x.png").exitCode, 2);                   // no input
    EXPECT_EQ(runCli("export phantom:32:sphere --png x.png").exitCode, 2); // no --iso
    EXPECT_EQ(runCli("export phantom:32:sphere --iso 300 --png x.png --panel left").exitCode, 2);
    EXPECT_NE(runCli("help").out.find("export INPUT"), std::string::npos);
}

// Every output refuses a target that is a link (out of the folder, dangling, or to the user's
// own file), even with --force, and a target that is the folder's parent; nothing is rendered
// or written, and the error names the file and the reason.
TEST(ExportCommand, NothingIsWrittenOutsideTheChosenFolder) {
    test::TempDir dir;
    writeText(dir / "notes.json", kAnnotations);
    for (const char* format : {"png", "pdf", "svg"}) {
        const test::LinkTrap trap(dir / format, std::string("out.") + format);
        for (const std::string& kind : test::LinkTrap::kinds()) {
            SCOPED_TRACE(std::string(format) + " " + kind);
            const auto link = trap.link(kind);
            const test::CliResult refused = runCli(exportArguments(
                dir, "--" + std::string(format) + " " + quoted(link.string()) + " --force"));
            EXPECT_EQ(refused.exitCode, 1);
            EXPECT_NE(refused.err.find(link.string() + ": is a symbolic link"), std::string::npos)
                << refused.err;
            EXPECT_TRUE(trap.untouched());
        }
    }
    const test::CliResult parent =
        runCli(exportArguments(dir, "--png " + quoted((dir / "png" / "exports" / "..").string())));
    EXPECT_EQ(parent.exitCode, 1);
    EXPECT_NE(parent.err.find("not a file name in a folder"), std::string::npos) << parent.err;
}

// --suggestive: the silhouette panel of the export gains the suggestive contours (the CT
// phantom's bone has concave folds) in the PNG and as paths in the SVG.
TEST(ExportCommand, SuggestiveContoursAddLines) {
    const test::TempDir dir;
    const std::string common = "export phantom:64 --iso 300.5 --size 200x200 --view 30,10 "
                               "--panel silhouette --backend cpu ";
    const auto dark = [](const core::ImageRgba8& image) {
        std::size_t n = 0;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x)
                n += image.at(x, y).r < 128;
        return n;
    };
    const auto paths = [](const std::filesystem::path& file) {
        const std::string svg = core::readFileText(file);
        std::size_t n = 0;
        for (std::size_t at = svg.find("<path"); at != std::string::npos;
             at = svg.find("<path", at + 1))
            ++n;
        return n;
    };
    ASSERT_EQ(runCli(common + "--png " + quoted((dir / "a.png").string()) + " --svg " +
                     quoted((dir / "a.svg").string()))
                  .exitCode,
              0);
    ASSERT_EQ(runCli(common + "--suggestive --png " + quoted((dir / "b.png").string()) + " --svg " +
                     quoted((dir / "b.svg").string()))
                  .exitCode,
              0);
    const std::size_t plain = dark(core::readPng(dir / "a.png"));
    ASSERT_GT(plain, 100u);
    EXPECT_GT(dark(core::readPng(dir / "b.png")), plain + 50);
    EXPECT_GT(paths(dir / "b.svg"), paths(dir / "a.svg"));
    // A stricter derivative test keeps fewer of them (as `render --suggestive-threshold`).
    ASSERT_EQ(runCli(common + "--suggestive --suggestive-threshold 40 --png " +
                     quoted((dir / "c.png").string()))
                  .exitCode,
              0);
    EXPECT_LT(dark(core::readPng(dir / "c.png")), dark(core::readPng(dir / "b.png")));
    const auto negative = runCli(common + "--suggestive --suggestive-threshold -1 --png " +
                                 quoted((dir / "d.png").string()));
    EXPECT_EQ(negative.exitCode, 2);
    EXPECT_NE(negative.err.find("--suggestive-threshold"), std::string::npos) << negative.err;
}
