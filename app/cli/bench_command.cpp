// `linework-cli bench`: the paper's Table 1 (marching cubes) and Tables 2-4 (methods 1/2/3 x S/L
// x mode a/b x visibility on/off) on the benchmark phantom or a volume file, plus peak memory.
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/core/error.h"
#include "lw/core/json_writer.h"
#include "lw/core/log.h"
#include "lw/render/aabb.h"
#include "lw/render/camera.h"
#include "lw/render/cuda_iso_surface.h"
#include "lw/render/iso_surface.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/silhouette_methods.h"
#include "lw/render/surface_sampling.h"
#include "lw/volume/phantom.h"
#include "lw/volume/volume_reader.h"
#include "panel_rendering.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace lw::cli {
namespace {

constexpr core::LogCategory kLog("lw.cli");

// The paper's view of the tables: a fixed oblique view, so the silhouette is neither a
// symmetric front view nor empty; every timed run turns it by kViewStepDeg so that mode a
// measures a genuinely new view with the extraction cached.
constexpr double kAzimuthDeg = 30.0;
constexpr double kElevationDeg = 20.0;
constexpr double kViewStepDeg = 1.0;

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> values) {
    if (values.empty())
        return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// A field of /proc/self/status in bytes (VmHWM: peak resident set, VmRSS: current); 0 where
// the file or field is missing (not Linux).
std::size_t procStatusBytes(const std::string& field) {
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind(field + ":", 0) == 0) {
            std::istringstream values(line.substr(field.size() + 1));
            std::size_t kib = 0;
            values >> kib;
            return kib * 1024;
        }
    }
    return 0;
}

double mib(std::size_t bytes) {
    return double(bytes) / (1024.0 * 1024.0);
}

struct BenchVolume {
    std::string label;
    volume::Volume volume;
    double iso = volume::kPhantomBoneIso;
};

struct Row {
    std::string method; // a silhouette method's key or "mc"
    std::string variant;
    std::string mode;               // empty for mc (it always extracts)
    std::optional<bool> visibility; // none for mc
    std::string backend;
    std::string volume;
    int brickCells = 0;
    double msMedian = 0.0;
    double msMin = 0.0;
    std::size_t triangles = 0;
    std::size_t segments = 0;
    render::StageTimes stages; // median of each stage over the runs
    int runs = 0;
    std::string skipped;         // why the row did not run; empty when it did
    std::size_t deviceBytes = 0; // CUDA: device memory the first frame held at the most
    // The whole mesh the CPU keeps on the host (marching cubes, S in mode a); 0 where none is.
    std::size_t hostMeshBytes = 0;
};

std::size_t hostBytesOf(const render::Mesh& mesh) {
    return std::size_t(kernels::meshBytes(mesh.vertexCount(), mesh.triangleCount()));
}

struct Plan {
    std::vector<std::string> methods; // in order, "mc" and method keys
    std::vector<std::string> variants;
    std::vector<std::string> modes;
    std::vector<bool> visibilities{true, false};
    render::Backend backend = render::Backend::Auto;
    int repeat = 5;
    glm::ivec2 image{1024, 1024};
    unsigned threads = 0;
    std::size_t gpuMemoryBudget = 0; // --gpu-budget (MiB), 0 = free memory less a margin
    // --border, --min-stroke: by default the surface closed at the border (the renderers' own
    // default) and no stroke pruning, as the tables have been measured; `--border closed
    // --min-stroke 10` times what the review draws.
    bool closeAtBorder = true;
    int minStrokePixels = 0;
    render::GradientStencil gradientStencil = render::GradientStencil::Central; // --gradient
    // --oversample, --thick-slices: off and linear by default (the methods on the grid as
    // given); auto and smooth time what the review draws on a coarse or thick-slice volume
    // (render/surface_sampling.h).
    render::VolumeSampling sampling = render::kSamplingAsLoaded;
    core::ImportLimits limits; // --max-volume-gib
};

int brickCellsFor(const std::string& variant, const volume::Volume& volume) {
    return variant == "L" ? render::parseChunks("auto", volume.dims()) : 0;
}

