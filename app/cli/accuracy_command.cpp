// `accuracy`: the paper's Table 5, measured. Analytic shapes are sampled on n^3 grids, every
// available silhouette method draws them, and the drawing is scored against the true occluding
// contour traced from the analytic function (true_contour.h), with a 1 pixel tolerance.
//
// By default every method is scored at each view of a sweep over the sphere (view_sweep.h) and
// the worst and median per method, variant, shape and size are reported: the goal is a score at
// every view, not at a chosen one. `--view AZ,EL` scores one view, as the command did before.
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/core/error.h"
#include "lw/core/json_writer.h"
#include "lw/core/png_io.h"
#include "lw/evaluation/analytic_shapes.h"
#include "lw/evaluation/contour_score.h"
#include "lw/evaluation/true_contour.h"
#include "lw/evaluation/view_sweep.h"
#include "lw/render/camera.h"
#include "lw/render/renderer_factory.h"
#include "panel_rendering.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace lw::cli {
namespace {

using evaluation::View;

std::vector<int> parseIntList(const std::string& option, const std::string& text, int minimum) {
    std::vector<int> values;
    for (const std::string& part : splitList(text, ',', false)) {
        int value = 0;
        const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (error != std::errc() || end != part.data() + part.size() || value < minimum)
            throw UsageError("--" + option + " " + text,
                             "expected a comma-separated list of integers >= " +
                                 std::to_string(minimum));
        values.push_back(value);
    }
    if (values.empty())
        throw UsageError("--" + option, "empty list");
    return values;
}

struct Row {
    int method = 0;
    std::string variant;    // S or L
    std::string backend;    // the renderer's: cpu, gl (cuda later)
    std::string visibility; // on | endpoints | along
    std::string shape;
    int size = 0;
    int image = 0;
    std::size_t viewIndex = 0; // in Options::views; rows of one group are sorted by it
    View view;
    evaluation::ContourScore score;
};

// One score over the views of a group: the worst (the first view in sweep order on a tie) and
// the median (the mean of the two middle values for an even count).
struct Spread {
    double worst = 1.0;
    double median = 1.0;
    View worstView;
};

// The rows of one method x visibility x variant x shape x size, over all views.
struct Summary {
    const Row* first = nullptr;
    int views = 0;
    Spread recall;
    Spread precision;
};

// The single view of the command before the sweep: oblique, so no shape is seen along a
// symmetry axis.
constexpr View kSingleView{30.0, 20.0};
constexpr double kPixelsPerVoxel = 2.0;
// The goal of issue 7 (recall and precision at every view); rows that miss it are marked.
constexpr double kGoal = 0.99;

struct Options {
    render::Backend backend = render::Backend::Auto;
    std::vector<int> methods;
    std::vector<int> sizes;
    std::vector<std::string> shapes;
    bool json = false;
    bool sweep = true; // false: one view from --view
    std::vector<View> views;
    // --images DIR: each row's drawing, truth and their difference as PNGs, to look at.
    std::optional<std::filesystem::path> imagesDir;
    render::GradientStencil gradientStencil = render::GradientStencil::Central; // --gradient
};

Options parseOptions(const std::vector<std::string>& args) {
    const Arguments arguments(
        args, {"json"},
        {"backend", "methods", "sizes", "shapes", "view", "views", "images", "gradient"});
    if (!arguments.positionals().empty())
        throw UsageError("accuracy", "takes no positional arguments");
    Options options;
    options.backend =
        parseUsage([&] { return render::parseBackend(arguments.option("backend", "auto")); });
    options.methods = parseIntList("methods", arguments.option("methods", "1,2,3"), 1);
    for (int m : options.methods)
        if (m > 3)
            throw UsageError("--methods", "methods are 1, 2 and 3");
    options.sizes = parseIntList("sizes", arguments.option("sizes", "32,64,256"), 8);
    const std::vector<std::string> known = evaluation::analyticShapeNames();
    options.shapes =
        arguments.option("shapes") ? splitList(*arguments.option("shapes"), ',', false) : known;
    for (const std::string& shape : options.shapes)
        if (std::find(known.begin(), known.end(), shape) == known.end())
            throw UsageError("--shapes " + shape, "not a known shape");
    options.json = arguments.flag("json");
    options.gradientStencil = parseGradientOption(arguments);
    if (const auto images = arguments.option("images"))
        options.imagesDir = *images;
    const ViewChoice choice = parseViewChoice(arguments, evaluation::kDefaultSweepViewCount);
    options.sweep = !choice.single;
    options.views = choice.views;
    return options;
}

using Renderers = std::unique_ptr<render::SilhouetteRenderer>[4];

// One renderer per method, bound to each sampled volume in turn; only method 1 may be missing
// (no OpenGL context), and then it is skipped with a note.
void createRenderers(const Options& options, Renderers& renderers,
                     std::vector<std::string>& notes) {
    for (int m = 1; m <= 3; ++m)
        if (std::find(options.methods.begin(), options.methods.end(), m) != options.methods.end())
            renderers[m] =
                createRendererOrSkip(render::SilhouetteMethod(m), options.backend, notes);
}

// "metaballs-64-m3-on-S-az180-el45": names a row's images.
std::string rowName(const Row& row) {
    char text[160];
    std::snprintf(text, sizeof text, "%s-%d-m%d-%s-%s-az%g-el%g", row.shape.c_str(), row.size,
                  row.method, row.visibility.c_str(), row.variant.c_str(), row.view.azimuthDeg,
                  row.view.elevationDeg);
    return text;
}

// The drawing (black on white), the truth and the diff (contourDiffImage's colours) of a row.
void writeRowImages(const std::filesystem::path& dir, const Row& row,
                    const render::PixelMask& drawn, const render::PixelMask& truth) {
    std::filesystem::create_directories(dir);
    const std::string name = rowName(row);
    const core::Rgba8 black{0, 0, 0, 255}, white{255, 255, 255, 255};
    core::writePng(dir / (name + "-drawn.png"), drawn.toImage(black, white), core::PngFormat::Rgb);
    core::writePng(dir / (name + "-truth.png"), truth.toImage(black, white), core::PngFormat::Rgb);
    core::writePng(dir / (name + "-diff.png"), evaluation::contourDiffImage(drawn, truth, 1),
                   core::PngFormat::Rgb);
}

// Scores every available method, S and L, on one shape sampled at n^3, at every view. The truth
// of a view is traced once and shared by all methods; the volume is bound once per method and
// variant, as a workstation binds it once and then turns the camera.
void measureShape(const std::string& shapeName, int n, const Options& options, Renderers& renderers,
                  std::vector<Row>& rows) {
    const std::vector<View>& views = options.views;
    const std::unique_ptr<evaluation::AnalyticShape> shape =
        evaluation::makeAnalyticShape(shapeName);
    const volume::Volume volume = evaluation::sampleShape(*shape, n);
    // The renderers outlive this shape's volume: unbind them before it goes, however this
    // function is left (the CUDA back-end may hold the volume's memory page-locked).
    struct Unbind {
        Renderers& renderers;
        ~Unbind() {
            for (auto& renderer : renderers)
                if (renderer)
                    renderer->releaseVolume();
        }
    } unbind{renderers};
    std::vector<render::Camera> cameras;
    std::vector<render::PixelMask> truths;
    for (const View& view : views) {
        render::CameraSetup setup;
        setup.bounds = shape->bounds();
        setup.azimuthDeg = view.azimuthDeg;
        setup.elevationDeg = view.elevationDeg;
        const int side = render::Camera::squareSizeForVoxelCoverage(
            setup, volume.geometry().spacingI(), kPixelsPerVoxel);
        cameras.emplace_back(setup, side, side);
        truths.push_back(evaluation::trueContourMask(*shape, cameras.back()));
    }
    // L: a 4 x 4 x 4 brick schedule, so chunking is exercised at every size.
    const int brickCells = std::max(4, (n - 1 + 3) / 4);

    for (const bool chunked : {false, true}) {
        render::SilhouetteSettings settings;
        settings.isoReal = evaluation::kShapeIso;
        settings.brickCells = chunked ? brickCells : 0;
        settings.gradientStencil = options.gradientStencil;
        for (int m = 1; m <= 3; ++m) {
            if (!renderers[m])
                continue;
            render::SilhouetteRenderer& renderer = *renderers[m];
            renderer.setVolume(volume);
            for (std::size_t v = 0; v < views.size(); ++v) {
                auto add = [&](const std::string& visibility, const render::PixelMask& drawn) {
                    Row row;
                    row.method = m;
                    row.backend = std::string(renderer.backendName()); // method 1 is "gl"
                    row.variant.assign(1, chunked ? 'L' : 'S');        // (a literal trips GCC 12)
                    row.visibility = visibility;
                    row.shape = shapeName;
                    row.size = n;
                    row.image = cameras[v].width();
                    row.viewIndex = v;
                    row.view = views[v];
                    row.score = evaluation::scoreContours(drawn, truths[v], 1);
                    if (options.imagesDir)
                        writeRowImages(*options.imagesDir, row, drawn, truths[v]);
                    rows.push_back(row);
                };
                if (m != 2) {
                    add("on", renderer.render(cameras[v], settings).lines);
                    continue;
                }
                settings.testAlongSegment = false;
                add("endpoints", renderer.render(cameras[v], settings).lines);
                settings.testAlongSegment = true;
                add("along", renderer.render(cameras[v], settings).lines);
                settings.testAlongSegment = false;
            }
        }
    }
}

bool sameGroup(const Row& a, const Row& b) {
    return a.method == b.method && a.visibility == b.visibility && a.variant == b.variant &&
           a.shape == b.shape && a.size == b.size;
}

void sortRows(std::vector<Row>& rows) {
    std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
        if (a.method != b.method)
            return a.method < b.method;
        if (a.visibility != b.visibility)
            return a.visibility > b.visibility; // "on", then "endpoints", then "along"
        if (a.variant != b.variant)
            return a.variant > b.variant; // S before L
        if (a.shape != b.shape)
            return a.shape < b.shape;
        if (a.size != b.size)
            return a.size < b.size;
        return a.viewIndex < b.viewIndex;
    });
}

