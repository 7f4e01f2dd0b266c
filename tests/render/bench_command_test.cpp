// `linework-cli bench --json` as the benchmark page uses it: the output parses as JSON and every
// row carries the keys docs/BENCHMARKS.md is written from, with plausible values.
#include "cli_runner.h"
#include "lw/core/json_reader.h"
#include "test_support.h"

#include <cstdlib>
#include <filesystem>
#include <gtest/gtest.h>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using lw::test::CliResult;
using lw::test::quoted;
using lw::test::runCli;

// The output as a tree the checks below walk: parsed by lw::core::parseJson (nlohmann-json), so
// a malformed document throws instead of being searched for substrings. Keys are unique.
struct Json {
    enum class Kind { Null, Bool, Number, String, Array, Object } kind = Kind::Null;
    bool boolean = false;
    double number = 0.0;
    std::string string;
    std::vector<Json> array;
    std::map<std::string, Json> object;

    const Json& at(const std::string& key) const {
        const auto it = object.find(key);
        if (it == object.end())
            throw std::runtime_error("missing key " + key);
        return it->second;
    }
};

Json treeOf(const lw::core::JsonValue& value) {
    using Type = lw::core::JsonValue::Type;
    Json out;
    static_assert(int(Json::Kind::Object) == int(Type::Object) &&
                  int(Json::Kind::Bool) == int(Type::Bool)); // the same kinds in the same order
    out.kind = Json::Kind(int(value.type()));
    if (value.type() == Type::Bool)
        out.boolean = value.boolean();
    else if (value.isNumber())
        out.number = value.number();
    else if (value.isString())
        out.string = value.string();
    else if (value.isArray())
        for (const auto& item : value.array())
            out.array.push_back(treeOf(item));
    else if (value.isObject())
        for (const auto& [key, member] : value.object())
            if (!out.object.emplace(key, treeOf(member)).second)
                throw std::runtime_error("JSON: duplicate key " + key);
    return out;
}

// Throws (lw::core::Error is a std::runtime_error) for anything that is not strict JSON.
Json parseJson(const std::string& text) {
    return treeOf(lw::core::parseJson(text, "bench --json"));
}

// These tests check the CPU rows and the errors of a machine without a GPU, so the CLI they start
// sees no CUDA device even on the GPU machine (the CUDA paths: render_cuda_backend_tests).
const bool kNoCudaDeviceForTheCli = [] {
    ::setenv("CUDA_VISIBLE_DEVICES", "", 1);
    return true;
}();

TEST(BenchCommand, JsonParserRejectsMalformedText) {
    EXPECT_THROW(parseJson("{\"rows\": [1, 2,]}"), std::runtime_error);
    EXPECT_THROW(parseJson("{\"a\": 1} x"), std::runtime_error);
    EXPECT_EQ(parseJson("{\"a\": [true, null, -1.5e2]}").at("a").array[2].number, -150.0);
}

TEST(BenchCommand, JsonRowsCarryTheKeys) {
    const CliResult result = runCli("bench --sizes 32 --repeat 1 --methods 2,3 --json");
    ASSERT_EQ(result.exitCode, 0) << result.out;
    Json document;
    ASSERT_NO_THROW(document = parseJson(result.out)) << result.out;
    const Json& rows = document.at("rows");
    ASSERT_EQ(rows.kind, Json::Kind::Array);
    // methods 2, 3 x S, L x mode a, b x visibility on, off
    ASSERT_EQ(rows.array.size(), 16u) << result.out;
    std::set<std::string> configurations;
    for (const Json& row : rows.array) {
        for (const char* key : {"method", "variant", "mode", "visibility", "backend", "volume",
                                "ms_median", "triangles", "segments", "stages", "runs"})
            ASSERT_NO_THROW(row.at(key)) << key;
        const double method = row.at("method").number;
        EXPECT_TRUE(method == 2 || method == 3);
        EXPECT_EQ(row.at("backend").string, "cpu");
        EXPECT_EQ(row.at("volume").string, "phantom 32x32x32");
        EXPECT_EQ(row.at("ms_median").kind, Json::Kind::Number);
        EXPECT_GT(row.at("ms_median").number, 0.0);
        EXPECT_GT(row.at("triangles").number, 1000.0);
        EXPECT_GT(row.at("segments").number, 100.0);
        EXPECT_EQ(row.at("runs").number, 1.0);
        for (const char* stage : {"extract", "silhouette", "visibility", "draw"})
            EXPECT_GE(row.at("stages").at(stage).number, 0.0) << stage;
        const std::string variant = row.at("variant").string;
        EXPECT_TRUE(variant == "S" || variant == "L") << variant;
        EXPECT_EQ(row.at("brick_cells").number > 0, variant == "L");
        configurations.insert(std::to_string(int(method)) + variant + row.at("mode").string +
                              row.at("visibility").string);
    }
    EXPECT_EQ(configurations.size(), 16u) << "every configuration exactly once";
    EXPECT_GT(document.at("memory").at("peak_rss_mib").number, 0.0);
}