// Marching cubes alone (Table 1): the brick grid is built once, as a viewer does for one
// volume, and the extraction is timed; the same path as `bench-mc`.
// On CUDA (S only: the chunked extraction runs on the CPU) the volume is uploaded once, then each
// extraction is timed: ms_median is the wall time of the call (kernels, scans and the two
// read-backs of the counts), stages.extract the kernels alone from CUDA events; the upload is a
// note.
Row benchMarchingCubesCuda(const BenchVolume& input, const Plan& plan,
                           std::vector<std::string>& notes) {
    Row row;
    row.method = "mc";
    row.variant = "S";
    row.backend = "cuda";
    row.volume = input.label;
    render::CudaIsoSurfaceExtractor extractor(input.volume);
    notes.push_back(input.label + ": volume upload " + std::to_string(extractor.uploadMs()) +
                    " ms (pageable host memory)");
    // Marching cubes as other libraries do it (the comparison): the surface open at the border.
    render::CudaExtraction result = extractor.extract(input.iso); // warm-up
    std::vector<double> times, device, stages[4];
    for (int i = 0; i < plan.repeat; ++i) {
        const auto start = Clock::now();
        result = extractor.extract(input.iso);
        times.push_back(msSince(start));
        device.push_back(result.deviceMs);
        const double stage[4] = {result.bricksMs, result.classifyMs, result.countMs,
                                 result.generateMs};
        for (int s = 0; s < 4; ++s)
            stages[s].push_back(stage[s]);
    }
    notes.push_back(input.label + ": CUDA marching cubes stages (median ms): bricks " +
                    std::to_string(median(stages[0])) + ", classify " +
                    std::to_string(median(stages[1])) + ", count " +
                    std::to_string(median(stages[2])) + ", generate " +
                    std::to_string(median(stages[3])));
    row.msMedian = median(times);
    row.msMin = *std::min_element(times.begin(), times.end());
    row.stages.extractMs = median(device);
    row.triangles = result.triangles;
    row.runs = plan.repeat;
    return row;
}

Row benchMarchingCubes(const BenchVolume& input, const std::string& variant, const Plan& plan,
                       std::vector<std::string>& notes) {
    if (variant == "S" && render::resolveBackend(plan.backend) == render::Backend::Cuda)
        return benchMarchingCubesCuda(input, plan, notes);
    Row row;
    row.method = "mc";
    row.variant = variant;
    row.backend = "cpu";
    row.volume = input.label;
    render::IsoSurfaceOptions options;
    options.brickCells = row.brickCells = brickCellsFor(variant, input.volume);
    options.threads = plan.threads;
    const render::IsoSurfaceExtractor extractor(input.volume, options);
    render::Mesh mesh;
    extractor.extract(input.iso, mesh); // warm-up: first-touch faults of the output buffers
    std::vector<double> times;
    for (int i = 0; i < plan.repeat; ++i) {
        const auto start = Clock::now();
        extractor.extract(input.iso, mesh);
        times.push_back(msSince(start));
    }
    row.msMedian = median(times);
    row.msMin = *std::min_element(times.begin(), times.end());
    row.stages.extractMs = row.msMedian;
    row.triangles = mesh.triangleCount();
    row.hostMeshBytes = hostBytesOf(mesh);
    row.runs = plan.repeat;
    return row;
}

