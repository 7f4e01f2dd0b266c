// `linework-cli render` as a user runs it: the PNG exists with the requested size and shows lines.
#include "cli_runner.h"
#include "lw/core/png_io.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <string>

namespace {

// The exit code alone: these tests look at the PNG, not at what the command prints.
int runCli(const std::string& arguments) {
    return lw::test::runCli(arguments).exitCode;
}

std::filesystem::path outputPath(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::path(LINEWORK_TEST_OUTPUT_DIR) / "render_command";
    std::filesystem::create_directories(dir);
    const std::filesystem::path path = dir / name;
    std::filesystem::remove(path);
    return path;
}

std::size_t darkPixels(const lw::core::ImageRgba8& image, int x0, int x1) {
    std::size_t n = 0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = x0; x < x1; ++x)
            if (image.at(x, y).r < 128)
                ++n;
    return n;
}

// These tests check the CPU rows and the errors of a machine without a GPU, so the CLI they start
// sees no CUDA device even on the GPU machine (the CUDA paths: render_cuda_backend_tests).
const bool kNoCudaDeviceForTheCli = [] {
    ::setenv("CUDA_VISIBLE_DEVICES", "", 1);
    return true;
}();

TEST(RenderCommand, PhantomSilhouetteHasRequestedSize) {
    const auto out = outputPath("phantom64.png");
    ASSERT_EQ(runCli("render phantom:64 --iso 300.5 --method 3 --size 160x120 --view 30,10 "
                     "--backend cpu -o '" +
                     out.string() + "'"),
              0);
    ASSERT_TRUE(std::filesystem::exists(out));
    const lw::core::ImageRgba8 image = lw::core::readPng(out);
    EXPECT_EQ(image.width(), 160);
    EXPECT_EQ(image.height(), 120);
    EXPECT_GT(darkPixels(image, 0, 160), 100u) << "black silhouette lines on white";
}

// --format svg (or an .svg name): the visible silhouette as vector paths of the frame's size;
// the iso panel has no vector form, so asking for it is a usage error.
TEST(RenderCommand, SvgHoldsTheSilhouetteAsPaths) {
    for (const std::string how : {"-o '%s'", "--format svg -o '%s'"}) {
        const auto out = outputPath(how.size() > 8 ? "lines_format.xml" : "lines.svg");
        std::string arguments = "render phantom:64:sphere --iso 300.5 --method 3 --size 200x160 "
                                "--view 30,10 --backend cpu ";
        arguments += how.substr(0, how.find("%s")) + out.string() + "'";
        ASSERT_EQ(runCli(arguments), 0) << arguments;
        std::ifstream in(out);
        const std::string svg((std::istreambuf_iterator<char>(in)), {});
        EXPECT_EQ(svg.rfind("<?xml", 0), 0u);
        EXPECT_NE(svg.find("viewBox=\"0 0 200 160\""), std::string::npos);
        EXPECT_NE(svg.find("<path d=\"M"), std::string::npos) << "the sphere's contour";
        EXPECT_NE(svg.find("Z\"/>"), std::string::npos) << "a whole sphere's contour is closed";
    }
    const auto out = outputPath("both.svg");
    EXPECT_EQ(runCli("render phantom:32 --iso 300.5 --panel both -o '" + out.string() + "'"), 2);
    EXPECT_FALSE(std::filesystem::exists(out));
}

// --line-width and --line-colour style the SVG's paths; --hidden-lines adds the hidden parts (the
// phantom's inner surfaces) as a dashed grey group beneath. Styles on a PNG, a bad width or
// colour, and hidden lines without visibility are usage errors that write nothing.
TEST(RenderCommand, SvgLineStyleAndHiddenLines) {
    const std::string common =
        "render phantom:64 --iso 300.5 --method 3 --size 200x160 --view 30,10 --backend cpu ";
    const auto out = outputPath("styled.svg");
    ASSERT_EQ(runCli(common + "--line-width 2.5 --line-colour '#a01020' --hidden-lines -o '" +
                     out.string() + "'"),
              0);
    std::ifstream in(out);
    const std::string svg((std::istreambuf_iterator<char>(in)), {});
    EXPECT_NE(svg.find("stroke-width=\"2.500\" stroke-linecap=\"round\""), std::string::npos);
    EXPECT_NE(svg.find("stroke=\"#a01020\""), std::string::npos);
    const std::size_t dashed = svg.find("stroke-dasharray=\"10.000 7.500\"");
    ASSERT_NE(dashed, std::string::npos) << "the hidden group, dashes of 4 and gaps of 3 widths";
    EXPECT_LT(dashed, svg.find("stroke=\"#a01020\"")) << "beneath the visible lines";
    EXPECT_NE(svg.find("stroke-width=\"1.250\""), std::string::npos) << "half the width";

    const auto refused = outputPath("refused.svg");
    const auto refusedPng = outputPath("refused.png");
    for (const std::string& bad : {"--hidden-lines --visibility off -o '" + refused.string() + "'",
                                   "--line-width 0 -o '" + refused.string() + "'",
                                   "--line-width 65 -o '" + refused.string() + "'",
                                   "--line-colour red -o '" + refused.string() + "'",
                                   "--line-width 2 -o '" + refusedPng.string() + "'",
                                   "--hidden-lines -o '" + refusedPng.string() + "'"})
        EXPECT_EQ(runCli(common + bad), 2) << bad;
    EXPECT_FALSE(std::filesystem::exists(refused));
    EXPECT_FALSE(std::filesystem::exists(refusedPng));
}

