#include "panel_rendering.h"

#include "cli_inputs.h"
#include "lw/core/error.h"
#include "lw/render/iso_surface.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/silhouette_methods.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <ostream>

namespace lw::cli {
namespace {

// Lines black on white, like the GL renderer's defaults and a printed report.
core::ImageRgba8 maskToImage(const render::PixelMask& mask) {
    return mask.toImage({0, 0, 0, 255}, {255, 255, 255, 255});
}

void reportFrame(const render::SilhouetteFrame& frame, std::ostream& out) {
    char line[256];
    std::snprintf(
        line, sizeof line,
        "triangles %zu, segments %zu, silhouette pixels %zu; ms: extract %.1f silhouette %.1f "
        "visibility %.1f draw %.1f total %.1f\n",
        frame.triangles, frame.segments, frame.lines.count(), frame.times.extractMs,
        frame.times.silhouetteMs, frame.times.visibilityMs, frame.times.drawMs,
        frame.times.totalMs());
    out << line;
}

// Renders the same view `repeat` more times, turning the view by a degree each time so every
// frame is a new view (mode a then measures what the goal asks: a new view, mesh cached).
void repeatFrames(render::SilhouetteRenderer& renderer, render::Camera camera,
                  const RenderRequest& request, std::ostream& out) {
    std::vector<double> totals, extract, silhouette, visibility, draw;
    for (int i = 1; i <= request.repeat; ++i) {
        camera.setView(camera.setup().azimuthDeg + 1.0, camera.setup().elevationDeg);
        const render::StageTimes times = renderer.render(camera, request.settings).times;
        totals.push_back(times.totalMs());
        extract.push_back(times.extractMs);
        silhouette.push_back(times.silhouetteMs);
        visibility.push_back(times.visibilityMs);
        draw.push_back(times.drawMs);
    }
    if (totals.empty())
        return;
    auto median = [](std::vector<double>& values) {
        std::sort(values.begin(), values.end());
        return values[values.size() / 2];
    };
    const double middle = median(totals);
    char line[256];
    std::snprintf(line, sizeof line,
                  "median of %d new views: %.1f ms (min %.1f, max %.1f); stages: extract %.1f "
                  "silhouette %.1f "
                  "visibility %.1f draw %.1f\n",
                  request.repeat, middle, totals.front(), totals.back(), median(extract),
                  median(silhouette), median(visibility), median(draw));
    out << line;
}

// The surface of the request extracted on the CPU (for a renderer that kept none, or a panel
// without the silhouette frame that would have kept it).
render::Mesh extractForRequest(const volume::Volume& volume, const RenderRequest& request) {
    render::IsoSurfaceOptions options;
    options.brickCells = request.settings.brickCells;
    options.threads = request.settings.threads;
    options.closeAtBorder = request.settings.closeAtBorder;
    options.gradientStencil = request.settings.gradientStencil;
    return render::extractIsoSurface(volume, request.settings.isoReal, options);
}

// The shaded iso-surface for the same view: method 1 shades it in GL; methods 2 and 3 on the CPU,
// method 3 from the mesh its silhouette frame extracted so both panels show the same surface.
core::ImageRgba8 renderIsoPanel(render::SilhouetteRenderer& renderer, const volume::Volume& volume,
                                const render::Camera& camera, const RenderRequest& request) {
    if (std::optional<core::ImageRgba8> own = renderer.shadedIsoPanel(camera, request.settings))
        return std::move(*own);
    render::Mesh extracted;
    const render::Mesh* mesh = &extracted;
    const render::Mesh* kept = renderer.surfaceMesh();
    if (kept && request.wantSilhouette)
        mesh = kept;
    else
        extracted = extractForRequest(volume, request);
    render::SurfaceShading shading;
    shading.threads = request.settings.threads;
    return render::shadeSurfaceCpu(*mesh, camera, shading);
}

// The suggestive contours of the request's surface (the mesh the silhouette frame drew, or the
// same surface extracted here), reported like the frame; with --repeat, the median of as many
// new views as the silhouette had.
void renderSuggestive(render::SilhouetteRenderer& renderer, const volume::Volume& volume,
                      render::Camera camera, const RenderRequest& request, RenderedPanels& panels,
                      std::ostream& out) {
    const render::Mesh mesh = render::surfaceOfFrame(renderer, volume, request.settings);
    render::SuggestiveContourSettings settings = request.suggestiveSettings;
    settings.visibility = request.settings.visibility;
    settings.minStrokePixels = request.settings.minStrokePixels;
    settings.threads = request.settings.threads;
    render::SuggestiveContourRenderer suggestive(
        volume, mesh, request.settings.isoReal, settings.threads, request.settings.gradientStencil);
    const render::SuggestiveFrame frame = suggestive.render(camera, settings);
    panels.suggestive = frame.lines;
    render::PolylineOptions lines;
    lines.minLengthPx = double(settings.minStrokePixels);
    panels.suggestivePolylines =
        render::visiblePolylines(render::chainSegments(frame.kept), camera, frame.lines, lines);
    char line[256];
    std::snprintf(line, sizeof line,
                  "suggestive contours: segments %zu, pixels %zu; ms: derivatives %.1f (once per "
                  "surface) frame %.1f\n",
                  frame.kept.size(), frame.lines.count(), suggestive.derivativesMs(), frame.ms);
    out << line;
    std::vector<double> times;
    for (int i = 1; i <= request.repeat; ++i) {
        camera.setView(camera.setup().azimuthDeg + 1.0, camera.setup().elevationDeg);
        times.push_back(suggestive.render(camera, settings).ms);
    }
    if (!times.empty()) {
        std::sort(times.begin(), times.end());
        std::snprintf(line, sizeof line,
                      "suggestive contours: median of %d new views: %.1f ms (min %.1f, max %.1f)\n",
                      request.repeat, times[times.size() / 2], times.front(), times.back());
        out << line;
    }
}

} // namespace

RenderedPanels renderPanels(render::SilhouetteRenderer& renderer, const volume::Volume& volume,
                            const render::Camera& camera, const RenderRequest& request,
                            std::ostream& out) {
    RenderedPanels panels;
    renderer.setVolume(volume);
    if (request.wantSilhouette) {
        const render::SilhouetteFrame frame = renderer.render(camera, request.settings);
        reportFrame(frame, out);
        repeatFrames(renderer, camera, request, out);
        panels.lines = frame.lines;
        render::PixelMask drawn = frame.lines;
        if (request.suggestive) {
            renderSuggestive(renderer, volume, camera, request, panels, out);
            render::addLines(drawn, panels.suggestive);
        }
        panels.silhouette =
            maskToImage(request.lineRadius > 0 ? drawn.dilated(request.lineRadius) : drawn);
    }
    if (request.wantIso)
        panels.iso = renderIsoPanel(renderer, volume, camera, request);
    return panels;
}

const std::set<std::string>& panelRenderOptions() {
    static const std::set<std::string> names = {
        "iso",      "method",     "chunks",       "mode",       "visibility",    "view",
        "camera",   "size",       "backend",      "threads",    "min-stroke",    "border",
        "gradient", "oversample", "thick-slices", "thin-walls", kMaxVolumeOption};
    return names;
}

void parseLineOptions(const Arguments& arguments, int defaultMinStroke,
                      render::SilhouetteSettings& settings) {
    // Strokes under this many pixels are speckle of noise, not contours (0: keep every pixel).
    const double minStroke = arguments.number("min-stroke", defaultMinStroke);
    if (!(minStroke >= 0.0 && minStroke <= 1e6))
        throw UsageError("--min-stroke", "expected a number of pixels >= 0");
    settings.minStrokePixels = int(minStroke);
    // Where the first or last slice cuts bone, the surface is closed there (its outline drawn)
    // unless --border open asks for marching cubes' open surface.
    const std::string border = arguments.option("border", "closed");
    if (border != "closed" && border != "open")
        throw UsageError("--border " + border, "expected closed or open");
    settings.closeAtBorder = border == "closed";
    settings.gradientStencil = parseGradientOption(arguments);
}

render::GradientStencil parseGradientOption(const Arguments& arguments) {
    // Central differences unless --gradient smoothed asks for the normals of a noisy scan.
    const std::string gradient = arguments.option("gradient", "central");
    const std::optional<render::GradientStencil> stencil = render::parseGradientStencil(gradient);
    if (!stencil)
        throw UsageError("--gradient " + gradient, "expected central or smoothed");
    return *stencil;
}

double parseThinWalls(const Arguments& arguments, double fallback) {
    const double thinWallMm = arguments.number("thin-walls", fallback);
    if (!(thinWallMm >= 0.0 && thinWallMm <= 100.0))
        throw UsageError("--thin-walls", "expected the widest wall in mm, 0 to 100 (0: none)");
    return thinWallMm;
}

render::VolumeSampling parseVolumeSampling(const Arguments& arguments,
                                           render::VolumeSampling fallback) {
    const std::string text = arguments.option(
        "oversample", std::string(render::oversamplingName(fallback.oversampling)));
    const std::optional<render::Oversampling> oversampling = render::parseOversampling(text);
    if (!oversampling)
        throw UsageError("--oversample " + text, "expected auto or off");
    const std::string thick = arguments.option(
        "thick-slices", std::string(render::thickSlicesName(fallback.thickSlices)));
    const std::optional<render::ThickSlices> thickSlices = render::parseThickSlices(thick);
    if (!thickSlices)
        throw UsageError("--thick-slices " + thick, "expected smooth or linear");
    return {*oversampling, *thickSlices, parseThinWalls(arguments, fallback.thinWallMm)};
}

render::SamplingPlan oversampleForRendering(const Arguments& arguments,
                                            render::VolumeSampling fallback,
                                            volume::Volume& volume) {
    const render::VolumeSampling sampling = parseVolumeSampling(arguments, fallback);
    const render::SamplingPlan plan =
        render::samplingPlan(volume.dims(), volume.geometry(), sampling);
    const unsigned threads = unsigned(std::max(0.0, arguments.number("threads", 0)));
    // Every command that draws takes --iso; the shape-based field of thick slices is of it.
    const double iso = arguments.number("iso", 0.0);
    if (std::optional<volume::Volume> finer =
            render::oversampledToRender(volume, sampling, iso, threads))
        volume = std::move(*finer);
    return plan;
}

std::string samplingDescription(const render::SamplingPlan& plan, glm::ivec3 drawnDims) {
    if (plan.asLoaded())
        return "as loaded";
    return (plan.shapeBased ? "shape-based across thick slices, " : "oversampled to ") +
           dimsText(drawnDims);
}

void parseSuggestiveThreshold(const Arguments& arguments, RenderRequest& request) {
    const double threshold =
        arguments.number("suggestive-threshold", request.suggestiveSettings.derivativeThreshold);
    if (!(threshold >= 0.0))
        throw UsageError("--suggestive-threshold", "expected a number >= 0");
    request.suggestiveSettings.derivativeThreshold = threshold;
}

RenderRequest parseRenderRequest(const Arguments& arguments, const std::string& command) {
    RenderRequest request;
    request.method =
        parseUsage([&] { return render::parseSilhouetteMethod(arguments.option("method", "3")); });
    request.backend =
        parseUsage([&] { return render::parseBackend(arguments.option("backend", "auto")); });
    const std::string mode = arguments.option("mode", "a");
    if (mode != "a" && mode != "b")
        throw UsageError("--mode " + mode, "expected a or b");
    request.settings.mode =
        mode == "a" ? render::ExtractionMode::CachedA : render::ExtractionMode::EveryFrameB;
    // on: each method's own test (method 2: a segment's two endpoints, as the review draws by
    // default); along: method 2 tests the point under every pixel of a segment (the review's
    // "along each segment" setting); off: every silhouette segment drawn.
    const std::string visibility = arguments.option("visibility", "on");
    if (visibility != "on" && visibility != "along" && visibility != "off")
        throw UsageError("--visibility " + visibility, "expected on, along or off");
    request.settings.visibility = visibility != "off";
    request.settings.testAlongSegment = visibility == "along";
    request.settings.threads = unsigned(std::max(0.0, arguments.number("threads", 0)));
    parseLineOptions(arguments, render::kDefaultMinStrokePixels, request.settings);
    if (!arguments.option("iso"))
        throw UsageError(command, "needs --iso HU");
    request.settings.isoReal = arguments.number("iso", 0.0);
    return request;
}

render::CameraSetup parseCameraView(const Arguments& arguments) {
    render::CameraSetup setup;
    const glm::dvec2 view = parseView(arguments.option("view", "0,0"));
    setup.azimuthDeg = view.x;
    setup.elevationDeg = view.y;
    const std::string projection = arguments.option("camera", "perspective");
    if (projection != "perspective" && projection != "ortho")
        throw UsageError("--camera " + projection, "expected perspective or ortho");
    setup.projection =
        projection == "ortho" ? render::Projection::Orthographic : render::Projection::Perspective;
    return setup;
}

glm::ivec2 parsePanelSize(const Arguments& arguments) {
    return parseImageSize("--size", arguments.option("size", "512x512"), 1);
}

void fitToVolume(const Arguments& arguments, const volume::Volume& volume, RenderRequest& request,
                 render::CameraSetup& setup) {
    request.settings.brickCells = parseUsage(
        [&] { return render::parseChunks(arguments.option("chunks", "off"), volume.dims()); });
    // Frame the surface, not the field of view around it.
    setup.bounds = render::surfaceBounds(volume, request.settings.isoReal);
}

std::unique_ptr<render::SilhouetteRenderer> createRendererOrSkip(render::SilhouetteMethod method,
                                                                 render::Backend backend,
                                                                 std::vector<std::string>& notes) {
    try {
        return render::createSilhouetteRenderer(method, backend);
    } catch (const core::Error& error) {
        const render::SilhouetteMethodInfo& info = render::silhouetteMethodInfo(method);
        if (!info.needsOpenGl)
            throw;
        notes.push_back("method " + std::string(info.key) + " skipped: " + error.reason());
        return nullptr;
    }
}

ViewSweepOptions parseViewSweepOptions(const Arguments& arguments, const std::string& command,
                                       const std::string& defaultSize) {
    ViewSweepOptions options;
    options.request = parseRenderRequest(arguments, command);
    options.setup = parseCameraView(arguments);
    options.size = parseImageSize("--size", arguments.option("size", defaultSize), 16);
    options.views = parseViewChoice(arguments, evaluation::kDefaultSweepViewCount).views;
    options.json = arguments.flag("json");
    if (const auto images = arguments.option("images"))
        options.imagesDir = *images;
    return options;
}

core::ImageRgba8 sideBySide(const core::ImageRgba8& left, const core::ImageRgba8& right) {
    const int height = std::max(left.height(), right.height());
    core::ImageRgba8 image(left.width() + right.width(), height, {255, 255, 255, 255});
    for (int y = 0; y < left.height(); ++y)
        std::copy_n(left.row(y), left.width(), image.row(y));
    for (int y = 0; y < right.height(); ++y)
        std::copy_n(right.row(y), right.width(), image.row(y) + left.width());
    return image;
}

render::PolylineSplit silhouettePolylines(render::SilhouetteRenderer& renderer,
                                          const volume::Volume& volume,
                                          const render::Camera& camera,
                                          const RenderRequest& request, bool withHidden,
                                          const render::PixelMask& lines) {
    render::Mesh extracted;
    const render::Mesh* mesh = renderer.surfaceMesh();
    if (!mesh) { // method 2, or a chunked frame of method 1, keeps none
        extracted = extractForRequest(volume, request);
        mesh = &extracted;
    }
    render::PolylineOptions options;
    options.minLengthPx = double(request.settings.minStrokePixels);
    return render::splitPolylines(*mesh, camera, lines, options, withHidden);
}

const std::set<std::string>& lineStyleOptions() {
    static const std::set<std::string> names = {"line-width", "line-colour"};
    return names;
}

LineStyle parseLineStyle(const Arguments& arguments, bool visibility) {
    LineStyle style;
    if (arguments.option("line-width")) {
        const double width = arguments.number("line-width", 1.0);
        if (!(width > 0.0 && width <= 64.0))
            throw UsageError("--line-width", "expected pixels in (0, 64]");
        style.widthPx = width;
    }
    style.colour = arguments.option("line-colour", style.colour);
    const bool hex = style.colour.size() == 7 && style.colour[0] == '#' &&
                     std::all_of(style.colour.begin() + 1, style.colour.end(), [](char c) {
                         return std::isxdigit(static_cast<unsigned char>(c));
                     });
    if (!hex)
        throw UsageError("--line-colour " + style.colour, "expected #RRGGBB");
    style.hidden = arguments.flag(kHiddenLinesFlag);
    if (style.hidden && !visibility)
        throw UsageError("--hidden-lines", "needs --visibility on: without it nothing is hidden");
    return style;
}

} // namespace lw::cli