// One configuration of a silhouette method: a warm-up frame at the base view (in mode a it
// fills the cache; its triangles and segments are the row's), then `repeat` frames, each one
// kViewStepDeg further round.
Row benchConfiguration(render::SilhouetteRenderer& renderer, const BenchVolume& input,
                       const std::string& variant, const std::string& mode, bool visibility,
                       const Plan& plan) {
    Row row;
    row.method = std::to_string(int(renderer.method()));
    row.variant = variant;
    row.mode = mode;
    row.visibility = visibility;
    row.backend = std::string(renderer.backendName());
    row.volume = input.label;

    render::SilhouetteSettings settings;
    settings.isoReal = input.iso;
    settings.brickCells = row.brickCells = brickCellsFor(variant, input.volume);
    settings.mode =
        mode == "a" ? render::ExtractionMode::CachedA : render::ExtractionMode::EveryFrameB;
    settings.visibility = visibility;
    settings.threads = plan.threads;
    settings.gpuMemoryBudget = plan.gpuMemoryBudget;
    settings.closeAtBorder = plan.closeAtBorder;
    settings.minStrokePixels = plan.minStrokePixels;
    settings.gradientStencil = plan.gradientStencil;

    render::CameraSetup setup;
    setup.bounds = render::volumeBounds(input.volume);
    setup.azimuthDeg = kAzimuthDeg;
    setup.elevationDeg = kElevationDeg;
    setup.projection = render::Projection::Perspective;
    render::Camera camera(setup, plan.image.x, plan.image.y);

    const render::SilhouetteFrame first = renderer.render(camera, settings);
    row.triangles = first.triangles;
    row.segments = first.segments;
    row.deviceBytes = first.deviceBytes;
    if (row.backend == "cpu" && variant == "S" && mode == "a")
        if (const render::Mesh* mesh = renderer.surfaceMesh())
            row.hostMeshBytes = hostBytesOf(*mesh);

    std::vector<double> totals, extract, silhouette, visibilityTimes, draw;
    for (int i = 1; i <= plan.repeat; ++i) {
        camera.setView(kAzimuthDeg + i * kViewStepDeg, kElevationDeg);
        const auto start = Clock::now();
        const render::SilhouetteFrame frame = renderer.render(camera, settings);
        totals.push_back(msSince(start));
        extract.push_back(frame.times.extractMs);
        silhouette.push_back(frame.times.silhouetteMs);
        visibilityTimes.push_back(frame.times.visibilityMs);
        draw.push_back(frame.times.drawMs);
    }
    row.msMedian = median(totals);
    row.msMin = *std::min_element(totals.begin(), totals.end());
    row.stages = {median(extract), median(silhouette), median(visibilityTimes), median(draw)};
    row.runs = plan.repeat;
    return row;
}

void benchVolume(const BenchVolume& input, const Plan& plan, std::vector<Row>& rows,
                 std::vector<std::string>& notes) {
    for (const std::string& method : plan.methods) {
        if (method == "mc") {
            for (const std::string& variant : plan.variants)
                rows.push_back(benchMarchingCubes(input, variant, plan, notes));
            continue;
        }
        std::unique_ptr<render::SilhouetteRenderer> renderer;
        std::string skipped;
        const render::SilhouetteMethodInfo& info =
            render::silhouetteMethodInfo(render::parseSilhouetteMethod(method, "--methods"));
        try {
            std::string note;
            renderer = render::createSilhouetteRenderer(info.method, plan.backend, &note);
            if (!note.empty() && std::find(notes.begin(), notes.end(), note) == notes.end())
                notes.push_back(note);
            renderer->setVolume(input.volume);
        } catch (const core::Error& error) {
            // Only an unavailable method is skipped (no GL context, no CUDA kernels for it);
            // anything else is a failure.
            if (!info.needsOpenGl)
                throw;
            skipped = error.what();
            kLog.warning("bench: method " + method + " skipped: " + skipped);
        }
        for (const std::string& variant : plan.variants)
            for (const std::string& mode : plan.modes)
                for (const bool visibility : plan.visibilities) {
                    if (renderer) {
                        rows.push_back(
                            benchConfiguration(*renderer, input, variant, mode, visibility, plan));
                        continue;
                    }
                    Row row;
                    row.method = method;
                    row.variant = variant;
                    row.mode = mode;
                    row.visibility = visibility;
                    row.backend =
                        info.needsOpenGl ? "gl" : std::string(render::backendName(plan.backend));
                    row.volume = input.label;
                    row.brickCells = brickCellsFor(variant, input.volume);
                    row.skipped = skipped;
                    rows.push_back(row);
                }
    }
}

