// `linework-cli quality` on the shared Philips head phantom (DICOMDIR export, STEREOTAXIS series,
// 300 HU): at az 45 el 0 its plastic plates, under a voxel thick, are seen nearly edge-on and
// their edges break into small closed bits of surface. Each bit must get its contour, so the
// shaded panel's outline is covered (512^2: 0.94 when the marching-cubes normals of those bits
// all faced one way, 0.998 with normals that agree with their edge).
#include "cli_runner.h"
#include "quality_cli.h"
#include "test_support.h"

#include <filesystem>
#include <gtest/gtest.h>
#include <string>

namespace {

// `quality` on the Philips DICOMDIR export at one view; `extra`: the series, view and size. The
// JSON, compacted, after the run succeeded and measured an outline of at least `outlinePixels`.
std::string philipsQuality(const std::string& extra, double outlinePixels) {
    const std::filesystem::path series =
        *lw::test::sharedDataDir() / "dicom" / "ct_headphantom_philips_dicomdir_export";
    const lw::test::CliResult r = lw::test::runCli("quality " + lw::test::quoted(series.string()) +
                                                   " --iso 300 " + extra + " --json");
    EXPECT_EQ(r.exitCode, 0) << r.out << r.err;
    const std::string json = lw::test::compact(r.out);
    EXPECT_GT(lw::test::numberOf(json, "outline_pixels"), outlinePixels) << json;
    return json;
}

} // namespace

TEST(QualityCommandData, ThinPlatesOfThePhilipsPhantomHaveTheirOutline) {
    const std::string json = philipsQuality("--view 45,0 --size 512x512", 800.0);
    EXPECT_GE(lw::test::numberOf(json, "outline_coverage_m3"), 0.98) << json;
    EXPECT_GE(lw::test::numberOf(json, "outline_coverage_m2"), 0.98) << json;
}

// The same phantom's STD BRAIN 5MM series (5 mm slabs, 0.45 mm pixels) seen from below at az 45
// el -35.3: the skull cap's far edge is a surface slanted across the slabs. Its outline is
// covered only when the normals' slab component comes from the slab edge itself (1024^2:
// 0.918 / 0.903 for methods 3 / 2 with central differences across the slabs, 0.992 with the
// edge's own difference).
TEST(QualityCommandData, SkullCapOfAFiveMillimetreSeriesHasItsOutline) {
    const std::string json =
        philipsQuality("--series 1.3.46.670589.33.1.6002432791750815306.26862469513794233732"
                       " --view 45,-35.3 --size 1024x1024",
                       2000.0);
    EXPECT_GE(lw::test::numberOf(json, "outline_coverage_m3"), 0.98) << json;
    EXPECT_GE(lw::test::numberOf(json, "outline_coverage_m2"), 0.98) << json;
}
