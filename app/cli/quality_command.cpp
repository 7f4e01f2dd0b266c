// `quality`: issue 7's line quality on real CT, where no analytic truth exists. At each view of
// the accuracy sweep (or a given one) the shaded panel and the three methods' silhouettes are
// rendered as the review and `render` render them (the render options and their defaults, stroke
// pruning included), and measured (lw/evaluation/line_quality.h):
//   - the shaded panel's outer outline covered by each method's lines (1 px),
//   - the share of each method's line pixels in 8-connected groups under 10 px (and method 3's
//     before pruning, the speckle pruning removes),
//   - methods 1 and 3, and method 2 and 3, agreeing (1 px, both ways); method 2 with its
//     along-segment test unless --method2-test endpoints asks for the review's default.
// Worst and median over the views against the goals; --json rows carry the view [az, el].
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/core/error.h"
#include "lw/core/png_io.h"
#include "lw/evaluation/contour_score.h"
#include "lw/evaluation/line_quality.h"
#include "lw/evaluation/thick_slices.h"
#include "lw/evaluation/view_sweep.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/shaded_surface_cpu.h"
#include "panel_rendering.h"
#include "quality_report.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace lw::cli {
namespace {

using evaluation::View;

struct Options : ViewSweepOptions {
    std::string input;
    std::optional<std::string> series;
    bool method2AlongSegment = true;
};

// `render`'s options less the ones this command sets itself (every method is drawn, with
// visibility, at the views of --view/--views), so an option added there (closing the surface
// at the border, say) reaches this measure too.
std::set<std::string> qualityOptions() {
    std::set<std::string> names = panelRenderOptions();
    for (const char* own : {"method", "visibility", "view"})
        names.erase(own);
    names.insert({"series", "view", "views", "images", "noise", "method2-test"});
    return names;
}

Options parseOptions(const Arguments& arguments) {
    if (arguments.positionals().size() != 1)
        throw UsageError("quality", "expects exactly one INPUT");
    Options options;
    static_cast<ViewSweepOptions&>(options) =
        parseViewSweepOptions(arguments, "quality", "1024x1024");
    options.input = arguments.positionals()[0];
    options.series = arguments.option("series");
    const std::string test = arguments.option("method2-test", "along");
    if (test != "along" && test != "endpoints")
        throw UsageError("--method2-test " + test, "expected along or endpoints");
    options.method2AlongSegment = test == "along";
    return options;
}

using Renderers = std::unique_ptr<render::SilhouetteRenderer>[4];

// Methods 2 and 3 always; method 1 where a GL context can be had, else skipped with a note (as
// `accuracy` does), so the measure still runs on a machine without EGL.
void createRenderers(const RenderRequest& request, Renderers& renderers,
                     std::vector<std::string>& notes) {
    for (int m = 1; m <= 3; ++m)
        renderers[m] = createRendererOrSkip(render::SilhouetteMethod(m), request.backend, notes);
}

// The images of one view, to look at what the numbers say: the shaded panel beside method 3's
// lines; the outline against method 3's lines (contourDiffImage: blue = outline with no line
// within 1 px); method 1 against method 3 (red: 1 only, blue: 3 only); the same two for
// method 2.
void writeViewImages(const std::filesystem::path& dir, const View& view,
                     const core::ImageRgba8& shaded, const render::PixelMask& outline,
                     const render::PixelMask (&lines)[4]) {
    std::filesystem::create_directories(dir);
    char name[64];
    std::snprintf(name, sizeof name, "az%g-el%g", view.azimuthDeg, view.elevationDeg);
    const core::Rgba8 black{0, 0, 0, 255}, white{255, 255, 255, 255};
    core::writePng(dir / (std::string(name) + "-panels.png"),
                   sideBySide(shaded, lines[3].toImage(black, white)), core::PngFormat::Rgb);
    core::writePng(dir / (std::string(name) + "-outline-m3.png"),
                   evaluation::contourDiffImage(lines[3], outline, 1), core::PngFormat::Rgb);
    if (lines[1].width() > 0)
        core::writePng(dir / (std::string(name) + "-m1-vs-m3.png"),
                       evaluation::contourDiffImage(lines[1], lines[3], 1), core::PngFormat::Rgb);
    core::writePng(dir / (std::string(name) + "-outline-m2.png"),
                   evaluation::contourDiffImage(lines[2], outline, 1), core::PngFormat::Rgb);
    core::writePng(dir / (std::string(name) + "-m2-vs-m3.png"),
                   evaluation::contourDiffImage(lines[2], lines[3], 1), core::PngFormat::Rgb);
}

// One view: method 3 first (its mesh is the one the shaded panel shows, as in the review), the
// panel's foreground from its depth buffer, then methods 2 (--method2-test) and 1.
ViewQuality measureView(Renderers& renderers, const Options& options, const View& view) {
    render::CameraSetup setup = options.setup;
    setup.azimuthDeg = view.azimuthDeg;
    setup.elevationDeg = view.elevationDeg;
    const render::Camera camera(setup, options.size.x, options.size.y);
    const render::SilhouetteSettings& settings = options.request.settings;

    render::PixelMask lines[4];
    lines[3] = renderers[3]->render(camera, settings).lines;
    std::vector<float> depth;
    const core::ImageRgba8 shaded =
        render::shadeSurfaceCpu(*renderers[3]->surfaceMesh(), camera, {}, &depth);
    render::PixelMask foreground(camera.width(), camera.height());
    for (std::size_t i = 0; i < depth.size(); ++i)
        foreground.pixels()[i] = depth[i] < 1.0f ? 1 : 0;
    render::SilhouetteSettings unpruned = settings;
    unpruned.minStrokePixels = 0;
    const render::PixelMask speckled = renderers[3]->render(camera, unpruned).lines;

    render::SilhouetteSettings method2 = settings;
    method2.testAlongSegment = options.method2AlongSegment;
    lines[2] = renderers[2]->render(camera, method2).lines;
    if (renderers[1])
        lines[1] = renderers[1]->render(camera, settings).lines;

    const render::PixelMask outline = evaluation::outerOutline(foreground);
    ViewQuality quality = measureLines(view, outline, lines, speckled);
    if (options.imagesDir)
        writeViewImages(*options.imagesDir, view, shaded, outline, lines);
    return quality;
}

} // namespace

