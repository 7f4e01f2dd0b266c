// `thick-slices`: how closely a thick-slice series draws like a thin one. The thin INPUT is the
// reference; its thick version is either made from it (--average N: each thick slice the mean
// of N thin ones, as a scanner integrates; lw/evaluation/thick_slices.h) or read (--thick PATH:
// the scanner's own thick reconstruction of the same acquisition). At each view both are drawn
// by one method with one camera in patient coordinates -- framed on the thin surface, not each
// on its own -- and the thick drawing is measured against the thin one within 2 px:
//   precision = thick line pixels with a thin one near, recall = thin line pixels with a thick
//   one near, ratio = thick line pixels / thin line pixels.
// The thick series is drawn twice, with straight lines between its slices and smoothed across
// them (--thick-slices linear | smooth, render/surface_sampling.h), so one run compares both.
// --bound (with --average) draws a third series the same way: the slab means taken at every thin
// slice (evaluation::slabMeansAtEverySlice), what the thick slices hold sampled densely -- the
// figures no interpolation between the thick slices is expected to pass.
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/core/json_writer.h"
#include "lw/core/png_io.h"
#include "lw/evaluation/contour_score.h"
#include "lw/evaluation/line_quality.h"
#include "lw/evaluation/thick_slices.h"
#include "lw/evaluation/view_sweep.h"
#include "lw/volume/volume_reader.h"
#include "panel_rendering.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <vector>

