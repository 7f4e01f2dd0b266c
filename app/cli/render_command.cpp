// `linework-cli render`: one view of an iso-surface and/or its silhouette as a PNG.
#include "arguments.h"
#include "commands.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/core/png_io.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/phantom.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/zbuffer_silhouette_renderer.h"
#include "lw/volume/volume_reader.h"

#if __has_include("lw/render/raycast_silhouette_renderer.h")
#include "lw/render/raycast_silhouette_renderer.h"
#define LW_CLI_HAVE_METHOD2 1
#else
#define LW_CLI_HAVE_METHOD2 0
#endif

#if defined(LINEWORK_GL) && LINEWORK_GL &&                                                         \
    __has_include("lw/render/silhouette_gl_renderer.h") && __has_include("lw/render/gl_context.h")
#include "lw/render/gl_context.h"
#include "lw/render/silhouette_gl_renderer.h"
#define LW_CLI_HAVE_METHOD1 1
#else
#define LW_CLI_HAVE_METHOD1 0
#endif

#ifdef LINEWORK_HAVE_DICOM
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"
#endif

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <memory>
#include <ostream>
#include <sstream>

namespace lw::cli {
namespace {

constexpr core::LogCategory kLog("lw.cli");

constexpr const char* kRenderUsage =
    "usage: render INPUT [--series UID] --iso HU --method 1|2|3 [--chunks off|auto|N] [--mode a|b] "
    "[--visibility on|off] [--view AZ,EL] [--camera perspective|ortho] [--size WxH] [--panel "
    "iso|silhouette|both] "
    "[--backend cpu|cuda|auto] -o OUT.png";

std::vector<double> parseNumbers(const std::string& text, char separator,
                                 const std::string& subject) {
    std::vector<double> values;
    std::stringstream stream(text);
    std::string part;
    while (std::getline(stream, part, separator)) {
        double value = 0.0;
        const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (part.empty() || error != std::errc() || end != part.data() + part.size())
            throw core::Error(subject, "'" + part + "' is not a number");
        values.push_back(value);
    }
    return values;
}

glm::ivec2 parseImageSize(const std::string& text) {
    const std::vector<double> values = parseNumbers(text, 'x', "--size " + text);
    if (values.size() != 2 || values[0] < 1 || values[1] < 1 || values[0] > 16384 ||
        values[1] > 16384 || values[0] != double(int(values[0])) ||
        values[1] != double(int(values[1])))
        throw core::Error("--size " + text, "expected WxH with whole numbers between 1 and 16384");
    return {int(values[0]), int(values[1])};
}

// phantom:N, phantom:NXxNYxNZ, optionally followed by :ct or :sphere.
volume::Volume loadPhantom(const std::string& spec) {
    const std::string body = spec.substr(std::string("phantom:").size());
    const auto colon = body.find(':');
    const std::string sizeText = body.substr(0, colon);
    const render::PhantomKind kind =
        render::parsePhantomKind(colon == std::string::npos ? "ct" : body.substr(colon + 1));
    const std::vector<double> parts = parseNumbers(sizeText, 'x', spec);
    if ((parts.size() != 1 && parts.size() != 3) ||
        std::any_of(parts.begin(), parts.end(),
                    [](double v) { return v < 2 || v > 4096 || v != double(int(v)); }))
        throw core::Error(
            spec,
            "expected phantom:N or phantom:NXxNYxNZ (2..4096) with an optional :ct or :sphere");
    const glm::ivec3 dims = parts.size() == 1
                                ? glm::ivec3(int(parts[0]))
                                : glm::ivec3(int(parts[0]), int(parts[1]), int(parts[2]));
    return render::makePhantom(dims, kind);
}

#ifdef LINEWORK_HAVE_DICOM
volume::Volume loadDicom(const std::string& path, const std::optional<std::string>& seriesUid) {
    const dicom::DicomIndex index = dicom::scanDicom(path);
    const dicom::SeriesInfo* chosen = nullptr;
    if (seriesUid) {
        chosen = index.findSeries(*seriesUid);
        if (!chosen)
            throw core::Error(path, "no series with UID " + *seriesUid);
    } else {
        // The series with the most slices: in a CT study that is the diagnostic volume, not a
        // scout or a dose report.
        for (const dicom::SeriesInfo* series : index.allSeries())
            if (!chosen || series->instances.size() > chosen->instances.size())
                chosen = series;
        if (!chosen)
            throw core::Error(path, "no DICOM series found");
    }
    const dicom::SeriesAssembly assembly = dicom::planVolumes(*chosen);
    const dicom::VolumePlan* plan = nullptr;
    for (const dicom::VolumePlan& candidate : assembly.volumes)
        if (!plan || candidate.slices.size() > plan->slices.size())
            plan = &candidate;
    if (!plan)
        throw core::Error(path, "series " + chosen->seriesInstanceUid +
                                    " holds no volume that can be assembled");
    if (plan->dims.z < 2)
        throw core::Error(path, "series " + chosen->seriesInstanceUid +
                                    " has a single slice; an iso-surface needs two");
    kLog.info("rendering series " + chosen->seriesInstanceUid + " (" +
              std::to_string(plan->slices.size()) + " slices)");
    return dicom::loadVolume(*chosen, *plan);
}
#endif

volume::Volume loadInput(const std::string& input, const std::optional<std::string>& seriesUid) {
    if (input.rfind("phantom:", 0) == 0)
        return loadPhantom(input);
#ifdef LINEWORK_HAVE_DICOM
    if (dicom::looksLikeDicomInput(input) ||
        volume::detectVolumeFormat(input) == volume::VolumeFormat::Unknown)
        return loadDicom(input, seriesUid);
#else
    if (seriesUid)
        throw core::Error("--series", "this build reads no DICOM (LINEWORK_DICOM off)");
#endif
    return volume::readVolumeFile(input);
}

// Lines black on white, like the GL renderer's defaults and a printed report.
core::ImageRgba8 maskToImage(const render::PixelMask& mask) {
    return mask.toImage({0, 0, 0, 255}, {255, 255, 255, 255});
}

struct RenderRequest {
    int method = 3;
    render::SilhouetteSettings settings;
    bool wantIso = false;
    bool wantSilhouette = true;
    int repeat = 0;
};

struct RenderedPanels {
    core::ImageRgba8 iso;
    core::ImageRgba8 silhouette;
};

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

RenderedPanels renderCpu(const volume::Volume& volume, const render::Camera& camera,
                         const RenderRequest& request, std::ostream& out) {
    RenderedPanels panels;
    std::unique_ptr<render::SilhouetteRenderer> renderer;
    render::ZBufferSilhouetteRenderer* zbuffer = nullptr;
    if (request.method == 3) {
        auto owned = std::make_unique<render::ZBufferSilhouetteRenderer>();
        zbuffer = owned.get();
        renderer = std::move(owned);
    } else {
#if LW_CLI_HAVE_METHOD2
        renderer = std::make_unique<render::RayCastSilhouetteRenderer>();
#else
        throw core::Error("--method 2", "method 2 is not available in this build");
#endif
    }
    renderer->setVolume(volume);
    if (request.wantSilhouette) {
        const render::SilhouetteFrame frame = renderer->render(camera, request.settings);
        reportFrame(frame, out);
        repeatFrames(*renderer, camera, request, out);
        panels.silhouette = maskToImage(frame.lines);
    }
    if (request.wantIso) {
        render::Mesh extracted;
        const render::Mesh* mesh = nullptr;
        if (zbuffer && request.wantSilhouette) {
            mesh = &zbuffer->mesh();
        } else {
            render::IsoSurfaceOptions options;
            options.brickCells = request.settings.brickCells;
            options.threads = request.settings.threads;
            extracted = render::extractIsoSurface(volume, request.settings.isoReal, options);
            mesh = &extracted;
        }
        render::SurfaceShading shading;
        shading.threads = request.settings.threads;
        panels.iso = render::shadeSurfaceCpu(*mesh, camera, shading);
    }
    return panels;
}

#if LW_CLI_HAVE_METHOD1
RenderedPanels renderGl(const volume::Volume& volume, const render::Camera& camera,
                        const RenderRequest& request, std::ostream& out) {
    render::EglHeadlessContext context;
    kLog.info("method 1 on " + context.description());
    render::IsoSurfaceOptions extractOptions;
    extractOptions.brickCells = request.settings.brickCells;
    extractOptions.threads = request.settings.threads;
    const render::Mesh mesh =
        render::extractIsoSurface(volume, request.settings.isoReal, extractOptions);
    render::SilhouetteGlRenderer gl;
    RenderedPanels panels;
    try {
        gl.uploadMesh(mesh);
        render::SilhouetteGlOptions options;
        options.visibility = request.settings.visibility;
        if (request.wantSilhouette) {
            options.panel = render::GlPanel::Silhouette;
            panels.silhouette = gl.renderImage(camera, options);
        }
        if (request.wantIso) {
            options.panel = render::GlPanel::Iso;
            panels.iso = gl.renderImage(camera, options);
        }
        out << "triangles " << mesh.triangleCount() << " (method 1, GL)\n";
    } catch (...) {
        gl.release();
        throw;
    }
    gl.release();
    return panels;
}
#endif

} // namespace

int runRender(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {},
                              {"series", "iso", "method", "chunks", "mode", "visibility", "view",
                               "camera", "size", "panel", "backend", "threads", "repeat"});
    if (arguments.positionals().size() != 1)
        throw core::Error("render", std::string("expects exactly one INPUT; ") + kRenderUsage);
    const auto output = arguments.option("output");
    if (!output)
        throw core::Error("render", std::string("needs -o OUT.png; ") + kRenderUsage);
    const std::string input = arguments.positionals()[0];

