// `accuracy`: the paper's Table 5, measured. Analytic shapes are sampled on n^3 grids, every
// available silhouette method draws them, and the drawing is scored against the true occluding
// contour traced from the analytic function (true_contour.h), with a 1 pixel tolerance.
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/core/error.h"
#include "lw/core/json_writer.h"
#include "lw/evaluation/analytic_shapes.h"
#include "lw/evaluation/contour_score.h"
#include "lw/evaluation/true_contour.h"
#include "lw/render/camera.h"
#include "lw/render/renderer_factory.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace lw::cli {
namespace {

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
    evaluation::ContourScore score;
};

// The default view of the accuracy images: oblique, so no shape is seen along a symmetry axis.
constexpr double kAzimuth = 30.0;
constexpr double kElevation = 20.0;
constexpr double kPixelsPerVoxel = 2.0;

} // namespace

int runAccuracy(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json"}, {"backend", "methods", "sizes", "shapes", "view"});
    if (!arguments.positionals().empty())
        throw UsageError("accuracy", "takes no positional arguments");
    const render::Backend backend =
        parseUsage([&] { return render::parseBackend(arguments.option("backend", "auto")); });
    const std::string backendUsed(render::backendName(render::resolveBackend(backend)));
    const std::vector<int> methods =
        parseIntList("methods", arguments.option("methods", "1,2,3"), 1);
    for (int m : methods)
        if (m > 3)
            throw UsageError("--methods", "methods are 1, 2 and 3");
    const std::vector<int> sizes = parseIntList("sizes", arguments.option("sizes", "32,64,256"), 8);
    const std::vector<std::string> known = evaluation::analyticShapeNames();
    const std::vector<std::string> shapes =
        arguments.option("shapes") ? splitList(*arguments.option("shapes"), ',', false) : known;
    for (const std::string& shape : shapes)
        if (std::find(known.begin(), known.end(), shape) == known.end())
            throw UsageError("--shapes " + shape, "not a known shape");
    const bool json = arguments.flag("json");
    double azimuth = kAzimuth, elevation = kElevation;
    if (const auto view = arguments.option("view")) {
        const glm::dvec2 parsed = parseView(*view);
        if (std::abs(parsed.y) > 90.0)
            throw UsageError("--view " + *view, "expected AZ,EL in degrees with |EL| <= 90");
        azimuth = parsed.x;
        elevation = parsed.y;
    }
    auto wants = [&](int m) {
        return std::find(methods.begin(), methods.end(), m) != methods.end();
    };

    // One renderer per method, bound to each sampled volume in turn; only method 1 may be missing
    // (no OpenGL context), and then it is skipped with a note.
    std::vector<std::string> notes;
    std::unique_ptr<render::SilhouetteRenderer> renderers[4];
    for (int m = 1; m <= 3; ++m) {
        if (!wants(m))
            continue;
        try {
            renderers[m] = render::createSilhouetteRenderer(render::SilhouetteMethod(m), backend);
        } catch (const core::Error& error) {
            if (m != 1)
                throw;
            notes.push_back("method 1 skipped: " + error.reason());
        }
    }

    std::vector<Row> rows;
    for (const std::string& shapeName : shapes) {
        const std::unique_ptr<evaluation::AnalyticShape> shape =
            evaluation::makeAnalyticShape(shapeName);
        for (int n : sizes) {
            const volume::Volume volume = evaluation::sampleShape(*shape, n);
            render::CameraSetup setup;
            setup.bounds = shape->bounds();
            setup.azimuthDeg = azimuth;
            setup.elevationDeg = elevation;
            const int side = render::Camera::squareSizeForVoxelCoverage(
                setup, volume.geometry().spacingI(), kPixelsPerVoxel);
            const render::Camera camera(setup, side, side);
            const render::PixelMask truth = evaluation::trueContourMask(*shape, camera);
            // L: a 4 x 4 x 4 brick schedule, so chunking is exercised at every size.
            const int brickCells = std::max(4, (n - 1 + 3) / 4);

            auto add = [&](int method, bool chunked, const std::string& visibility,
                           const render::PixelMask& drawn) {
                Row row;
                row.method = method;
                row.backend = std::string(renderers[method]->backendName()); // method 1 is "gl"
                row.variant.assign(
                    1, chunked ? 'L' : 'S'); // (assign of a literal trips GCC 12's -Wrestrict)
                row.visibility = visibility;
                row.shape = shapeName;
                row.size = n;
                row.image = side;
                row.score = evaluation::scoreContours(drawn, truth, 1);
                rows.push_back(row);
            };

            for (const bool chunked : {false, true}) {
                render::SilhouetteSettings settings;
                settings.isoReal = evaluation::kShapeIso;
                settings.brickCells = chunked ? brickCells : 0;
                for (int m = 1; m <= 3; ++m) {
                    if (!renderers[m])
                        continue;
                    render::SilhouetteRenderer& renderer = *renderers[m];
                    renderer.setVolume(volume);
                    if (m != 2) {
                        add(m, chunked, "on", renderer.render(camera, settings).lines);
                        continue;
                    }
                    settings.testAlongSegment = false;
                    add(2, chunked, "endpoints", renderer.render(camera, settings).lines);
                    settings.testAlongSegment = true;
                    add(2, chunked, "along", renderer.render(camera, settings).lines);
                    settings.testAlongSegment = false;
                }
            }
        }
    }

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
            writer.field("backend", row.backend).field("shape", row.shape).field("size", row.size);
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
