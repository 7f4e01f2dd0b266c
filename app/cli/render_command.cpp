// `linework-cli render`: one view of an iso-surface and/or its silhouette as a PNG, the visible
// silhouette as SVG lines (--format svg, or an OUT ending in .svg), or a slice with its iso
// contour (--panel slice: slice_rendering.h).
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/core/file_util.h"
#include "lw/core/png_io.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/svg_lines.h"
#include "panel_rendering.h"
#include "slice_rendering.h"

#include <memory>
#include <ostream>

namespace lw::cli {

int runRender(const std::vector<std::string>& args, std::ostream& out) {
    std::set<std::string> options = panelRenderOptions();
    options.insert({"series", "panel", "repeat", "format", "suggestive-threshold"});
    options.insert(lineStyleOptions().begin(), lineStyleOptions().end());
    options.insert(sliceOptions().begin(), sliceOptions().end());
    const Arguments arguments(args, {"suggestive", kHiddenLinesFlag}, options);
    if (arguments.positionals().size() != 1)
        throw UsageError("render", "expects exactly one INPUT");
    const auto output = arguments.option("output");
    if (!output)
        throw UsageError("render", "needs -o OUT.png");
    const std::string input = arguments.positionals()[0];

    const std::string panel = arguments.option("panel", "silhouette");
    if (panel == "slice")
        return renderSliceCommand(arguments, input, *output, out);
    if (panel != "iso" && panel != "silhouette" && panel != "both")
        throw UsageError("--panel " + panel, "expected iso, silhouette, both or slice");
    for (const std::string& name : sliceOptions())
        if (arguments.option(name))
            throw UsageError("--" + name, "places a slice (--panel slice)");
    const bool svgName = output->size() > 4 && output->substr(output->size() - 4) == ".svg";
    const std::string format = arguments.option("format", svgName ? "svg" : "png");
    if (format != "png" && format != "svg")
        throw UsageError("--format " + format, "expected png or svg");
    if (format == "svg" && panel != "silhouette")
        throw UsageError("--format svg", "holds the silhouette lines only (--panel silhouette)");
    RenderRequest request = parseRenderRequest(arguments, "render");
    const LineStyle lineStyle = parseLineStyle(arguments, request.settings.visibility);
    if (format != "svg" &&
        (lineStyle.widthPx || arguments.option("line-colour") || lineStyle.hidden))
        throw UsageError("--line-width, --line-colour, --hidden-lines",
                         "style the vector lines of --format svg (export --png draws them as "
                         "antialiased strokes)");
    request.suggestive = arguments.flag("suggestive");
    if (request.suggestive && panel == "iso")
        throw UsageError("--suggestive", "draws into the silhouette panel (--panel iso has none)");
    parseSuggestiveThreshold(arguments, request);
    request.wantIso = panel != "silhouette";
    request.wantSilhouette = panel != "iso";
    request.repeat = std::max(0, int(arguments.number("repeat", 0)));
    render::CameraSetup setup = parseCameraView(arguments);
    const glm::ivec2 size = parsePanelSize(arguments);

    volume::Volume volume; // declared first: the renderer holds it and must not outlive it
    // Before the input is read, so an unavailable method or back-end fails at once.
    const std::unique_ptr<render::SilhouetteRenderer> renderer =
        render::createSilhouetteRenderer(request.method, request.backend);
    volume = loadInput(input, arguments.option("series"), importLimits(arguments));
    oversampleForRendering(arguments, render::VolumeSampling{}, volume);
    fitToVolume(arguments, volume, request, setup);
    const render::Camera camera(setup, size.x, size.y);

    RenderedPanels panels = renderPanels(*renderer, volume, camera, request, out);
    if (format == "svg") {
        render::PolylineSplit lines =
            silhouettePolylines(*renderer, volume, camera, request, lineStyle.hidden, panels.lines);
        lines.visible.insert(lines.visible.end(), panels.suggestivePolylines.begin(),
                             panels.suggestivePolylines.end());
        render::SvgLineStyle style;
        style.background = "#ffffff";
        style.colour = lineStyle.colour;
        style.widthPx = lineStyle.widthPx.value_or(1.0);
        const std::string svg = render::silhouetteSvg(lines.visible, camera.width(),
                                                      camera.height(), style, lines.hidden);
        core::writeFileAtomically(*output, svg.data(), svg.size());
        out << "wrote " << *output << " (" << lines.visible.size() << " polylines";
        if (lineStyle.hidden)
            out << ", " << lines.hidden.size() << " hidden";
        out << ", " << camera.width() << "x" << camera.height() << ")\n";
        return 0;
    }

    core::ImageRgba8 image;
    if (request.wantIso && request.wantSilhouette)
        image = sideBySide(panels.iso, panels.silhouette);
    else
        image = request.wantIso ? std::move(panels.iso) : std::move(panels.silhouette);
    core::writePng(*output, image, core::PngFormat::Rgb);
    out << "wrote " << *output << " (" << image.width() << "x" << image.height() << ")\n";
    return 0;
}

} // namespace lw::cli
