#include "shell/review_export.h"

#include "annotate/annotation_document.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/report/encapsulated_pdf.h"
#include "lw/report/export_files.h"
#include "lw/report/pdf_report.h"
#include "lw/report/secondary_capture.h"
#include "review/panel_render_job.h"
#include "review/review_widget.h"
#include "shell/slice_export.h"

#include <QElapsedTimer>
#include <QEventLoop>
#include <QFileInfo>
#include <QFutureWatcher>
#include <QProgressDialog>
#include <QtConcurrent/QtConcurrentRun>
#include <functional>
#include <new>

#ifndef LINEWORK_VERSION
#define LINEWORK_VERSION "unknown"
#endif

namespace lw::gui {
namespace {

constexpr core::LogCategory kLog("lw.gui");

// What a writer gets: a copy of everything it needs, so it can run on any thread.
struct ExportContent {
    report::RenderedPanels panels;
    std::vector<annotation::Annotation> annotations;
    report::PanelLayout layout = report::PanelLayout::SideBySide;
    QColor background;
    SlicePanels slices; // made on the UI thread from the views (none without slices shown)

    QImage picture() const {
        return withSlicePanels(report::composeExportImage(panels, annotations, layout, background),
                               slices, background);
    }
    // For the PDF: the picture without the silhouette's vector lines, and those lines, which it
    // draws as paths (with no vectors the picture keeps the raster lines and these are none).
    QImage pictureWithoutLines() const {
        return withSlicePanels(report::composeExportImage(panels, annotations, layout, background,
                                                          {}, report::SilhouetteLines::LeftOut),
                               slices, background);
    }
    report::PictureLines vectorLines() const {
        return {report::pictureLines(panels, layout), panels.silhouetteLineWidth,
                panels.silhouetteLineColour, report::pictureHiddenLines(panels, layout)};
    }
};

// Writes the files of one export; throws core::Error naming the file.
using ExportWriter = std::function<void(const ExportContent&)>;

std::filesystem::path fsPath(const QString& path) {
    return std::filesystem::path(path.toStdString());
}

template <typename Work> QString guarded(const QString& target, QSize size, Work&& work) {
    try {
        work();
        return {};
    } catch (const core::Error& error) {
        return QString::fromStdString(error.what());
    } catch (const std::bad_alloc&) {
        return QObject::tr("%1: out of memory rendering %2 x %3 pixels; choose a smaller size")
            .arg(target)
            .arg(size.width())
            .arg(size.height());
    }
}

// Writes the rendered panels and their vector lines, drawn in the job's line style.
void writeRendered(ExportContent content, const std::pair<QImage, QImage>& panels,
                   PanelVectors vectors, const PanelRenderJob& job, const QString& target,
                   const ExportWriter& write) {
    if (panels.first.isNull() && panels.second.isNull())
        throw core::Error(target.toStdString(),
                          "nothing to export yet (the surface is still being computed)");
    content.panels = {panels.first, panels.second, job.camera};
    content.panels.silhouetteLines = std::move(vectors.lines);
    content.panels.hiddenLines = std::move(vectors.hidden);
    content.panels.silhouetteLineWidth = job.appearance.lineWidth;
    content.panels.silhouetteLineColour = job.appearance.lineColour;
    write(content);
}

// Where an export's time goes, logged: the panels rendered, then the picture composed, encoded
// and written.
class ExportClock {
public:
    ExportClock() { m_timer.start(); }
    void rendered() { m_renderedMs = double(m_timer.nsecsElapsed()) / 1e6; }
    void written(const QString& target) const {
        const double totalMs = double(m_timer.nsecsElapsed()) / 1e6;
        kLog.info(QString("export %1: panels rendered in %2 ms, composed, encoded and written in "
                          "%3 ms")
                      .arg(QFileInfo(target).fileName())
                      .arg(m_renderedMs, 0, 'f', 1)
                      .arg(totalMs - m_renderedMs, 0, 'f', 1)
                      .toStdString());
    }

private:
    QElapsedTimer m_timer;
    double m_renderedMs = 0.0;
};

// Runs `future` to its end with a progress dialog over `parent` (shown after a moment only).
QString waitWithProgress(QFuture<QString> future, const QString& what, QWidget* parent) {
    QProgressDialog progress(what, QString(), 0, 0, parent);
    progress.setWindowModality(Qt::WindowModal);
    progress.setMinimumDuration(300);
    QFutureWatcher<QString> watcher;
    QEventLoop loop;
    QObject::connect(&watcher, &QFutureWatcher<QString>::finished, &loop, &QEventLoop::quit);
    watcher.setFuture(future);
    if (!future.isFinished())
        loop.exec();
    return future.result();
}

// Checks the target (`precheck`, before any work), renders the review's panels at the
// picture's size and hands them to `write`: off the UI thread unless the panels' own GL
// contexts must draw.
QString runExport(ReviewWidget& review, const ExportPicture& picture, const QString& target,
                  const std::function<void()>& precheck, ExportWriter write,
                  QWidget* progressParent) {
    const QSize size = picture.panelSize;
    if (QString error = guarded(target, size, precheck); !error.isEmpty())
        return error;
    const PanelRenderJob job = review.renderJob(size);
    ExportContent content{
        {}, review.annotations().annotations(), picture.layout, review.settings().background, {}};
    const int panelCount = picture.layout == report::PanelLayout::SideBySide ? 2 : 1;
    content.slices = slicePanelsOf(review, size, QSize(size.width() * panelCount, size.height()),
                                   content.annotations);
    if (review.rendersOnUiThread()) // a GPU draws in the panels' contexts: fast, and only here
        return guarded(target, size, [&] {
            PanelVectors vectors;
            ExportClock clock;
            const std::pair<QImage, QImage> panels = review.renderPanels(size, &vectors);
            clock.rendered();
            writeRendered(content, panels, std::move(vectors), job, target, write);
            clock.written(target);
        });
    QFuture<QString> future = QtConcurrent::run([job, content, target, size, write] {
        return guarded(target, size, [&] {
            PanelVectors vectors;
            ExportClock clock;
            const std::pair<QImage, QImage> panels = renderPanelJob(job, &vectors);
            clock.rendered();
            writeRendered(content, panels, std::move(vectors), job, target, write);
            clock.written(target);
        });
    });
    return waitWithProgress(future,
                            QObject::tr("Exporting %1 at %2 x %3…")
                                .arg(QFileInfo(target).fileName())
                                .arg(size.width())
                                .arg(size.height()),
                            progressParent);
}

std::string renderingOf(ReviewWidget& review) {
    return report::describeRendering(review.settings().method, review.iso(),
                                     review.camera().cameraSetup());
}

} // namespace

QString exportReviewPng(ReviewWidget& review, const QString& path, const ExportPicture& picture,
                        core::Overwrite overwrite, QWidget* progressParent) {
    return runExport(
        review, picture, path, [&] { core::checkWritableTarget(fsPath(path), overwrite); },
        [path, overwrite](const ExportContent& content) {
            report::writeExportFile(
                fsPath(path), report::encodePngBytes(content.picture(), fsPath(path)), overwrite);
        },
        progressParent);
}

namespace {

report::ReportInfo reportInfoOf(ReviewWidget& review, const ReportOptions& options) {
    report::ReportInfo info;
    info.identity = review.source().dicom;
    info.sourceDescription = review.source().title.toStdString();
    info.method = renderingOf(review);
    info.comment = options.comment.toStdString();
    info.anonymise = options.anonymise;
    info.softwareVersion = LINEWORK_VERSION;
    return info;
}

QByteArray pdfOf(const report::ReportInfo& info, const ExportContent& content) {
    return report::renderPdfReport(info, content.pictureWithoutLines(), content.annotations,
                                   content.vectorLines());
}

QString notDicom(ReviewWidget& review, const QString& target) {
    return QObject::tr("%1: a Secondary Capture joins the source's study, and %2 is not a "
                       "DICOM series")
        .arg(target, review.source().title);
}

report::SecondaryCaptureSeries secondaryCaptureSeriesOf(ReviewWidget& review) {
    report::SecondaryCaptureSeries series;
    series.source = *review.source().dicom;
    series.derivationDescription = renderingOf(review);
    series.softwareVersion = LINEWORK_VERSION;
    return series;
}

} // namespace

QString exportReviewReport(ReviewWidget& review, const QString& path, const ReportOptions& options,
                           core::Overwrite overwrite, QWidget* progressParent) {
    const report::ReportInfo info = reportInfoOf(review, options);
    return runExport(
        review, options.picture, path, [&] { core::checkWritableTarget(fsPath(path), overwrite); },
        [path, overwrite, info](const ExportContent& content) {
            report::writeExportFile(fsPath(path), pdfOf(info, content), overwrite);
        },
        progressParent);
}

QString exportReviewSecondaryCapture(ReviewWidget& review, const QString& folder,
                                     const ExportPicture& picture, core::Overwrite overwrite,
                                     QWidget* progressParent) {
    if (!review.source().dicom)
        return notDicom(review, folder);
    const report::SecondaryCaptureSeries series = secondaryCaptureSeriesOf(review);
    return runExport(
        review, picture, folder,
        [&] { report::checkSecondaryCaptureTarget(fsPath(folder), overwrite); },
        [folder, overwrite, series](const ExportContent& content) {
            report::writeSecondaryCapture(fsPath(folder), {content.picture()}, series, overwrite);
        },
        progressParent);
}

QString exportReviewForPacs(ReviewWidget& review, const QString& secondaryCaptureFolder,
                            const QString& encapsulatedPdfPath, const ReportOptions& options,
                            QWidget* progressParent) {
    if (!review.source().dicom)
        return notDicom(review, secondaryCaptureFolder);
    const report::ReportInfo info = reportInfoOf(review, options);
    const report::SecondaryCaptureSeries series = secondaryCaptureSeriesOf(review);
    report::EncapsulatedPdfSeries pdfSeries;
    pdfSeries.source = *review.source().dicom;
    pdfSeries.softwareVersion = LINEWORK_VERSION;
    constexpr core::Overwrite kNew = core::Overwrite::Refuse;
    return runExport(
        review, options.picture, secondaryCaptureFolder,
        [&] {
            report::checkSecondaryCaptureTarget(fsPath(secondaryCaptureFolder), kNew);
            core::checkWritableTarget(fsPath(encapsulatedPdfPath), kNew);
        },
        [secondaryCaptureFolder, encapsulatedPdfPath, info, series,
         pdfSeries](const ExportContent& content) {
            report::writeSecondaryCapture(fsPath(secondaryCaptureFolder), {content.picture()},
                                          series, kNew);
            report::writeEncapsulatedPdf(fsPath(encapsulatedPdfPath), pdfOf(info, content),
                                         pdfSeries, kNew);
        },
        progressParent);
}

} // namespace lw::gui