TEST(RenderCommand, BothPanelsSideBySideChunkedOrtho) {
    const auto out = outputPath("both.png");
    ASSERT_EQ(runCli("render phantom:48 --iso 300.5 --method 3 --chunks 16 --mode b --camera ortho "
                     "--panel both "
                     "--size 100x80 -o '" +
                     out.string() + "'"),
              0);
    const lw::core::ImageRgba8 image = lw::core::readPng(out);
    ASSERT_EQ(image.width(), 200);
    ASSERT_EQ(image.height(), 80);
    EXPECT_GT(darkPixels(image, 100, 200), 50u) << "silhouette on the right";
    std::size_t grey = 0; // the shaded surface on the left: lit grey, not the white background
    for (int y = 0; y < 80; ++y)
        for (int x = 0; x < 100; ++x)
            if (image.at(x, y).r < 250)
                ++grey;
    EXPECT_GT(grey, 300u);
}

TEST(RenderCommand, RejectsBadRequests) {
    const auto out = outputPath("never.png");
    EXPECT_EQ(
        runCli("render phantom:32 --iso 300.5 --method 3 --backend cuda -o '" + out.string() + "'"),
        1);
    EXPECT_EQ(runCli("render phantom:32 --iso 300.5 --method 4 -o '" + out.string() + "'"), 2);
    EXPECT_EQ(runCli("render phantom:32 --iso 300.5 --size 0x10 -o '" + out.string() + "'"), 2);
    EXPECT_EQ(runCli("render phantom:32 --method 3 -o '" + out.string() + "'"), 2)
        << "--iso is required";
    EXPECT_EQ(runCli("render /nonexistent/volume.nrrd --iso 300.5 -o '" + out.string() + "'"), 1);
    EXPECT_EQ(
        runCli("render phantom:32 --iso 300.5 --visibility sometimes -o '" + out.string() + "'"),
        2);
    EXPECT_FALSE(std::filesystem::exists(out));
}

// Method 2's visibility tests: at the ends of each segment (--visibility on, the default) and
// along it draw nearly the same lines, both fewer than with visibility off.
TEST(RenderCommand, Method2VisibilityAlongTheSegments) {
    std::size_t dark[3] = {};
    const char* const tests[] = {"on", "along", "off"};
    for (int i = 0; i < 3; ++i) {
        const auto out = outputPath(std::string("method2_") + tests[i] + ".png");
        ASSERT_EQ(runCli("render phantom:64 --iso 300.5 --method 2 --size 256x256 --view 30,20 "
                         "--backend cpu --visibility " +
                         std::string(tests[i]) + " -o '" + out.string() + "'"),
                  0)
            << tests[i];
        dark[i] = darkPixels(lw::core::readPng(out), 0, 256);
    }
    EXPECT_GT(dark[0], 100u);
    EXPECT_NEAR(double(dark[1]), double(dark[0]), 0.05 * double(dark[0]));
    EXPECT_LT(dark[1], dark[2]);
}

// What a command prints on stderr (runCli drops it) and its exit code.
lw::test::CliResult runCliWithStderr(const std::string& arguments) {
    return lw::test::runProgram("/bin/sh", "-c '\"" LINEWORK_CLI_PATH "\" " + arguments + " 2>&1'");
}

// Issue 30: --max-volume-gib is the limit every volume path asks; over it the input is refused
// before it is made, with both sizes and the option named; a limit that is not a number above 0
// is a usage error.
TEST(RenderCommand, MaxVolumeGibRefusesBeforeAllocating) {
    const auto out = outputPath("never.png");
    const lw::test::CliResult refused = runCliWithStderr(
        "render phantom:64 --iso 300.5 --max-volume-gib 0.0001 -o '" + out.string() + "'");
    EXPECT_EQ(refused.exitCode, 1) << refused.out;
    EXPECT_NE(refused.out.find("the phantom (64×64×64 int16) = 512.0 KiB is more than the limit of "
                               "104.9 KiB (as set; --max-volume-gib raises it)"),
              std::string::npos)
        << refused.out;
    EXPECT_FALSE(std::filesystem::exists(out));
    EXPECT_EQ(runCli("render phantom:64 --iso 300.5 --max-volume-gib 0 -o '" + out.string() + "'"),
              2);
    EXPECT_EQ(runCli("render phantom:32 --iso 300.5 --max-volume-gib 1 -o '" + out.string() + "'"),
              0);
}