TEST(BenchCommand, MarchingCubesRowAndPeakMemoryOfOneConfiguration) {
    const CliResult mc = runCli("bench --sizes 32 --repeat 1 --methods mc --json");
    ASSERT_EQ(mc.exitCode, 0) << mc.out;
    const Json rows = parseJson(mc.out).at("rows");
    ASSERT_EQ(rows.array.size(), 2u);
    EXPECT_EQ(rows.array[0].at("method").string, "mc");
    EXPECT_EQ(rows.array[0].at("triangles").number, rows.array[1].at("triangles").number)
        << "S == L";

    const CliResult peak =
        runCli("bench --sizes 32 --repeat 1 --peak-memory-of 3,L --image 64x64 --json");
    ASSERT_EQ(peak.exitCode, 0) << peak.out;
    const Json document = parseJson(peak.out);
    ASSERT_EQ(document.at("rows").array.size(), 4u) << "3 L: modes a, b x visibility on, off only";
    for (const Json& row : document.at("rows").array) {
        EXPECT_EQ(row.at("method").number, 3.0);
        EXPECT_EQ(row.at("variant").string, "L");
    }
    const Json& memory = document.at("memory");
    EXPECT_EQ(memory.at("configuration").string, "3,L");
    EXPECT_NEAR(memory.at("volume_mib").number, 32.0 * 32 * 32 * 2 / (1024 * 1024), 1e-9);
    EXPECT_GE(memory.at("peak_rss_mib").number, memory.at("baseline_rss_mib").number);
    // L keeps no whole mesh: the peak is not compared with one.
    EXPECT_EQ(memory.object.count("mesh_mib"), 0u);

    // S in mode a keeps it on the host: its size and the peak against volume + mesh (issue 30).
    const CliResult kept = runCli(
        "bench --backend cpu --sizes 32 --repeat 1 --peak-memory-of 3,S --modes a --image 64x64 "
        "--json");
    ASSERT_EQ(kept.exitCode, 0) << kept.out;
    const Json keptDocument = parseJson(kept.out);
    const Json& keptMemory = keptDocument.at("memory");
    const double meshMib = keptMemory.at("mesh_mib").number;
    EXPECT_GT(meshMib, 0.0);
    const double ratio =
        keptMemory.at("peak_rss_mib").number / (keptMemory.at("volume_mib").number + meshMib);
    // The JSON numbers carry 10 significant digits.
    EXPECT_NEAR(keptMemory.at("peak_over_volume_and_mesh").number, ratio, 1e-8 * ratio);
}

TEST(BenchCommand, MethodWithoutGlIsReportedAsSkipped) {
    // glvnd then finds no EGL vendor, as on a machine without a GL driver.
    const CliResult result =
        runCli("bench --sizes 32 --repeat 1 --methods 1,3 --variants S --modes a --json",
               "__EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl_vendor.json ");
    ASSERT_EQ(result.exitCode, 0) << result.out;
    const Json rows = parseJson(result.out).at("rows");
    ASSERT_EQ(rows.array.size(), 4u) << "method 1's rows are reported, not dropped";
    for (const Json& row : rows.array) {
        if (row.at("method").number == 1) {
            EXPECT_EQ(row.at("ms_median").kind, Json::Kind::Null);
            EXPECT_NE(row.at("skipped").string.find("no OpenGL context"), std::string::npos)
                << row.at("skipped").string;
        } else {
            EXPECT_GT(row.at("ms_median").number, 0.0);
            EXPECT_EQ(row.object.count("skipped"), 0u);
        }
    }
}

// --border and --min-stroke time a frame as the review draws it; the report says what ran. The
// defaults stay as the tables were measured: closed at the border, no stroke pruning.
TEST(BenchCommand, BorderAndStrokePruningAreOptions) {
    const std::string base = "bench --sizes 32 --repeat 1 --methods 3 --variants S --modes a ";
    const CliResult defaults = runCli(base + "--json");
    ASSERT_EQ(defaults.exitCode, 0) << defaults.err;
    const Json plain = parseJson(defaults.out);
    EXPECT_EQ(plain.at("border").string, "closed");
    EXPECT_EQ(plain.at("min_stroke").number, 0.0);

    const CliResult open = runCli(base + "--border open --min-stroke 10 --json");
    ASSERT_EQ(open.exitCode, 0) << open.err;
    const Json document = parseJson(open.out);
    EXPECT_EQ(document.at("border").string, "open");
    EXPECT_EQ(document.at("min_stroke").number, 10.0);
    ASSERT_EQ(document.at("rows").array.size(), 2u);
    for (const Json& row : document.at("rows").array)
        EXPECT_GT(row.at("ms_median").number, 0.0);
    // The phantom lies inside the volume: closing adds nothing, so the same segments.
    EXPECT_EQ(document.at("rows").array[0].at("segments").number,
              plain.at("rows").array[0].at("segments").number);

    const CliResult text = runCli(base + "--border closed --min-stroke 10");
    ASSERT_EQ(text.exitCode, 0) << text.err;
    EXPECT_NE(text.out.find("border closed, min stroke 10 px, gradient central"), std::string::npos)
        << text.out;
    EXPECT_EQ(plain.at("gradient").string, "central");
}