void writeJsonRow(core::JsonWriter& writer, const Row& row) {
    writer.beginObject();
    if (row.method == "mc")
        writer.field("method", "mc");
    else
        writer.field("method", std::stoi(row.method));
    writer.field("variant", row.variant);
    writer.key("mode");
    row.mode.empty() ? writer.null() : writer.value(row.mode);
    writer.key("visibility");
    row.visibility ? writer.value(*row.visibility ? "on" : "off") : writer.null();
    writer.field("backend", row.backend)
        .field("volume", row.volume)
        .field("brick_cells", row.brickCells);
    writer.key("ms_median");
    row.skipped.empty() ? writer.value(row.msMedian) : writer.null();
    writer.key("ms_min");
    row.skipped.empty() ? writer.value(row.msMin) : writer.null();
    writer.field("triangles", row.triangles).field("segments", row.segments);
    writer.key("stages").beginObject();
    writer.field("extract", row.stages.extractMs).field("silhouette", row.stages.silhouetteMs);
    writer.field("visibility", row.stages.visibilityMs).field("draw", row.stages.drawMs);
    writer.endObject();
    writer.field("runs", row.runs);
    if (row.deviceBytes > 0)
        writer.field("device_mib", double(row.deviceBytes) / double(1 << 20));
    if (!row.skipped.empty())
        writer.field("skipped", row.skipped);
    writer.endObject();
}

void writeTextRow(std::ostream& out, const Row& row) {
    char line[512];
    const char* visibility = !row.visibility ? "-" : *row.visibility ? "on" : "off";
    if (!row.skipped.empty()) {
        // The EGL reason lists one platform per line; a table row keeps it on one.
        std::string reason;
        for (const char c : row.skipped) {
            if (c == '\n')
                reason += ";";
            else if (!(c == ' ' && !reason.empty() &&
                       (reason.back() == ' ' || reason.back() == ';')))
                reason += c;
            if (c == '\n')
                reason += ' ';
        }
        std::snprintf(line, sizeof line,
                      "%-6s %-7s %-4s %-4s %-5s %-14s skipped: ", row.method.c_str(),
                      row.variant.c_str(), row.mode.empty() ? "-" : row.mode.c_str(), visibility,
                      row.backend.c_str(), row.volume.c_str());
        out << line << reason << "\n"; // the reason may be longer than `line`
        return;
    } else {
        std::snprintf(
            line, sizeof line,
            "%-6s %-7s %-4s %-4s %-5s %-14s %9.1f %9.1f %10zu %9zu %8.1f %8.1f %8.1f %8.1f\n",
            row.method.c_str(), row.variant.c_str(), row.mode.empty() ? "-" : row.mode.c_str(),
            visibility, row.backend.c_str(), row.volume.c_str(), row.msMedian, row.msMin,
            row.triangles, row.segments, row.stages.extractMs, row.stages.silhouetteMs,
            row.stages.visibilityMs, row.stages.drawMs);
    }
    out << line;
}

// What bench measures: "mc" (marching cubes alone) and every silhouette method's key.
std::string benchChoices(const char* separator) {
    std::string choices = "mc";
    for (const render::SilhouetteMethodInfo& info : render::silhouetteMethods()) {
        choices += separator;
        choices += info.key;
    }
    return choices;
}

std::vector<std::string> parseChoiceList(const std::string& text, const std::string& option,
                                         const std::vector<std::string>& allowed) {
    std::vector<std::string> values;
    for (const std::string& part : splitList(text)) {
        if (std::find(allowed.begin(), allowed.end(), part) == allowed.end()) {
            std::string expected;
            for (const std::string& a : allowed)
                expected += (expected.empty() ? "" : ", ") + a;
            throw UsageError(option + " " + text, "'" + part + "' is not one of " + expected);
        }
        if (std::find(values.begin(), values.end(), part) == values.end())
            values.push_back(part);
    }
    if (values.empty())
        throw UsageError(option, "the list is empty");
    return values;
}

} // namespace