    RenderRequest request;
    const std::string methodText = arguments.option("method", "3");
    if (methodText != "1" && methodText != "2" && methodText != "3")
        throw core::Error("--method " + methodText, "expected 1, 2 or 3");
    request.method = methodText[0] - '0';

    const std::string mode = arguments.option("mode", "a");
    if (mode != "a" && mode != "b")
        throw core::Error("--mode " + mode, "expected a or b");
    request.settings.mode =
        mode == "a" ? render::ExtractionMode::CachedA : render::ExtractionMode::EveryFrameB;
    const std::string visibility = arguments.option("visibility", "on");
    if (visibility != "on" && visibility != "off")
        throw core::Error("--visibility " + visibility, "expected on or off");
    request.settings.visibility = visibility == "on";
    request.settings.threads = unsigned(std::max(0.0, arguments.number("threads", 0)));
    request.repeat = std::max(0, int(arguments.number("repeat", 0)));

    const std::string panel = arguments.option("panel", "silhouette");
    if (panel != "iso" && panel != "silhouette" && panel != "both")
        throw core::Error("--panel " + panel, "expected iso, silhouette or both");
    request.wantIso = panel != "silhouette";
    request.wantSilhouette = panel != "iso";

    const std::string backend = arguments.option("backend", "auto");
    if (backend == "cuda")
        throw core::Error("--backend cuda", "CUDA backend not built");
    if (backend != "cpu" && backend != "auto")
        throw core::Error("--backend " + backend, "expected cpu, cuda or auto");
    if (backend == "auto" && request.method != 1)
        kLog.info("backend auto: CUDA backend not built, rendering on the CPU");

