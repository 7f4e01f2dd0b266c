// `linework-cli export`: the review of one view as a report, headless — PNG, PDF, SVG, DICOM
// Secondary Capture and the PDF as DICOM Encapsulated PDF, with the annotations of a JSON file
// burned in; with --send NODE the DICOM files then go to the PACS (export_send.h). Built where
// modules/report is (GUI and DICOM enabled); Qt Gui runs on its offscreen platform, so no display
// is needed.
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/annotation/annotation_json.h"
#include "lw/core/error.h"
#include "lw/render/renderer_factory.h"
#include "lw/report/encapsulated_pdf.h"
#include "lw/report/export_files.h"
#include "lw/report/export_image.h"
#include "lw/report/pdf_report.h"
#include "lw/report/qt_image.h"
#include "lw/report/secondary_capture.h"
#include "lw/report/svg_export.h"
#include "panel_rendering.h"
#ifdef LINEWORK_HAVE_PACS
#include "export_send.h"
#endif

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
    std::optional<std::filesystem::path> png, pdf, svg, sc, encapsulatedPdf;
    std::optional<std::string> sendTo; // --send NODE
    core::Overwrite overwrite = core::Overwrite::Refuse;
};

// --send and --encapsulated-pdf: both put the report into the patient's study, so neither goes
// with --anonymise; --send sends the Secondary Capture and the Encapsulated PDF, written beside
// the PDF (report.pdf -> report.dcm) unless --encapsulated-pdf names it.
void parseDicomTargets(const Arguments& arguments, ExportTargets& targets) {
    if (const auto value = arguments.option("encapsulated-pdf"))
        targets.encapsulatedPdf = std::filesystem::path(*value);
    targets.sendTo = arguments.option("send");
    const char* joining = targets.sendTo ? "--send" : "--encapsulated-pdf";
    if ((targets.sendTo || targets.encapsulatedPdf) && arguments.flag("anonymise"))
        throw UsageError(joining, "an anonymised export cannot be sent to the PACS because it "
                                  "would no longer belong to the patient's study");
    if (targets.encapsulatedPdf && !targets.pdf)
        throw UsageError("--encapsulated-pdf", "needs --pdf (the report it wraps)");
    if (targets.sendTo && !targets.sc && !targets.pdf)
        throw UsageError("--send", "needs --sc or --pdf: the Secondary Capture and the report "
                                   "(as Encapsulated PDF) are what is sent");
    if (targets.sendTo && targets.pdf && !targets.encapsulatedPdf)
        targets.encapsulatedPdf = std::filesystem::path(*targets.pdf).replace_extension(".dcm");
    if (targets.encapsulatedPdf && targets.encapsulatedPdf == targets.pdf)
        throw UsageError("--encapsulated-pdf", "names the PDF itself");
    if (!targets.sendTo)
        for (const char* name : {"nodes", "aet", "timeout"})
            if (arguments.option(name))
                throw UsageError(std::string("--") + name, "only goes with --send NODE");
}

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
    parseDicomTargets(arguments, targets);
    return targets;
}

// Before anything is rendered: an export bound to be refused (an existing file, a folder that
// is missing or not writable) fails at once and writes nothing.
void checkTargets(const ExportTargets& targets) {
    for (const auto& path : {targets.png, targets.pdf, targets.svg, targets.encapsulatedPdf})
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

QByteArray pdfReport(const ExportJob& job) {
    // The silhouette as vector paths over a picture that leaves it out.
    const QImage base = report::composeExportImage(job.panels, job.annotations, job.layout,
                                                   Qt::white, {}, report::SilhouetteLines::LeftOut);
    const report::PictureLines lines{
        report::pictureLines(job.panels, job.layout), job.panels.silhouetteLineWidth,
        job.panels.silhouetteLineColour, report::pictureHiddenLines(job.panels, job.layout)};
    return report::renderPdfReport(job.info, base, job.annotations, lines);
}

// Writes the outputs one by one and returns the DICOM files among them (what --send sends);
// when one fails, those written before it are removed again, so a failed export leaves no
// partial set of files behind.
std::vector<std::filesystem::path> writeOutputs(const ExportJob& job, const ExportTargets& targets,
                                                std::ostream& out) {
    Stopwatch watch;
    std::vector<std::filesystem::path> written, dicomFiles;
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
            const QByteArray pdf = pdfReport(job);
            write(*targets.pdf, pdf);
            if (targets.encapsulatedPdf) {
                report::EncapsulatedPdfSeries series;
                series.source = job.info.identity.value();
                series.softwareVersion = LINEWORK_VERSION;
                const std::filesystem::path& path = *targets.encapsulatedPdf;
                const std::vector<char> bytes =
                    report::encapsulatedPdfBytes(pdf, series, path.string());
                write(path, QByteArray(bytes.data(), qsizetype(bytes.size())));
                dicomFiles.push_back(path);
            }
        }
        if (targets.sc) {
            report::SecondaryCaptureSeries series;
            series.source = job.info.identity.value();
            series.derivationDescription = job.info.method;
            series.softwareVersion = LINEWORK_VERSION;
            for (const auto& file :
                 report::writeSecondaryCapture(*targets.sc, {picture}, series, targets.overwrite)) {
                reportWritten(out, file, watch.lapMs());
                dicomFiles.push_back(file);
            }
        }
    } catch (...) {
        std::error_code ignored;
        for (const std::filesystem::path& path : written)
            std::filesystem::remove(path, ignored);
        throw;
    }
    return dicomFiles;
}

