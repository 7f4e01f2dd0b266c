// `linework-cli render --panel slice`: a slice of the series with its iso contour, as a user runs
// it. The sphere phantom (1 mm voxels centred on the origin, radius 0.6 of the half-extent, -1000
// outside and +1000 inside) has its edge at iso 0 on a circle around the image's centre.
#include "cli_runner.h"
#include "lw/core/png_io.h"

#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <gtest/gtest.h>
#include <string>

namespace {

std::filesystem::path slicePath(const std::string& name) {
    const std::filesystem::path dir =
        std::filesystem::path(LINEWORK_TEST_OUTPUT_DIR) / "render_slice_command";
    std::filesystem::create_directories(dir);
    const std::filesystem::path path = dir / name;
    std::filesystem::remove(path);
    return path;
}

struct ColourCount {
    int onCircle = 0;  // pixels of the colour within 1.5 px of the sphere's edge
    int offCircle = 0; // pixels of the colour elsewhere
};

ColourCount countColour(const lw::core::ImageRgba8& image, lw::core::Rgba8 colour, double radius) {
    ColourCount count;
    const glm::dvec2 centre(0.5 * (image.width() - 1), 0.5 * (image.height() - 1));
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x) {
            const lw::core::Rgba8 p = image.at(x, y);
            if (p.r != colour.r || p.g != colour.g || p.b != colour.b)
                continue;
            const double r = glm::length(glm::dvec2(x, y) - centre);
            ++(std::abs(r - radius) <= 1.5 ? count.onCircle : count.offCircle);
        }
    return count;
}

TEST(RenderSliceCommand, ContourPixelsInTheLineColourOnTheSpheresEdge) {
    // phantom.py's axes run from -1 to 1 over the 64 voxels: radius 0.6 is 18.9 voxels.
    const double radius = 0.6 * 31.5;
    const struct {
        std::string options;
        lw::core::Rgba8 colour;
    } cases[] = {{"", {255, 255, 0, 255}}, {"--line-colour '#FF00FF'", {255, 0, 255, 255}}};
    for (const auto& c : cases) {
        const auto out = slicePath("sphere_axial.png");
        const auto result = lw::test::runCli("render phantom:64:sphere --iso 0 --panel slice " +
                                             c.options + " -o " + lw::test::quoted(out.string()));
        ASSERT_EQ(result.exitCode, 0) << result.err;
        EXPECT_NE(result.out.find("axial at 0.00 mm"), std::string::npos) << result.out;
        const lw::core::ImageRgba8 image = lw::core::readPng(out);
        ASSERT_EQ(image.width(), 64);
        ASSERT_EQ(image.height(), 64);
        const ColourCount count = countColour(image, c.colour, radius);
        EXPECT_GT(count.onCircle, int(0.8 * 2.0 * 3.14159 * radius)) << c.options;
        EXPECT_EQ(count.offCircle, 0) << c.options;
        // The bone window 2000/500: inside the sphere (+1000 HU) 3/4 grey, outside (-1000 HU) black.
        EXPECT_EQ(image.at(32, 32).r, 191);
        EXPECT_EQ(image.at(32, 32).b, 191);
        EXPECT_EQ(image.at(2, 2).r, 0);
    }
}

TEST(RenderSliceCommand, ThreePlanesHaveTheSeriesExtentInPixels) {
    const struct {
        const char* plane;
        int width, height;
    } planes[] = {{"axial", 40, 50}, {"coronal", 40, 60}, {"sagittal", 50, 60}};
    for (const auto& p : planes) {
        const auto out = slicePath(std::string(p.plane) + ".png");
        const auto result = lw::test::runCli(
            "render phantom:40x50x60:sphere --iso 0 --panel slice --plane " + std::string(p.plane) +
            " --position 3 --window 400/40 -o " + lw::test::quoted(out.string()));
        ASSERT_EQ(result.exitCode, 0) << p.plane << ": " << result.err;
        const lw::core::ImageRgba8 image = lw::core::readPng(out);
        EXPECT_EQ(image.width(), p.width) << p.plane;
        EXPECT_EQ(image.height(), p.height) << p.plane;
    }
}

TEST(RenderSliceCommand, PositionOutsideTheSeriesIsAUsageErrorNamingTheRange) {
    const auto out = slicePath("outside.png");
    const auto result = lw::test::runCli("render phantom:32:sphere --iso 0 --panel slice --plane "
                                         "coronal --position 40 -o " +
                                         lw::test::quoted(out.string()));
    EXPECT_EQ(result.exitCode, 2);
    EXPECT_NE(result.err.find("coronal positions run from -15.50 to 15.50 mm"), std::string::npos)
        << result.err;
    EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(RenderSliceCommand, OptionsThatMakeNoSenseForASliceAreRefused) {
    const auto out = slicePath("refused.png");
    const std::string o = " -o " + lw::test::quoted(out.string());
    for (const std::string arguments : {
             "render phantom:32 --iso 0 --panel slice --method 3",
             "render phantom:32 --iso 0 --panel slice --view 30,10",
             "render phantom:32 --iso 0 --panel slice --size 100x100",
             "render phantom:32 --iso 0 --panel slice --format svg",
             "render phantom:32 --iso 0 --panel slice --hidden-lines",
             "render phantom:32 --iso 0 --panel slice --plane oblique",
             "render phantom:32 --iso 0 --panel slice --window 400",
             "render phantom:32 --iso 0 --panel slice --window -5/40",
             "render phantom:32 --iso 0 --panel slice --line-colour yellow",
             "render phantom:32 --panel slice",
             "render phantom:32 --iso 0 --panel silhouette --plane axial",
             "render phantom:32 --iso 0 --panel both --position 3",
         }) {
        const auto result = lw::test::runCli(arguments + o);
        EXPECT_EQ(result.exitCode, 2) << arguments << ": " << result.err;
        EXPECT_FALSE(std::filesystem::exists(out)) << arguments;
    }
}

} // namespace