int runQuality(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json"}, qualityOptions());
    Options options = parseOptions(arguments);
    std::vector<std::string> notes;
    volume::Volume volume; // declared before the renderers: they hold it and must not outlive it
    Renderers renderers;
    // Before the input is read, so an unavailable back-end fails at once.
    createRenderers(options.request, renderers, notes);
    input::OpenedVolume opened =
        openCliInput(options.input, options.series, importLimits(arguments));
    volume = std::move(opened.volume);
    // --noise SIGMA: scanner-like noise (real units) before anything else, as a sharp kernel's.
    const double noise = arguments.number("noise", 0.0);
    if (!(noise >= 0.0))
        throw UsageError("--noise", "expected a standard deviation >= 0 (real units, HU for CT)");
    evaluation::addVoxelNoise(volume, noise);
    const render::SamplingPlan sampling =
        oversampleForRendering(arguments, render::VolumeSampling{}, volume);
    fitToVolume(arguments, volume, options.request, options.setup);
    for (auto& renderer : renderers)
        if (renderer)
            renderer->setVolume(volume);

    std::vector<ViewQuality> rows;
    for (const View& view : options.views)
        rows.push_back(measureView(renderers, options, view));

    QualityRun run;
    run.input = options.input;
    run.description = opened.description;
    run.sampling = samplingDescription(sampling, volume.dims());
    run.iso = options.request.settings.isoReal;
    run.minStrokePixels = options.request.settings.minStrokePixels;
    run.method2AlongSegment = options.method2AlongSegment;
    run.width = options.size.x;
    run.height = options.size.y;
    run.notes = notes;
    if (options.json)
        writeQualityJson(run, rows, out);
    else
        writeQualityTable(run, rows, out);
    return 0;
}

} // namespace lw::cli