template <typename Score> Spread spreadOf(const std::vector<const Row*>& group, Score score) {
    Spread spread;
    std::vector<double> values;
    for (const Row* row : group) {
        const double value = score(*row);
        if (values.empty() || value < spread.worst) {
            spread.worst = value;
            spread.worstView = row->view;
        }
        values.push_back(value);
    }
    spread.median = medianOf(std::move(values));
    return spread;
}

// Rows must be sorted (sortRows): a group's rows are then adjacent.
std::vector<Summary> summarise(const std::vector<Row>& rows) {
    std::vector<Summary> summaries;
    for (std::size_t begin = 0; begin < rows.size();) {
        std::vector<const Row*> group;
        std::size_t end = begin;
        while (end < rows.size() && sameGroup(rows[begin], rows[end]))
            group.push_back(&rows[end++]);
        Summary summary;
        summary.first = &rows[begin];
        summary.views = int(group.size());
        summary.recall = spreadOf(group, [](const Row& r) { return r.score.recall; });
        summary.precision = spreadOf(group, [](const Row& r) { return r.score.precision; });
        summaries.push_back(summary);
        begin = end;
    }
    return summaries;
}

void writeView(core::JsonWriter& writer, const View& view) {
    writer.beginArray().value(view.azimuthDeg).value(view.elevationDeg).endArray();
}

