#include "shell/png_export.h"

#include "lw/core/error.h"
#include "lw/core/png_io.h"
#include "review/panel_render_job.h"
#include "review/qt_image.h"
#include "review/review_widget.h"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QEventLoop>
#include <QFileInfo>
#include <QFormLayout>
#include <QFutureWatcher>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressDialog>
#include <QSpinBox>
#include <QtConcurrent/QtConcurrentRun>
#include <cstring>
#include <new>

namespace lw::gui {
namespace {

// Renders and writes; thread-safe when `job` is used (no review access).
QString writeExport(const QImage& image, const QString& path) {
    if (image.isNull())
        return QObject::tr("%1: nothing to export yet (the surface is still being computed)")
            .arg(path);
    core::writePng(path.toStdString(), toCoreImage(image), core::PngFormat::Rgb);
    return {};
}

QImage composeLayout(const std::pair<QImage, QImage>& panels, ExportLayout layout,
                     QColor background) {
    switch (layout) {
    case ExportLayout::SideBySide:
        return sideBySide(panels.first, panels.second, background);
    case ExportLayout::IsoPanel:
        return panels.first;
    case ExportLayout::SilhouettePanel:
        return panels.second;
    }
    return {};
}

template <typename Work> QString guarded(const QString& path, QSize size, Work&& work) {
    try {
        return work();
    } catch (const core::Error& error) {
        return QString::fromStdString(error.what());
    } catch (const std::bad_alloc&) {
        return QObject::tr("%1: out of memory rendering %2 x %3 pixels; choose a smaller size")
            .arg(path)
            .arg(size.width())
            .arg(size.height());
    }
}

} // namespace

QString exportReviewPng(ReviewWidget& review, const QString& path, QSize panelSize,
                        ExportLayout layout, QWidget* progressParent) {
    const QColor background = review.settings().background;
    if (review.rendersOnUiThread()) // a GPU draws in the panels' contexts: fast, and only here
        return guarded(path, panelSize, [&] {
            return writeExport(composeLayout(review.renderPanels(panelSize), layout, background),
                               path);
        });
    // Off the UI thread: the job is a copy of what the panels show.
    const PanelRenderJob job = review.renderJob(panelSize);
    QFuture<QString> future = QtConcurrent::run([job, layout, background, path, panelSize] {
        return guarded(path, panelSize, [&] {
            return writeExport(composeLayout(renderPanelJob(job), layout, background), path);
        });
    });
    QProgressDialog progress(QObject::tr("Rendering %1 at %2 x %3…")
                                 .arg(QFileInfo(path).fileName())
                                 .arg(panelSize.width())
                                 .arg(panelSize.height()),
                             QString(), 0, 0, progressParent);
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

PngExportDialog::PngExportDialog(QSize panelSize, QWidget* parent) : QDialog(parent) {
    setWindowTitle(tr("Export PNG"));
    setObjectName("pngExportDialog");
    m_layout = new QComboBox;
    m_layout->addItems(
        {tr("Both panels side by side"), tr("Iso-surface panel"), tr("Silhouette panel")});
    m_width = new QSpinBox;
    m_height = new QSpinBox;
    for (QSpinBox* box : {m_width, m_height}) {
        box->setRange(16, 8192);
        box->setSuffix(tr(" px"));
    }
    // Twice the screen by default: print resolution for a report page.
    m_width->setValue(2 * panelSize.width());
    m_height->setValue(2 * panelSize.height());
    auto* size = new QHBoxLayout;
    size->addWidget(m_width);
    size->addWidget(new QLabel(QStringLiteral("×")));
    size->addWidget(m_height);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    auto* form = new QFormLayout(this);
    form->addRow(tr("Picture:"), m_layout);
    form->addRow(tr("Size of each panel:"), size);
    form->addRow(
        new QLabel(tr("The panels are rendered again at this size; lines widen with it.")));
    form->addRow(buttons);
}

QSize PngExportDialog::panelSize() const {
    return {m_width->value(), m_height->value()};
}

ExportLayout PngExportDialog::layout() const {
    return ExportLayout(m_layout->currentIndex());
}

} // namespace lw::gui