// --gradient smoothed: the normals of a noisy scan (voxel_grid.h); the surface's triangles are
// the same, the silhouette segments (from the normals) are not.
TEST(BenchCommand, GradientStencilIsAnOption) {
    const std::string base = "bench --sizes 32 --repeat 1 --methods 3 --variants S --modes a ";
    const CliResult central = runCli(base + "--json");
    const CliResult smoothed = runCli(base + "--gradient smoothed --json");
    ASSERT_EQ(central.exitCode, 0) << central.err;
    ASSERT_EQ(smoothed.exitCode, 0) << smoothed.err;
    const Json a = parseJson(central.out), b = parseJson(smoothed.out);
    EXPECT_EQ(b.at("gradient").string, "smoothed");
    EXPECT_EQ(a.at("rows").array[0].at("triangles").number,
              b.at("rows").array[0].at("triangles").number);
    EXPECT_NE(a.at("rows").array[0].at("segments").number,
              b.at("rows").array[0].at("segments").number);
    const CliResult bad = runCli("bench --sizes 32 --gradient sobel");
    EXPECT_EQ(bad.exitCode, 2);
    EXPECT_NE(bad.err.find("--gradient sobel: expected central or smoothed"), std::string::npos)
        << bad.err;
}

TEST(BenchCommand, BadBorderOrMinStrokeIsAUsageError) {
    const CliResult border = runCli("bench --sizes 32 --border shut");
    EXPECT_EQ(border.exitCode, 2);
    EXPECT_NE(border.err.find("--border shut: expected closed or open"), std::string::npos)
        << border.err;
    EXPECT_NE(border.err.find("[--border closed|open] [--min-stroke PX]"), std::string::npos)
        << "the usage names the options";
    for (const char* value : {"-1", "ten"}) {
        const CliResult stroke = runCli(std::string("bench --sizes 32 --min-stroke ") + value);
        EXPECT_EQ(stroke.exitCode, 2) << value;
        EXPECT_NE(stroke.err.find("--min-stroke"), std::string::npos) << stroke.err;
    }
}

// A DICOM series reaches `bench --input` through `convert` (bench reads volume files only).
TEST(BenchCommand, ConvertWritesAnInputForBench) {
    const lw::test::TempDir dir;
    const std::string nrrd = (dir / "phantom.nrrd").string();
    const CliResult convert = runCli("convert phantom:32 -o " + quoted(nrrd));
    ASSERT_EQ(convert.exitCode, 0) << convert.err;
    EXPECT_NE(convert.out.find("32x32x32"), std::string::npos) << convert.out;
    const CliResult bench = runCli("bench --input " + quoted(nrrd) +
                                   " --iso 300.5 --repeat 1 --methods 3 --variants S --modes a "
                                   "--json");
    ASSERT_EQ(bench.exitCode, 0) << bench.err;
    const Json rows = parseJson(bench.out).at("rows");
    ASSERT_EQ(rows.array.size(), 2u);
    EXPECT_GT(rows.array[0].at("segments").number, 100.0);
    EXPECT_EQ(runCli("convert phantom:8 -o " + quoted((dir / "x.png").string())).exitCode, 2)
        << "NRRD only";
    EXPECT_EQ(runCli("convert -o " + quoted(nrrd)).exitCode, 2) << "no INPUT";
}

TEST(BenchCommand, BadOptionsFailWithAUsageError) {
    EXPECT_EQ(runCli("bench --sizes 32 --backend cuda").exitCode, 1) << "no CUDA device";
    EXPECT_EQ(runCli("bench --sizes 32 --methods 4").exitCode, 2);
    EXPECT_EQ(runCli("bench --sizes 0").exitCode, 2);
    EXPECT_EQ(runCli("bench --sizes 32 --repeat 0").exitCode, 2);
    EXPECT_EQ(runCli("bench --sizes 32,48 --peak-memory-of 3,L").exitCode, 2);
    EXPECT_EQ(runCli("bench --input /nonexistent.nrrd").exitCode, 2) << "--input needs --iso";
    EXPECT_EQ(runCli("bench --input /nonexistent.nrrd --iso 300 --methods 3 --variants S").exitCode,
              1)
        << "an input that cannot be read";
}

} // namespace
