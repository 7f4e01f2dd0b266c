// openInput on the shared third-party DICOM data: what the CLI and the GUI open.
#include "lw/core/error.h"
#include "lw/input/open_input.h"
#include "test_support.h"

#include <algorithm>
#include <gtest/gtest.h>

namespace fs = std::filesystem;
using namespace lw;

namespace {

fs::path dicomData() {
    const auto dir = test::sharedDataDir();
    if (!dir)
        throw std::runtime_error("shared data missing (the data main should have skipped)");
    return *dir / "dicom";
}

bool anyContains(const std::vector<std::string>& lines, const std::string& text) {
    return std::any_of(lines.begin(), lines.end(), [&](const std::string& line) {
        return line.find(text) != std::string::npos;
    });
}

} // namespace

TEST(OpenInputData, TiltedSeriesWithUnevenGapsHasWarnings) {
    const fs::path folder = dicomData() / "ct_head_ge_hispeed_tilt_varspacing";
    const input::OpenedVolume opened = input::openInput(folder.string());
    EXPECT_EQ(opened.volume.dims(), glm::ivec3(512, 512, 28));
    EXPECT_FALSE(opened.seriesUid.empty());
    EXPECT_NE(opened.description.find("512x512x28"), std::string::npos) << opened.description;
    EXPECT_TRUE(anyContains(opened.warnings, "gantry tilt 18."))
        << ::testing::PrintToString(opened.warnings);
    EXPECT_TRUE(anyContains(opened.warnings, "uneven slice gaps"))
        << ::testing::PrintToString(opened.warnings);
}

TEST(OpenInputData, DicomdirExportWithMissingFiles) {
    const fs::path dicomdir = dicomData() / "ct_headphantom_philips_dicomdir_export" / "DICOMDIR";
    const input::OpenedVolume opened = input::openInput(dicomdir.string());
    EXPECT_GE(opened.volume.dims().z, 2);
    EXPECT_EQ(opened.source, dicomdir.string());
    // Every file the DICOMDIR lists but the export lacks is a warning "file: reason".
    const auto missing =
        std::count_if(opened.warnings.begin(), opened.warnings.end(), [](const std::string& line) {
            return line.find(": referenced by DICOMDIR but missing") != std::string::npos;
        });
    EXPECT_EQ(missing, 338);
}