// The fields before "view" are those of the single-view command, in the same order, so its
// consumers read the rows as before; "summary" is new.
void writeJson(const Options& options, const std::string& backendUsed,
               const std::vector<std::string>& notes, const std::vector<Row>& rows,
               const std::vector<Summary>& summaries, std::ostream& out) {
    core::JsonWriter writer;
    writer.beginObject();
    writer.field("backend", backendUsed);
    if (!options.sweep)
        writer.field("azimuth", options.views[0].azimuthDeg)
            .field("elevation", options.views[0].elevationDeg);
    writer.field("pixels_per_voxel", kPixelsPerVoxel).field("tolerance_px", 1);
    writer.field("gradient", render::gradientStencilName(options.gradientStencil));
    writer.key("views").beginArray();
    for (const View& view : options.views)
        writeView(writer, view);
    writer.endArray();
    writer.key("notes").beginArray();
    for (const auto& note : notes)
        writer.value(note);
    writer.endArray();
    writer.key("rows").beginArray();
    for (const Row& row : rows) {
        writer.beginObject();
        writer.field("method", row.method)
            .field("variant", row.variant)
            .field("visibility", row.visibility);
        writer.field("backend", row.backend).field("shape", row.shape).field("size", row.size);
        writer.field("image", row.image)
            .field("recall", row.score.recall)
            .field("precision", row.score.precision);
        writer.field("true_pixels", row.score.truePixels)
            .field("drawn_pixels", row.score.drawnPixels);
        writeView(writer.key("view"), row.view);
        writer.endObject();
    }
    writer.endArray();
    writer.key("summary").beginArray();
    for (const Summary& s : summaries) {
        const Row& row = *s.first;
        writer.beginObject();
        writer.field("method", row.method)
            .field("variant", row.variant)
            .field("visibility", row.visibility);
        writer.field("backend", row.backend).field("shape", row.shape).field("size", row.size);
        writer.field("views", s.views);
        writer.field("recall_worst", s.recall.worst).field("recall_median", s.recall.median);
        writeView(writer.key("recall_worst_view"), s.recall.worstView);
        writer.field("precision_worst", s.precision.worst)
            .field("precision_median", s.precision.median);
        writeView(writer.key("precision_worst_view"), s.precision.worstView);
        writer.endObject();
    }
    writer.endArray();
    writer.endObject();
    out << writer.str() << "\n";
}