namespace lw::cli {
namespace {

using evaluation::View;

inline constexpr int kToleranceGoalPx = 2;
// What is measured against the thin drawing, in report order: the thick series drawn linear and
// smooth, and (--bound) the slab means at every thin slice.
enum Candidate { kLinear, kSmooth, kBound, kCandidates };
constexpr const char* kCandidateNames[kCandidates] = {"linear", "smooth", "bound"};

struct Options : ViewSweepOptions {
    std::string input;
    std::optional<std::string> series;
    std::optional<std::string> thickInput;
    std::optional<std::string> thickSeries;
    int average = 5;
    std::optional<std::string> saveThick; // the thick series measured, as NRRD
    bool bound = false;
    double thinWallMm = render::kThickSliceThinWallMm; // the smooth field's (--thin-walls)
    int candidates() const { return bound ? kCandidates : kBound; }
};

Options parseOptions(const Arguments& arguments) {
    if (arguments.positionals().size() != 1)
        throw UsageError("thick-slices", "expects exactly one (thin) INPUT");
    Options options;
    static_cast<ViewSweepOptions&>(options) =
        parseViewSweepOptions(arguments, "thick-slices", "768x768");
    options.input = arguments.positionals()[0];
    options.series = arguments.option("series");
    options.thickInput = arguments.option("thick");
    options.thickSeries = arguments.option("thick-series");
    const double average = arguments.number("average", 5);
    if (!(average >= 2 && average <= 64 && average == double(int(average))))
        throw UsageError("--average", "expected a whole number of slices from 2 to 64");
    if (options.thickInput && arguments.option("average"))
        throw UsageError("--average", "makes the thick series; --thick reads one: not both");
    options.average = int(average);
    options.bound = arguments.flag("bound");
    options.thinWallMm = parseThinWalls(arguments, render::kThickSliceThinWallMm);
    if (options.bound && options.thickInput)
        throw UsageError("--bound", "needs the thick series made here (--average), not --thick");
    options.saveThick = arguments.option("save-thick");
    if (options.saveThick && !options.saveThick->ends_with(".nrrd"))
        throw UsageError("--save-thick " + *options.saveThick, "expected a name ending in .nrrd");
    return options;
}

// One series as drawn: its resampled volume and the renderer that holds it.
struct DrawnSeries {
    std::string label;
    volume::Volume volume;
    std::unique_ptr<render::SilhouetteRenderer> renderer;
    std::string sampling; // samplingDescription of the grid drawn
};

void prepare(DrawnSeries& series, const volume::Volume& loaded, render::VolumeSampling sampling,
             const Options& options) {
    std::optional<volume::Volume> finer = render::oversampledToRender(
        loaded, sampling, options.request.settings.isoReal, options.request.settings.threads);
    series.volume = finer ? std::move(*finer) : loaded.clone();
    series.sampling = samplingDescription(
        render::samplingPlan(loaded.dims(), loaded.geometry(), sampling), series.volume.dims());
    series.renderer =
        render::createSilhouetteRenderer(options.request.method, options.request.backend);
    series.renderer->setVolume(series.volume);
}

struct ThickMeasure {
    std::size_t linePixels = 0;
    double precision = 0.0;
    double recall = 0.0;
    double ratio = 0.0;
};

struct ViewRow {
    View view;
    std::size_t thinPixels = 0;
    ThickMeasure thick[kCandidates];
};

render::PixelMask drawView(DrawnSeries& series, const render::Camera& camera,
                           const Options& options) {
    return series.renderer->render(camera, options.request.settings).lines;
}

void writeDiff(const Options& options, const View& view, const std::string& label,
               const render::PixelMask& thick, const render::PixelMask& thin) {
    std::filesystem::create_directories(*options.imagesDir);
    char name[96];
    std::snprintf(name, sizeof name, "az%g-el%g-%s.png", view.azimuthDeg, view.elevationDeg,
                  label.c_str());
    core::writePng(*options.imagesDir / name,
                   evaluation::contourDiffImage(thick, thin, kToleranceGoalPx),
                   core::PngFormat::Rgb);
}

ViewRow measureView(DrawnSeries& thin, DrawnSeries (&thick)[kCandidates], const Options& options,
                    const View& view) {
    render::CameraSetup setup = options.setup;
    setup.azimuthDeg = view.azimuthDeg;
    setup.elevationDeg = view.elevationDeg;
    const render::Camera camera(setup, options.size.x, options.size.y);
    const render::PixelMask reference = drawView(thin, camera, options);
    ViewRow row;
    row.view = view;
    row.thinPixels = reference.count();
    for (int mode = 0; mode < options.candidates(); ++mode) {
        const render::PixelMask lines = drawView(thick[mode], camera, options);
        const evaluation::LineAgreement agreement =
            evaluation::lineAgreement(lines, reference, kToleranceGoalPx);
        ThickMeasure& measure = row.thick[mode];
        measure.linePixels = lines.count();
        measure.precision = agreement.firstNearSecond;
        measure.recall = agreement.secondNearFirst;
        measure.ratio = row.thinPixels ? double(measure.linePixels) / double(row.thinPixels) : 0.0;
        if (options.imagesDir)
            writeDiff(options, view, thick[mode].label, lines, reference);
    }
    return row;
}

struct Summary {
    double precision = 0.0, recall = 0.0, ratio = 0.0; // medians
    double worstPrecision = 0.0, worstRecall = 0.0, worstRatio = 0.0;
};

Summary summarise(const std::vector<ViewRow>& rows, int mode) {
    std::vector<double> precision, recall, ratio;
    for (const ViewRow& row : rows) {
        precision.push_back(row.thick[mode].precision);
        recall.push_back(row.thick[mode].recall);
        ratio.push_back(row.thick[mode].ratio);
    }
    Summary s;
    s.precision = medianOf(precision);
    s.recall = medianOf(recall);
    s.ratio = medianOf(ratio);
    s.worstPrecision =
        precision.empty() ? 0.0 : *std::min_element(precision.begin(), precision.end());
    s.worstRecall = recall.empty() ? 0.0 : *std::min_element(recall.begin(), recall.end());
    s.worstRatio = ratio.empty() ? 0.0 : *std::max_element(ratio.begin(), ratio.end());
    return s;
}

struct RunInfo {
    std::string thin;  // what was drawn as the reference
    std::string thick; // how the thick series was had
    std::string sampled[kCandidates];
};

void writeTable(const RunInfo& info, const Options& options, const std::vector<ViewRow>& rows,
                std::ostream& out) {
    char line[256];
    out << "thin " << info.thin << "\nthick " << info.thick << "\n";
    std::snprintf(line, sizeof line,
                  "method %d, iso %g, %dx%d, within %d px; thick drawn linear (%s) and smooth "
                  "(%s)\n",
                  int(options.request.method), options.request.settings.isoReal, options.size.x,
                  options.size.y, kToleranceGoalPx, info.sampled[kLinear].c_str(),
                  info.sampled[kSmooth].c_str());
    out << line;
    if (options.bound)
        out << "bound: the slab means at every thin slice (" << info.sampled[kBound] << ")\n";
    std::snprintf(line, sizeof line, "%-16s %8s", "view", "thin px");
    out << line;
    for (int mode = 0; mode < options.candidates(); ++mode) {
        std::snprintf(line, sizeof line, " | %8s %6s %6s %6s", kCandidateNames[mode], "prec",
                      "recall", "ratio");
        out << line;
    }
    out << "\n";
    for (const ViewRow& row : rows) {
        char view[32];
        std::snprintf(view, sizeof view, "az %g el %g", row.view.azimuthDeg, row.view.elevationDeg);
        std::snprintf(line, sizeof line, "%-16s %8zu", view, row.thinPixels);
        out << line;
        for (int mode = 0; mode < options.candidates(); ++mode) {
            const ThickMeasure& m = row.thick[mode];
            std::snprintf(line, sizeof line, " | %8zu %6.3f %6.3f %6.3f", m.linePixels, m.precision,
                          m.recall, m.ratio);
            out << line;
        }
        out << "\n";
    }
    for (int mode = 0; mode < options.candidates(); ++mode) {
        const Summary s = summarise(rows, mode);
        std::snprintf(line, sizeof line,
                      "%-6s median precision %.3f recall %.3f ratio %.3f; worst %.3f %.3f %.3f\n",
                      kCandidateNames[mode], s.precision, s.recall, s.ratio, s.worstPrecision,
                      s.worstRecall, s.worstRatio);
        out << line;
    }
}

void writeJson(const RunInfo& info, const Options& options, const std::vector<ViewRow>& rows,
               std::ostream& out) {
    core::JsonWriter writer;
    writer.beginObject();
    writer.field("input", options.input).field("thin", info.thin).field("thick", info.thick);
    writer.field("method", int(options.request.method));
    writer.field("iso", options.request.settings.isoReal);
    writer.field("width", options.size.x).field("height", options.size.y);
    writer.field("tolerance_px", kToleranceGoalPx);
    for (int mode = 0; mode < options.candidates(); ++mode) {
        const Summary s = summarise(rows, mode);
        writer.key(kCandidateNames[mode]).beginObject();
        writer.field("sampled", info.sampled[mode]);
        writer.field("median_precision", s.precision).field("median_recall", s.recall);
        writer.field("median_ratio", s.ratio).field("worst_precision", s.worstPrecision);
        writer.field("worst_recall", s.worstRecall).field("worst_ratio", s.worstRatio);
        writer.key("rows").beginArray();
        for (const ViewRow& row : rows) {
            const ThickMeasure& m = row.thick[mode];
            writer.beginObject().key("view").beginArray();
            writer.value(row.view.azimuthDeg).value(row.view.elevationDeg).endArray();
            writer.field("thin_pixels", row.thinPixels).field("line_pixels", m.linePixels);
            writer.field("precision", m.precision).field("recall", m.recall);
            writer.field("ratio", m.ratio).endObject();
        }
        writer.endArray().endObject();
    }
    writer.endObject();
    out << writer.str() << "\n";
}

} // namespace

int runThickSlices(const std::vector<std::string>& args, std::ostream& out) {
    std::set<std::string> names = panelRenderOptions();
    names.erase("oversample");
    names.erase("thick-slices");
    names.insert({"series", "thick", "thick-series", "average", "views", "images", "save-thick",
                  "thin-walls"});
    const Arguments arguments(args, {"json", "bound"}, names);
    Options options = parseOptions(arguments);
    const core::ImportLimits limits = importLimits(arguments);
    const volume::Volume thinLoaded = loadInput(options.input, options.series, limits);
    const volume::Volume thickLoaded =
        options.thickInput ? loadInput(*options.thickInput, options.thickSeries, limits)
                           : evaluation::thickSlabsOf(thinLoaded, options.average);
    if (options.saveThick)
        volume::writeNrrd(*options.saveThick, thickLoaded);

    RunInfo info;
    DrawnSeries thin{"thin", {}, nullptr, {}};
    // The thin series drawn as the workstation draws it (thick itself where its slices are).
    prepare(thin, thinLoaded,
            {render::Oversampling::Auto, render::ThickSlices::Smooth, options.thinWallMm}, options);
    fitToVolume(arguments, thin.volume, options.request, options.setup); // the thin surface framed
    DrawnSeries thick[kCandidates] = {
        {"linear", {}, nullptr, {}}, {"smooth", {}, nullptr, {}}, {"bound", {}, nullptr, {}}};
    prepare(thick[kLinear], thickLoaded, {render::Oversampling::Auto, render::ThickSlices::Linear},
            options);
    prepare(thick[kSmooth], thickLoaded,
            {render::Oversampling::Auto, render::ThickSlices::Smooth, options.thinWallMm}, options);
    if (options.bound) // at the thin spacing: drawn as the thin series is
        prepare(thick[kBound], evaluation::slabMeansAtEverySlice(thinLoaded, options.average),
                render::VolumeSampling{}, options);
    for (int mode = 0; mode < options.candidates(); ++mode)
        info.sampled[mode] = thick[mode].sampling;
    info.thin = options.input + " " + dimsText(thinLoaded.dims()) + ", " + thin.sampling;
    info.thick = (options.thickInput
                      ? *options.thickInput
                      : "the mean of every " + std::to_string(options.average) + " thin slices") +
                 " " + dimsText(thickLoaded.dims());

    std::vector<ViewRow> rows;
    for (const View& view : options.views)
        rows.push_back(measureView(thin, thick, options, view));
    if (options.json)
        writeJson(info, options, rows, out);
    else
        writeTable(info, options, rows, out);
    return 0;
}

} // namespace lw::cli
