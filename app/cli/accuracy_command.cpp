// `accuracy`: the paper's Table 5, measured. Analytic shapes are sampled on n^3 grids, every
// available silhouette method draws them, and the drawing is scored against the true occluding
// contour traced from the analytic function (true_contour.h), with a 1 pixel tolerance.
#include "arguments.h"
#include "commands.h"
#include "lw/core/error.h"
#include "lw/core/json_writer.h"
#include "lw/render/analytic_shapes.h"
#include "lw/render/camera.h"
#include "lw/render/contour_score.h"
#include "lw/render/iso_surface.h"
#include "lw/render/raycast_silhouette_renderer.h"
#include "lw/render/true_contour.h"

#if __has_include("lw/render/zbuffer_silhouette_renderer.h")
#include "lw/render/zbuffer_silhouette_renderer.h"
#define LW_ACCURACY_HAVE_METHOD3 1
#else
#define LW_ACCURACY_HAVE_METHOD3 0
#endif

#if defined(LINEWORK_GL) && LINEWORK_GL &&                                                         \
    __has_include("lw/render/silhouette_gl_renderer.h") && __has_include("lw/render/gl_context.h")
#include "lw/render/gl_context.h"
#include "lw/render/silhouette_gl_renderer.h"
#define LW_ACCURACY_HAVE_METHOD1 1
#else
#define LW_ACCURACY_HAVE_METHOD1 0
#endif

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace lw::cli {
namespace {

std::vector<std::string> splitList(const std::string& text) {
    std::vector<std::string> parts;
    std::stringstream stream(text);
    std::string part;
    while (std::getline(stream, part, ','))
        if (!part.empty())
            parts.push_back(part);
    return parts;
}

std::vector<int> parseIntList(const std::string& option, const std::string& text, int minimum) {
    std::vector<int> values;
    for (const std::string& part : splitList(text)) {
        int value = 0;
        const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (error != std::errc() || end != part.data() + part.size() || value < minimum)
            throw core::Error("--" + option + " " + text,
                              "expected a comma-separated list of integers >= " +
                                  std::to_string(minimum));
        values.push_back(value);
    }
    if (values.empty())
        throw core::Error("--" + option, "empty list");
    return values;
}

struct Row {
    int method = 0;
    std::string variant;    // S or L
    std::string visibility; // on | endpoints | along
    std::string shape;
    int size = 0;
    int image = 0;
    render::ContourScore score;
};

// The default view of the accuracy images: oblique, so no shape is seen along a symmetry axis.
constexpr double kAzimuth = 30.0;
constexpr double kElevation = 20.0;
constexpr double kPixelsPerVoxel = 2.0;

} // namespace

int runAccuracy(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json"}, {"backend", "methods", "sizes", "shapes", "view"});
    if (!arguments.positionals().empty())
        throw core::Error("accuracy",
                          "usage: accuracy [--backend cpu|cuda|auto] [--methods 1,2,3] "
                          "[--sizes 32,64,256] [--shapes sphere,...] [--view AZ,EL] [--json]");
    const std::string backend = arguments.option("backend", "auto");
    if (backend != "cpu" && backend != "cuda" && backend != "auto")
        throw core::Error("--backend " + backend, "expected cpu, cuda or auto");
    if (backend == "cuda")
        throw core::Error("--backend cuda",
                          "this build has no CUDA implementation of the silhouette methods");
    const std::string backendUsed = "cpu"; // auto: no CUDA silhouette back-end in this build
    const std::vector<int> methods =
        parseIntList("methods", arguments.option("methods", "1,2,3"), 1);
    for (int m : methods)
        if (m > 3)
            throw core::Error("--methods", "methods are 1, 2 and 3");
    const std::vector<int> sizes = parseIntList("sizes", arguments.option("sizes", "32,64,256"), 8);
    const std::vector<std::string> shapes = arguments.option("shapes")
                                                ? splitList(*arguments.option("shapes"))
                                                : render::analyticShapeNames();
    const bool json = arguments.flag("json");
    double azimuth = kAzimuth, elevation = kElevation;
    if (const auto view = arguments.option("view")) {
        const auto parts = splitList(*view);
        char* end0 = nullptr;
        char* end1 = nullptr;
        if (parts.size() == 2) {
            azimuth = std::strtod(parts[0].c_str(), &end0);
            elevation = std::strtod(parts[1].c_str(), &end1);
        }
        if (parts.size() != 2 || *end0 != '\0' || *end1 != '\0' || std::abs(elevation) > 90.0)
            throw core::Error("--view " + *view, "expected AZ,EL in degrees with |EL| <= 90");
    }
    auto wants = [&](int m) {
        return std::find(methods.begin(), methods.end(), m) != methods.end();
    };

    std::vector<std::string> notes;
#if LW_ACCURACY_HAVE_METHOD1
    std::unique_ptr<render::EglHeadlessContext> glContext;
    std::unique_ptr<render::SilhouetteGlRenderer> glRenderer;
    if (wants(1)) {
        try {
            glContext = std::make_unique<render::EglHeadlessContext>();
            glRenderer = std::make_unique<render::SilhouetteGlRenderer>();
            glRenderer->initialize();
        } catch (const core::Error& error) {
            glRenderer.reset();
            glContext.reset();
            notes.push_back(std::string("method 1 skipped: no OpenGL context (") + error.what() +
                            ")");
        }
    }
#else
    if (wants(1))
        notes.push_back("method 1 skipped: this build has no GL renderer (EGL/OpenGL not found)");
#endif
#if !LW_ACCURACY_HAVE_METHOD3
    if (wants(3))
        notes.push_back("method 3 skipped: this build has no z-buffer renderer");
#endif

    std::vector<Row> rows;
    for (const std::string& shapeName : shapes) {
        const std::unique_ptr<render::AnalyticShape> shape = render::makeAnalyticShape(shapeName);
        for (int n : sizes) {
            const volume::Volume volume = render::sampleShape(*shape, n);
            render::CameraSetup setup;
            setup.bounds = shape->bounds();
            setup.azimuthDeg = azimuth;
            setup.elevationDeg = elevation;
            const int side = render::Camera::squareSizeForVoxelCoverage(
                setup, volume.geometry().spacingI(), kPixelsPerVoxel);
            const render::Camera camera(setup, side, side);
            const render::PixelMask truth = render::trueContourMask(*shape, camera);
            // L: a 4 x 4 x 4 brick schedule, so chunking is exercised at every size.
            const int brickCells = std::max(4, (n - 1 + 3) / 4);

            auto add = [&](int method, bool chunked, const std::string& visibility,
                           const render::PixelMask& drawn) {
                Row row;
                row.method = method;
                row.variant.assign(1, chunked ? 'L' : 'S'); // (assign of a literal trips GCC 12's -Wrestrict)
                row.visibility = visibility;
                row.shape = shapeName;
                row.size = n;
                row.image = side;
                row.score = render::scoreContours(drawn, truth, 1);
                rows.push_back(row);
            };

            for (const bool chunked : {false, true}) {
                render::SilhouetteSettings settings;
                settings.isoReal = render::kShapeIso;
                settings.brickCells = chunked ? brickCells : 0;
#if LW_ACCURACY_HAVE_METHOD1
                if (glRenderer) {
                    render::IsoSurfaceOptions options;
                    options.brickCells = settings.brickCells;
                    const render::Mesh mesh =
                        render::extractIsoSurface(volume, render::kShapeIso, options);
                    glRenderer->uploadMesh(mesh);
                    render::SilhouetteGlOptions gl;
                    gl.panel = render::GlPanel::Silhouette;
                    gl.background = {0.0f, 0.0f, 0.0f, 1.0f};
                    gl.lineColour = {1.0f, 1.0f, 1.0f, 1.0f};
                    const core::ImageRgba8 image = glRenderer->renderImage(camera, gl);
                    add(1, chunked, "on", render::PixelMask::fromImage(image, {0, 0, 0, 255}));
                }
#endif
                if (wants(2)) {
                    render::RayCastSilhouetteRenderer renderer;
                    renderer.setVolume(volume);
                    settings.testAlongSegment = false;
                    add(2, chunked, "endpoints", renderer.render(camera, settings).lines);
                    settings.testAlongSegment = true;
                    add(2, chunked, "along", renderer.render(camera, settings).lines);
                    settings.testAlongSegment = false;
                }
#if LW_ACCURACY_HAVE_METHOD3
                if (wants(3)) {
                    render::ZBufferSilhouetteRenderer renderer;
                    renderer.setVolume(volume);
                    add(3, chunked, "on", renderer.render(camera, settings).lines);
                }
#endif
            }
        }
    }
#if LW_ACCURACY_HAVE_METHOD1
    if (glRenderer) {
        glRenderer->release();
        glRenderer.reset();
    }
#endif

    std::sort(rows.begin(), rows.end(), [](const Row& a, const Row& b) {
        if (a.method != b.method)
            return a.method < b.method;
        if (a.visibility != b.visibility)
            return a.visibility > b.visibility; // "on", then "endpoints", then "along"
        if (a.variant != b.variant)
            return a.variant > b.variant; // S before L
        if (a.shape != b.shape)
            return a.shape < b.shape;
        return a.size < b.size;
    });

    if (json) {
        core::JsonWriter writer;
        writer.beginObject();
        writer.field("backend", backendUsed);
        writer.field("azimuth", azimuth).field("elevation", elevation);
        writer.field("pixels_per_voxel", kPixelsPerVoxel).field("tolerance_px", 1);
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
            writer.field("backend", backendUsed).field("shape", row.shape).field("size", row.size);
            writer.field("image", row.image)
                .field("recall", row.score.recall)
                .field("precision", row.score.precision);
            writer.field("true_pixels", row.score.truePixels)
                .field("drawn_pixels", row.score.drawnPixels);
            writer.endObject();
        }
        writer.endArray();
        writer.endObject();
        out << writer.str() << "\n";
        return 0;
    }

    char line[256];
    std::snprintf(line, sizeof line,
                  "accuracy (backend %s, view az %g el %g, %g px per voxel, 1 px tolerance)\n",
                  backendUsed.c_str(), azimuth, elevation, kPixelsPerVoxel);
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
    for (const auto& note : notes)
        out << "note: " << note << "\n";
    return 0;
}

} // namespace lw::cli