#ifdef LINEWORK_HAVE_PACS
using SendTarget = PacsTarget;
#else
struct SendTarget {};
#endif

// The node --send names, resolved before anything is rendered (an unknown node is a usage
// error that writes nothing).
std::optional<SendTarget> sendTarget(const Arguments& arguments, const ExportTargets& targets) {
    if (!targets.sendTo)
        return std::nullopt;
#ifdef LINEWORK_HAVE_PACS
    return resolvePacsTarget(arguments, *targets.sendTo);
#else
    (void)arguments;
    throw core::Error("--send", "this linework-cli was built without PACS support (it needs "
                                "DCMTK: LINEWORK_DICOM)");
#endif
}

int send(const std::optional<SendTarget>& target, const std::vector<std::filesystem::path>& files,
         std::ostream& out) {
#ifdef LINEWORK_HAVE_PACS
    return target ? sendExports(*target, files, out) : 0;
#else
    (void)target, (void)files, (void)out;
    return 0;
#endif
}

std::set<std::string> exportOptions() {
    std::set<std::string> options = panelRenderOptions();
    options.insert({"series", "panel", "annotations", "comment", "png", "pdf", "svg", "sc",
                    "suggestive-threshold", "encapsulated-pdf", "send", "nodes", "aet", "timeout"});
    options.insert(lineStyleOptions().begin(), lineStyleOptions().end());
    return options;
}

// The silhouette's lines as vectors too: antialiased in the PNG, paths in the SVG and the PDF.
void addVectorLines(ExportJob& job, render::SilhouetteRenderer& renderer,
                    const volume::Volume& volume, const RenderRequest& request,
                    const LineStyle& lineStyle, const RenderedPanels& panels) {
    render::PolylineSplit lines = silhouettePolylines(renderer, volume, job.panels.camera, request,
                                                      lineStyle.hidden, panels.lines);
    job.panels.silhouetteLines = std::move(lines.visible);
    job.panels.silhouetteLines.insert(job.panels.silhouetteLines.end(),
                                      panels.suggestivePolylines.begin(),
                                      panels.suggestivePolylines.end());
    job.panels.hiddenLines = std::move(lines.hidden);
    job.panels.silhouetteLineWidth = lineStyle.widthPx.value_or(2.0 * request.lineRadius + 1.0);
    job.panels.silhouetteLineColour = QColor(QString::fromStdString(lineStyle.colour));
}

} // namespace

int runExport(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"force", "anonymise", "suggestive", kHiddenLinesFlag},
                              exportOptions());
    if (arguments.positionals().size() != 1)
        throw UsageError("export", "expects exactly one INPUT");
    const ExportTargets targets = parseTargets(arguments);
    const std::optional<SendTarget> sendTo = sendTarget(arguments, targets);
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
    if (targets.encapsulatedPdf && !opened.dicom)
        throw core::Error(targets.encapsulatedPdf->string(),
                          "an Encapsulated PDF joins the source's study: the input must be DICOM");
    fitToVolume(arguments, volume, request, setup);
    job.panels.camera = render::Camera(setup, size.x, size.y);
    const RenderedPanels panels = renderPanels(*renderer, volume, job.panels.camera, request, out);
    job.panels.iso = report::toQImage(panels.iso);
    job.panels.silhouette = report::toQImage(panels.silhouette);
    if (request.wantSilhouette)
        addVectorLines(job, *renderer, volume, request, lineStyle, panels);

    job.info.identity = opened.dicom;
    job.info.sourceDescription = opened.description;
    job.info.method = report::describeRendering(request.method, request.settings.isoReal, setup);
    job.info.comment = arguments.option("comment", "");
    job.info.anonymise = arguments.flag("anonymise");
    job.info.softwareVersion = LINEWORK_VERSION;
    return send(sendTo, writeOutputs(job, targets, out), out);
}

} // namespace lw::cli
