// `linework-cli export`: the review of one view as a report, headless — PNG, PDF, SVG and DICOM
// Secondary Capture with the annotations of a JSON file burned in. Built where modules/report is
// (GUI and DICOM enabled); Qt Gui runs on its offscreen platform, so no display is needed.
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/annotation/annotation_json.h"
#include "lw/core/error.h"
#include "lw/render/renderer_factory.h"
#include "lw/report/export_files.h"
#include "lw/report/export_image.h"
#include "lw/report/pdf_report.h"
#include "lw/report/qt_image.h"
#include "lw/report/secondary_capture.h"
#include "lw/report/svg_export.h"
#include "panel_rendering.h"

#include <QGuiApplication>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <ostream>

#ifndef LINEWORK_VERSION
#define LINEWORK_VERSION "unknown"
#endif

namespace lw::cli {
namespace {

struct ExportTargets {
    std::optional<std::filesystem::path> png, pdf, svg, sc;
    core::Overwrite overwrite = core::Overwrite::Refuse;
};

ExportTargets parseTargets(const Arguments& arguments) {
    ExportTargets targets;
    const auto path = [&](const char* name) -> std::optional<std::filesystem::path> {
        if (const auto value = arguments.option(name))
            return std::filesystem::path(*value);
        return std::nullopt;
    };
    targets.png = path("png");
    targets.pdf = path("pdf");
    targets.svg = path("svg");
    targets.sc = path("sc");
    if (!targets.png && !targets.pdf && !targets.svg && !targets.sc)
        throw UsageError("export", "needs at least one of --png, --pdf, --svg, --sc");
    targets.overwrite = arguments.flag("force") ? core::Overwrite::Allow : core::Overwrite::Refuse;
    return targets;
}

// Before anything is rendered: an export bound to be refused (an existing file, a folder that
// is missing or not writable) fails at once and writes nothing.
void checkTargets(const ExportTargets& targets) {
    for (const auto& path : {targets.png, targets.pdf, targets.svg})
        if (path)
            core::checkWritableTarget(*path, targets.overwrite);
    if (targets.sc)
        report::checkSecondaryCaptureTarget(*targets.sc, targets.overwrite);
}

report::PanelLayout parseLayout(const Arguments& arguments) {
    const std::string panel = arguments.option("panel", "both");
    if (panel == "both")
        return report::PanelLayout::SideBySide;
    if (panel == "iso")
        return report::PanelLayout::IsoPanel;
    if (panel == "silhouette")
        return report::PanelLayout::SilhouettePanel;
    throw UsageError("--panel " + panel, "expected iso, silhouette or both");
}

class Stopwatch {
public:
    double lapMs() {
        const auto now = std::chrono::steady_clock::now();
        const double ms = std::chrono::duration<double, std::milli>(now - m_last).count();
        m_last = now;
        return ms;
    }

private:
    std::chrono::steady_clock::time_point m_last = std::chrono::steady_clock::now();
};

void reportWritten(std::ostream& out, const std::filesystem::path& path, double ms) {
    char line[64];
    std::snprintf(line, sizeof line, " (%.0f ms)\n", ms);
    out << "wrote " << path.string() << line;
}

struct ExportJob {
    report::RenderedPanels panels;
    std::vector<annotation::Annotation> annotations;
    report::PanelLayout layout = report::PanelLayout::SideBySide;
    report::ReportInfo info;
};

// Writes the outputs one by one; when one fails, those written before it are removed again, so
// a failed export leaves no partial set of files behind.
void writeOutputs(const ExportJob& job, const ExportTargets& targets, std::ostream& out) {
    Stopwatch watch;
    std::vector<std::filesystem::path> written;
    const auto write = [&](const std::filesystem::path& path, const QByteArray& bytes) {
        report::writeExportFile(path, bytes, targets.overwrite);
        written.push_back(path);
        reportWritten(out, path, watch.lapMs());
    };
    try {
        const QImage picture = report::composeExportImage(job.panels, job.annotations, job.layout);
        if (targets.png)
            write(*targets.png, report::encodePngBytes(picture, *targets.png));
        if (targets.svg)
            write(*targets.svg, report::renderSvg(job.panels, job.annotations, job.layout));
        if (targets.pdf) {
            // The silhouette as vector paths over a picture that leaves it out.
            const QImage base =
                report::composeExportImage(job.panels, job.annotations, job.layout, Qt::white, {},
                                           report::SilhouetteLines::LeftOut);
            const report::PictureLines lines{report::pictureLines(job.panels, job.layout),
                                             job.panels.silhouetteLineWidth,
                                             job.panels.silhouetteLineColour,
                                             report::pictureHiddenLines(job.panels, job.layout)};
            write(*targets.pdf, report::renderPdfReport(job.info, base, job.annotations, lines));
        }
        if (targets.sc) {
            report::SecondaryCaptureSeries series;
            series.source = job.info.identity.value();
            series.derivationDescription = job.info.method;
            series.softwareVersion = LINEWORK_VERSION;
            for (const auto& file :
                 report::writeSecondaryCapture(*targets.sc, {picture}, series, targets.overwrite))
                reportWritten(out, file, watch.lapMs());
        }
    } catch (...) {
        std::error_code ignored;
        for (const std::filesystem::path& path : written)
            std::filesystem::remove(path, ignored);
        throw;
    }
}

} // namespace

int runExport(const std::vector<std::string>& args, std::ostream& out) {
    std::set<std::string> options = panelRenderOptions();
    options.insert({"series", "panel", "annotations", "comment", "png", "pdf", "svg", "sc",
                    "suggestive-threshold"});
    options.insert(lineStyleOptions().begin(), lineStyleOptions().end());
    const Arguments arguments(args, {"force", "anonymise", "suggestive", kHiddenLinesFlag},
                              options);
    if (arguments.positionals().size() != 1)
        throw UsageError("export", "expects exactly one INPUT");
    const ExportTargets targets = parseTargets(arguments);
    ExportJob job;
    job.layout = parseLayout(arguments);
    RenderRequest request = parseRenderRequest(arguments, "export");
    const LineStyle lineStyle = parseLineStyle(arguments, request.settings.visibility);
    request.wantIso = job.layout != report::PanelLayout::SilhouettePanel;
    request.wantSilhouette = job.layout != report::PanelLayout::IsoPanel;
    request.suggestive = arguments.flag("suggestive") && request.wantSilhouette;
    parseSuggestiveThreshold(arguments, request);
    render::CameraSetup setup = parseCameraView(arguments);
    const glm::ivec2 size = parsePanelSize(arguments);
    // Lines widen with the resolution like the annotations do (1 px at 512 px high).
    request.lineRadius = int(std::lround((1.5 * size.y / 512.0 - 1.0) / 2.0));
    checkTargets(targets);
    if (const auto file = arguments.option("annotations"))
        job.annotations = annotation::readAnnotationsFile(*file);

    // Fonts and QPainter text need a QGuiApplication; the offscreen platform needs no display.
    int argc = 3;
    char name[] = "linework-cli", platform[] = "-platform", offscreen[] = "offscreen";
    char* argv[] = {name, platform, offscreen, nullptr};
    const QGuiApplication application(argc, argv);

    volume::Volume volume; // declared before the renderer, which holds it
    const std::unique_ptr<render::SilhouetteRenderer> renderer =
        render::createSilhouetteRenderer(request.method, request.backend);
    input::OpenedVolume opened = openCliInput(arguments.positionals()[0],
                                              arguments.option("series"), importLimits(arguments));
    volume = std::move(opened.volume);
    oversampleForRendering(arguments, render::VolumeSampling{}, volume);
    if (targets.sc && !opened.dicom) // before rendering: nothing is written then
        throw core::Error(targets.sc->string(), "a Secondary Capture joins the source's study: "
                                                "the input must be DICOM");
    fitToVolume(arguments, volume, request, setup);
    job.panels.camera = render::Camera(setup, size.x, size.y);
    const RenderedPanels panels = renderPanels(*renderer, volume, job.panels.camera, request, out);
    job.panels.iso = report::toQImage(panels.iso);
    job.panels.silhouette = report::toQImage(panels.silhouette);
    if (request.wantSilhouette) {
        // The lines as vectors too: antialiased in the PNG, paths in the SVG and the PDF.
        render::PolylineSplit lines = silhouettePolylines(*renderer, volume, job.panels.camera,
                                                          request, lineStyle.hidden, panels.lines);
        job.panels.silhouetteLines = std::move(lines.visible);
        job.panels.silhouetteLines.insert(job.panels.silhouetteLines.end(),
                                          panels.suggestivePolylines.begin(),
                                          panels.suggestivePolylines.end());
        job.panels.hiddenLines = std::move(lines.hidden);
        job.panels.silhouetteLineWidth = lineStyle.widthPx.value_or(2.0 * request.lineRadius + 1.0);
        job.panels.silhouetteLineColour = QColor(QString::fromStdString(lineStyle.colour));
    }

    job.info.identity = opened.dicom;
    job.info.sourceDescription = opened.description;
    job.info.method = report::describeRendering(request.method, request.settings.isoReal, setup);
    job.info.comment = arguments.option("comment", "");
    job.info.anonymise = arguments.flag("anonymise");
    job.info.softwareVersion = LINEWORK_VERSION;
    writeOutputs(job, targets, out);
    return 0;
}

} // namespace lw::cli