namespace {

const std::set<std::string> kBenchOptions = {
    "sizes",          "input",        "iso",        "backend",       "methods",
    "variants",       "modes",        "repeat",     "image",         "threads",
    "peak-memory-of", "gpu-budget",   "border",     "min-stroke",    "gradient",
    "oversample",     "thick-slices", "thin-walls", kMaxVolumeOption};

// What to run: methods, variants, modes, repeat, image, threads, budget; --peak-memory-of
// narrows it to one configuration (returned in `peakMethod`).
Plan parsePlan(const Arguments& arguments, std::optional<std::string>& peakMethod) {
    Plan plan;
    plan.backend =
        parseUsage([&] { return render::parseBackend(arguments.option("backend", "auto")); });
    render::resolveBackend(plan.backend); // fail before the first run (no CUDA device)
    plan.methods = parseChoiceList(arguments.option("methods", benchChoices(",")), "--methods",
                                   splitList(benchChoices(",")));
    plan.variants = parseChoiceList(arguments.option("variants", "S,L"), "--variants", {"S", "L"});
    plan.modes = parseChoiceList(arguments.option("modes", "a,b"), "--modes", {"a", "b"});
    const double repeat = arguments.number("repeat", 5);
    if (repeat < 1 || repeat != double(int(repeat)))
        throw UsageError("--repeat", "expected a whole number >= 1");
    plan.repeat = int(repeat);
    plan.threads = unsigned(std::max(0.0, arguments.number("threads", 0)));
    const double budgetMiB = arguments.number("gpu-budget", 0);
    if (budgetMiB < 0)
        throw UsageError("--gpu-budget", "expected MiB >= 0 (0: the free device memory)");
    plan.gpuMemoryBudget = std::size_t(budgetMiB * 1024.0 * 1024.0);
    if (const auto image = arguments.option("image"))
        plan.image = parseImageSize("--image", *image, 2);
    render::SilhouetteSettings lines; // closed at the border unless --border open
    parseLineOptions(arguments, 0, lines);
    plan.closeAtBorder = lines.closeAtBorder;
    plan.minStrokePixels = lines.minStrokePixels;
    plan.gradientStencil = lines.gradientStencil;
    plan.sampling = parseVolumeSampling(arguments, render::kSamplingAsLoaded);
    plan.limits = importLimits(arguments);
    if (const auto peak = arguments.option("peak-memory-of")) {
        const std::vector<std::string> parts = splitList(*peak);
        if (parts.size() != 2)
            throw UsageError("--peak-memory-of " + *peak, "expected METHOD,VARIANT, e.g. 3,L");
        plan.methods = parseChoiceList(parts[0], "--peak-memory-of", splitList(benchChoices(",")));
        plan.variants = parseChoiceList(parts[1], "--peak-memory-of", {"S", "L"});
        peakMethod = *peak;
    }
    return plan;
}

// The volumes: the phantom at each size, or the given file (one volume); checked before the
// first (possibly long) run.
std::vector<std::string> parseVolumeSpecs(const Arguments& arguments, bool onePerProcess) {
    std::vector<std::string> specs;
    if (const auto input = arguments.option("input")) {
        if (arguments.option("sizes"))
            throw UsageError("bench", "--input and --sizes exclude each other");
        if (!arguments.option("iso"))
            throw UsageError("--input " + *input,
                             "needs --iso HU (the iso-value of the surface to extract)");
        specs.push_back(*input);
    } else {
        specs = splitList(arguments.option("sizes", "32,256"));
        if (specs.empty())
            throw UsageError("--sizes", "the list is empty");
        for (const std::string& size : specs)
            parseDimsOption("--sizes", size, 2);
    }
    if (onePerProcess && specs.size() != 1)
        throw UsageError("--peak-memory-of",
                         "measures one volume per process: give one size or --input");
    return specs;
}

// What the whole run measured, for either report.
struct BenchResult {
    std::vector<Row> rows;
    std::vector<std::string> notes;
    std::optional<std::string> peakMethod;
    std::size_t baselineRss = 0, peakRss = 0, volumeBytes = 0;
    std::size_t meshBytes = 0; // the largest host mesh a row kept (0: none)
    // The peak against what the data itself takes (issue 30's goal: at most 1.15).
    double peakOverData() const {
        return double(peakRss) / double(std::max<std::size_t>(1, volumeBytes + meshBytes));
    }
    // Over the volume and the process's own start-up footprint: what the methods added.
    double extraPercent() const {
        const double extra = double(peakRss) - double(baselineRss) - double(volumeBytes);
        return volumeBytes ? 100.0 * extra / double(volumeBytes) : 0.0;
    }
};

void writeJsonReport(const Plan& plan, const BenchResult& result, std::ostream& out) {
    core::JsonWriter writer;
    writer.beginObject();
    writer.field("view", "az " + std::to_string(int(kAzimuthDeg)) + " el " +
                             std::to_string(int(kElevationDeg)) + " perspective, +" +
                             std::to_string(int(kViewStepDeg)) + " deg az per run");
    writer.field("image", std::to_string(plan.image.x) + "x" + std::to_string(plan.image.y));
    writer.field("repeat", plan.repeat);
    writer.field("border", plan.closeAtBorder ? "closed" : "open");
    writer.field("min_stroke", plan.minStrokePixels);
    writer.field("gradient", render::gradientStencilName(plan.gradientStencil));
    writer.field("oversample", render::oversamplingName(plan.sampling.oversampling));
    writer.field("thick_slices", render::thickSlicesName(plan.sampling.thickSlices));
    writer.field("thin_walls_mm", plan.sampling.thinWallMm);
    writer.key("notes").beginArray();
    for (const std::string& note : result.notes)
        writer.value(note);
    writer.endArray();
    writer.key("rows").beginArray();
    for (const Row& row : result.rows)
        writeJsonRow(writer, row);
    writer.endArray();
    writer.key("memory").beginObject();
    if (result.peakMethod)
        writer.field("configuration", *result.peakMethod);
    writer.field("peak_rss_mib", mib(result.peakRss))
        .field("baseline_rss_mib", mib(result.baselineRss));
    writer.field("volume_mib", mib(result.volumeBytes))
        .field("extra_over_volume_percent", result.extraPercent());
    if (result.meshBytes)
        writer.field("mesh_mib", mib(result.meshBytes))
            .field("peak_over_volume_and_mesh", result.peakOverData());
    writer.endObject();
    writer.endObject();
    out << writer.str() << "\n";
}

void writeTextReport(const Plan& plan, const BenchResult& result, std::ostream& out) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "bench: view az %g el %g perspective (+%g deg per run), image %dx%d, median of "
                  "%d runs after a warm-up; border %s, min stroke %d px, gradient %s, "
                  "oversample %s, thick slices %s, thin walls %g mm\n",
                  kAzimuthDeg, kElevationDeg, kViewStepDeg, plan.image.x, plan.image.y, plan.repeat,
                  plan.closeAtBorder ? "closed" : "open", plan.minStrokePixels,
                  render::gradientStencilName(plan.gradientStencil).data(),
                  render::oversamplingName(plan.sampling.oversampling).data(),
                  render::thickSlicesName(plan.sampling.thickSlices).data(),
                  plan.sampling.thinWallMm);
    out << line;
    std::snprintf(line, sizeof line,
                  "%-6s %-7s %-4s %-4s %-5s %-14s %9s %9s %10s %9s %8s %8s %8s %8s\n", "method",
                  "variant", "mode", "vis", "back", "volume", "ms_median", "ms_min", "triangles",
                  "segments", "extract", "silh", "visib", "draw");
    out << line;
    for (const Row& row : result.rows)
        writeTextRow(out, row);
    for (const std::string& note : result.notes)
        out << "note: " << note << "\n";
    const std::optional<std::string>& peak = result.peakMethod;
    std::snprintf(line, sizeof line,
                  "peak memory%s%s: %.1f MiB (VmHWM); start-up %.1f MiB, volume %.1f MiB, extra "
                  "%.1f%% of the volume\n",
                  peak ? " of " : "", peak ? peak->c_str() : "", mib(result.peakRss),
                  mib(result.baselineRss), mib(result.volumeBytes), result.extraPercent());
    out << line;
    if (result.meshBytes) {
        std::snprintf(line, sizeof line, "host mesh %.1f MiB: peak = %.3f x (volume + mesh)\n",
                      mib(result.meshBytes), result.peakOverData());
        out << line;
    }
}

} // namespace