// The single-view table, as before the sweep.
void writeViewTable(const Options& options, const std::string& backendUsed,
                    const std::vector<Row>& rows, std::ostream& out) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "accuracy (backend %s, view az %g el %g, %g px per voxel, 1 px tolerance)\n",
                  backendUsed.c_str(), options.views[0].azimuthDeg, options.views[0].elevationDeg,
                  kPixelsPerVoxel);
    out << line;
    std::snprintf(line, sizeof line, "%-6s %-7s %-10s %-13s %5s %6s %8s %9s\n", "method", "variant",
                  "visibility", "shape", "size", "image", "recall", "precision");
    out << line;
    for (const Row& row : rows) {
        std::snprintf(line, sizeof line, "%-6d %-7s %-10s %-13s %5d %6d %8.4f %9.4f\n", row.method,
                      row.variant.c_str(), row.visibility.c_str(), row.shape.c_str(), row.size,
                      row.image, row.score.recall, row.score.precision);
        out << line;
    }
}

// "(AZ,EL)", as --view takes it between the parentheses.
std::string viewName(const View& view) {
    char text[48];
    std::snprintf(text, sizeof text, "(%g,%g)", view.azimuthDeg, view.elevationDeg);
    return text;
}

// Worst and median per group over the sweep, the worst view named as --view takes it.
void writeSweepTable(const Options& options, const std::string& backendUsed,
                     const std::vector<Summary>& summaries, std::ostream& out) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "accuracy (backend %s, %zu views: cube faces, edges, corners, then random from "
                  "seed %u; %g px per voxel, 1 px tolerance)\n",
                  backendUsed.c_str(), options.views.size(), evaluation::kDefaultSweepSeed,
                  kPixelsPerVoxel);
    out << line;
    std::snprintf(line, sizeof line, "%-6s %-7s %-10s %-13s %5s %5s  %-25s %6s  %-25s %6s\n",
                  "method", "variant", "visibility", "shape", "size", "views",
                  "recall worst (az,el)", "median", "precision worst (az,el)", "median");
    out << line;
    int missed = 0;
    for (const Summary& s : summaries) {
        const Row& row = *s.first;
        const bool miss = s.recall.worst < kGoal || s.precision.worst < kGoal;
        missed += miss;
        std::snprintf(line, sizeof line,
                      "%-6d %-7s %-10s %-13s %5d %5d  %.4f %-18s %.4f  %.4f %-18s %.4f%s\n",
                      row.method, row.variant.c_str(), row.visibility.c_str(), row.shape.c_str(),
                      row.size, s.views, s.recall.worst, viewName(s.recall.worstView).c_str(),
                      s.recall.median, s.precision.worst, viewName(s.precision.worstView).c_str(),
                      s.precision.median, miss ? " *" : "");
        out << line;
    }
    out << "* below " << kGoal << " at some view (" << missed << " of " << summaries.size()
        << "); the goal is recall and precision >= " << kGoal << " at every view\n";
}

} // namespace

int runAccuracy(const std::vector<std::string>& args, std::ostream& out) {
    const Options options = parseOptions(args);
    const std::string backendUsed(render::backendName(render::resolveBackend(options.backend)));
    std::vector<std::string> notes;
    Renderers renderers;
    createRenderers(options, renderers, notes);

    std::vector<Row> rows;
    for (const std::string& shapeName : options.shapes)
        for (int n : options.sizes)
            measureShape(shapeName, n, options, renderers, rows);
    sortRows(rows);
    const std::vector<Summary> summaries = summarise(rows);

    if (options.json) {
        writeJson(options, backendUsed, notes, rows, summaries, out);
        return 0;
    }
    if (options.sweep)
        writeSweepTable(options, backendUsed, summaries, out);
    else
        writeViewTable(options, backendUsed, rows, out);
    for (const auto& note : notes)
        out << "note: " << note << "\n";
    return 0;
}

} // namespace lw::cli