// README and `help`: 0 success, 1 an input that cannot be read, 2 a usage error (with the usage).
TEST(CliUsage, UsageErrorsExitTwoWithTheCommandsUsage) {
    const struct {
        std::string arguments;
        std::string usage; // the start of the command's usage line
    } cases[] = {
        {"info", "  info PATH"},
        {"info --bogus x", "  info PATH"},
        {"render phantom:16 -o /tmp/lw-never.png", "  render INPUT"},
        {"render phantom:16 --iso -o /tmp/lw-never.png", "  render INPUT"},
        {"render phantom:16 --iso bone -o /tmp/lw-never.png", "  render INPUT"},
        {"render phantom:16 --iso 300 --mode c -o /tmp/lw-never.png", "  render INPUT"},
        {"render phantom:16 --iso 300 --chunks banana -o /tmp/lw-never.png", "  render INPUT"},
        {"phantom --size 8 --kind cube -o /tmp/lw-never.nrrd", "  phantom --size"},
        {"bench-mc --size 8 --repeat x", "  bench-mc"},
        {"bench-import", "  bench-import PATH"},
        {"accuracy extra", "  accuracy"},
    };
    for (const auto& c : cases) {
        const lw::test::CliResult r = runCliWithStderr(c.arguments);
        EXPECT_EQ(r.exitCode, 2) << c.arguments << "\n" << r.out;
        EXPECT_NE(r.out.find("\n" + c.usage), std::string::npos) << c.arguments << "\n" << r.out;
    }
    EXPECT_EQ(runCli(""), 2);
    EXPECT_EQ(runCli("no-such-command"), 2);
    const lw::test::CliResult help = lw::test::runCli("help");
    EXPECT_EQ(help.exitCode, 0);
    // Only what a clone of the project has: the phantom's reference script is not part of it.
    EXPECT_EQ(help.out.find("phantom.py"), std::string::npos) << help.out;
}

TEST(CliUsage, UnreadableInputExitsOne) {
    const lw::test::CliResult info = runCliWithStderr("info /nonexistent/volume.nrrd");
    EXPECT_EQ(info.exitCode, 1) << info.out;
    EXPECT_NE(info.out.find("/nonexistent/volume.nrrd"), std::string::npos) << info.out;
    EXPECT_EQ(info.out.find("usage"), std::string::npos) << info.out;
    EXPECT_EQ(runCli("render /nonexistent/volume.nrrd --iso 300 -o /tmp/lw-never.png"), 1);
}

// --suggestive draws the suggestive contours with the silhouette: the silhouette's pixels stay
// and new ones come (the CT phantom's bone has concave folds), in PNG and in SVG; the iso panel
// alone has no lines to add them to.
TEST(RenderCommand, SuggestiveAddsLinesToTheSilhouette) {
    const auto plain = outputPath("suggestive_off.png");
    const auto with = outputPath("suggestive_on.png");
    const std::string common =
        "render phantom:64 --iso 300.5 --size 160x120 --view 30,10 --backend cpu ";
    ASSERT_EQ(runCli(common + "-o '" + plain.string() + "'"), 0);
    ASSERT_EQ(runCli(common + "--suggestive -o '" + with.string() + "'"), 0);
    const lw::core::ImageRgba8 a = lw::core::readPng(plain);
    const lw::core::ImageRgba8 b = lw::core::readPng(with);
    ASSERT_EQ(a.width(), b.width());
    std::size_t kept = 0, added = 0;
    for (int y = 0; y < a.height(); ++y)
        for (int x = 0; x < a.width(); ++x) {
            const bool inA = a.at(x, y).r < 128, inB = b.at(x, y).r < 128;
            kept += inA && inB;
            added += inB && !inA;
        }
    const std::size_t silhouette = darkPixels(a, 0, a.width());
    ASSERT_GT(silhouette, 100u);
    EXPECT_EQ(kept, silhouette);
    EXPECT_GT(added, 50u);
    // SVG: the suggestive contours' visible parts are paths beside the silhouette's.
    const auto countPaths = [](const std::filesystem::path& path) {
        std::ifstream in(path);
        const std::string svg((std::istreambuf_iterator<char>(in)), {});
        std::size_t paths = 0;
        for (std::size_t at = svg.find("<path"); at != std::string::npos;
             at = svg.find("<path", at + 1))
            ++paths;
        return paths;
    };
    const auto plainSvg = outputPath("suggestive_off.svg");
    const auto withSvg = outputPath("suggestive_on.svg");
    ASSERT_EQ(runCli(common + "-o '" + plainSvg.string() + "'"), 0);
    ASSERT_EQ(runCli(common + "--suggestive -o '" + withSvg.string() + "'"), 0);
    EXPECT_GT(countPaths(plainSvg), 0u);
    EXPECT_GT(countPaths(withSvg), countPaths(plainSvg));
    EXPECT_EQ(
        runCli(common + "--suggestive --panel iso -o '" + outputPath("iso.png").string() + "'"), 2);
}

} // namespace