namespace {

// The drawn copy of a shape-based (thick-slice) volume, made per iso-value: on the host and, where
// the back-end is CUDA, on the device (the slices uploaded once, as the review does), each timed
// over the runs. A note; the rows then draw the host's copy (the same voxels).
void noteDrawnCopyTimes(const BenchVolume& input, const Plan& plan,
                        std::vector<std::string>& notes) {
    if (!render::samplingPlan(input.volume.dims(), input.volume.geometry(), plan.sampling)
             .dependsOnIso())
        return;
    const auto source = std::make_shared<const volume::Volume>(input.volume.clone());
    std::vector<double> fresh, kept, device;
    for (int i = 0; i < plan.repeat; ++i) {
        const auto start = Clock::now();
        render::volumeToRender(source, plan.sampling, input.iso, plan.threads);
        fresh.push_back(msSince(start));
    }
    // As the review makes it: into a copy kept from the iso-value before.
    render::DrawnVolumeMaker hostMaker(source, render::Backend::Cpu);
    hostMaker.make(plan.sampling, input.iso, plan.threads);
    for (int i = 0; i < plan.repeat; ++i) {
        const auto start = Clock::now();
        hostMaker.make(plan.sampling, input.iso, plan.threads);
        kept.push_back(msSince(start));
    }
    std::string note =
        input.label + ": the drawn copy (thick slices, each iso-value) on the host " +
        std::to_string(median(kept)) + " ms into a kept copy, as the review makes it (" +
        std::to_string(median(fresh)) + " ms into a new volume)";
    render::DrawnVolumeMaker maker(source, plan.backend);
    maker.make(plan.sampling, input.iso, plan.threads); // the slices' upload, once a volume
    if (maker.lastMadeOnDevice()) {
        std::vector<double> distances, refinements, downloads;
        for (int i = 0; i < plan.repeat; ++i) {
            const auto start = Clock::now();
            maker.make(plan.sampling, input.iso, plan.threads);
            device.push_back(msSince(start));
            const render::DeviceCopyTimes stages = maker.lastDeviceTimes();
            distances.push_back(stages.distanceMs);
            refinements.push_back(stages.refinementMs);
            downloads.push_back(stages.downloadMs);
        }
        note += ", on the CUDA device " + std::to_string(median(device)) +
                " ms (kernels and the copy's download; stages by CUDA events: distances " +
                std::to_string(median(distances)) + ", refinement " +
                std::to_string(median(refinements)) + ", download " +
                std::to_string(median(downloads)) + " ms)";
    }
    notes.push_back(note + " (median ms)");
}

} // namespace