    render::CameraSetup setup;
    const std::vector<double> view = parseNumbers(arguments.option("view", "0,0"), ',', "--view");
    if (view.size() != 2)
        throw core::Error("--view", "expected AZ,EL in degrees");
    setup.azimuthDeg = view[0];
    setup.elevationDeg = view[1];
    const std::string projection = arguments.option("camera", "perspective");
    if (projection != "perspective" && projection != "ortho")
        throw core::Error("--camera " + projection, "expected perspective or ortho");
    setup.projection =
        projection == "ortho" ? render::Projection::Orthographic : render::Projection::Perspective;
    const glm::ivec2 size = parseImageSize(arguments.option("size", "512x512"));

#if !LW_CLI_HAVE_METHOD1
    if (request.method == 1)
        throw core::Error("--method 1", "method 1 is not available in this build (no OpenGL/EGL)");
#endif
#if !LW_CLI_HAVE_METHOD2
    if (request.method == 2)
        throw core::Error("--method 2", "method 2 is not available in this build");
#endif

    if (!arguments.option("iso"))
        throw core::Error("render", std::string("needs --iso HU; ") + kRenderUsage);
    request.settings.isoReal = arguments.number("iso", 0.0);
    const volume::Volume volume = loadInput(input, arguments.option("series"));
    request.settings.brickCells =
        render::parseChunks(arguments.option("chunks", "off"), volume.dims());
    setup.bounds = render::volumeBounds(volume);
    const render::Camera camera(setup, size.x, size.y);

    RenderedPanels panels;
#if LW_CLI_HAVE_METHOD1
    if (request.method == 1)
        panels = renderGl(volume, camera, request, out);
    else
#endif
        panels = renderCpu(volume, camera, request, out);

    core::ImageRgba8 image;
    if (request.wantIso && request.wantSilhouette) {
        // Side by side: the iso-surface left, its silhouette right, the same camera.
        image = core::ImageRgba8(2 * size.x, size.y, {255, 255, 255, 255});
        for (int y = 0; y < size.y; ++y) {
            std::copy_n(panels.iso.row(y), size.x, image.row(y));
            std::copy_n(panels.silhouette.row(y), size.x, image.row(y) + size.x);
        }
    } else {
        image = request.wantIso ? std::move(panels.iso) : std::move(panels.silhouette);
    }
    core::writePng(*output, image, core::PngFormat::Rgb);
    out << "wrote " << *output << " (" << image.width() << "x" << image.height() << ")\n";
    return 0;
}

} // namespace lw::cli