int runBench(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json"}, kBenchOptions);
    if (!arguments.positionals().empty())
        throw UsageError("bench", "takes no positional arguments");
    BenchResult result;
    const Plan plan = parsePlan(arguments, result.peakMethod);
    const auto input = arguments.option("input");
    const std::vector<std::string> volumeSpecs =
        parseVolumeSpecs(arguments, result.peakMethod.has_value());

    // The process before any volume exists: what the peak is compared with.
    result.baselineRss = procStatusBytes("VmRSS");
    for (const std::string& spec : volumeSpecs) {
        BenchVolume bench{
            .label = {}, .volume = {}, .iso = arguments.number("iso", volume::kPhantomBoneIso)};
        if (input) {
            bench.volume = volume::readVolumeFile(spec, nullptr, plan.limits);
            bench.label = spec;
        } else {
            const glm::ivec3 dims = parseDimsOption("--sizes", spec, 2);
            bench.volume =
                volume::makePhantom(dims, volume::PhantomKind::Ct, plan.threads, plan.limits);
            bench.label = "phantom " + dimsText(dims);
        }
        noteDrawnCopyTimes(bench, plan, result.notes);
        if (std::optional<volume::Volume> finer =
                render::oversampledToRender(bench.volume, plan.sampling, bench.iso, plan.threads))
            bench.volume = std::move(*finer);
        result.volumeBytes = std::max(result.volumeBytes, bench.volume.byteSize());
        kLog.info("bench: " + bench.label + " (" + dimsText(bench.volume.dims()) + ")");
        benchVolume(bench, plan, result.rows, result.notes);
        for (const Row& row : result.rows)
            result.meshBytes = std::max(result.meshBytes, row.hostMeshBytes);
    }
    result.peakRss = procStatusBytes("VmHWM");
    if (arguments.flag("json"))
        writeJsonReport(plan, result, out);
    else
        writeTextReport(plan, result, out);
    return 0;
}

} // namespace lw::cli
