#include "shell/export_actions.h"

#include "lw/report/secondary_capture.h"
#include "review/review_panel.h"
#include "review/review_widget.h"
#include "shell/export_dialogs.h"
#include "shell/review_export.h"

#include <QAction>
#include <QDir>
#include <QFileDialog>
#include <QFileInfo>
#include <QMainWindow>
#include <QMessageBox>
#include <QStatusBar>
#include <optional>

namespace lw::gui {
namespace {

struct ChosenTarget {
    QString path;
    // Allow only where the user agreed to replace what is there.
    core::Overwrite overwrite = core::Overwrite::Refuse;
};

// A file to write; the save dialog confirms replacing an existing file. nullopt: cancelled.
std::optional<ChosenTarget> chooseFile(QWidget* parent, const QString& title, const QString& filter,
                                       const QString& suffix) {
    QString path = QFileDialog::getSaveFileName(parent, title, QString(), filter);
    if (path.isEmpty())
        return std::nullopt;
    if (!path.endsWith(suffix, Qt::CaseInsensitive)) {
        path += suffix; // a name the dialog did not check: ask here
        if (QFileInfo::exists(path) &&
            QMessageBox::question(parent, title, QObject::tr("%1 exists. Replace it?").arg(path)) !=
                QMessageBox::Yes)
            return std::nullopt;
    }
    return ChosenTarget{path,
                        QFileInfo::exists(path) ? core::Overwrite::Allow : core::Overwrite::Refuse};
}

// A folder for the Secondary Capture; replacing an earlier one there is asked for.
std::optional<ChosenTarget> chooseFolder(QWidget* parent, const QString& title) {
    const QString folder = QFileDialog::getExistingDirectory(parent, title);
    if (folder.isEmpty())
        return std::nullopt;
    const QString first =
        QDir(folder).filePath(QString::fromStdString(report::secondaryCaptureFileName(1)));
    if (!QFileInfo::exists(first))
        return ChosenTarget{folder, core::Overwrite::Refuse};
    if (QMessageBox::question(parent, title,
                              QObject::tr("%1 holds a Secondary Capture already (%2). Replace it?")
                                  .arg(folder, QFileInfo(first).fileName())) != QMessageBox::Yes)
        return std::nullopt;
    return ChosenTarget{folder, core::Overwrite::Allow};
}

} // namespace

ExportActions::ExportActions(QMainWindow& window, std::function<ReviewWidget*()> currentReview)
    : QObject(&window), m_window(window), m_currentReview(std::move(currentReview)) {
    const auto make = [this](const QString& text, const QKeySequence& key, const QString& name,
                             void (ExportActions::*slot)()) {
        auto* action = new QAction(text, this);
        action->setShortcut(key);
        action->setObjectName(name);
        connect(action, &QAction::triggered, this, slot);
        return action;
    };
    m_png = make(tr("&Export PNG…"), QKeySequence(tr("Ctrl+E")), "exportPngAction",
                 &ExportActions::exportPng);
    m_report = make(tr("Export &report (PDF)…"), QKeySequence(tr("Ctrl+Shift+E")),
                    "exportReportAction", &ExportActions::exportReport);
    m_secondaryCapture =
        make(tr("Export Secondary &Capture (DICOM)…"), QKeySequence(),
             "exportSecondaryCaptureAction", &ExportActions::exportSecondaryCapture);
}

ReviewWidget* ExportActions::reviewOrSayWhy() const {
    ReviewWidget* review = m_currentReview();
    if (!review)
        m_window.statusBar()->showMessage(tr("Open a review to export it"), 5000);
    return review;
}

void ExportActions::tell(const QString& error, const QString& written) const {
    if (error.isEmpty())
        m_window.statusBar()->showMessage(tr("Exported %1").arg(written), 8000);
    else
        QMessageBox::warning(&m_window, tr("Export failed"), error);
}

void ExportActions::exportPng() {
    ReviewWidget* review = reviewOrSayWhy();
    if (!review)
        return;
    PictureExportDialog dialog(tr("Export PNG"), review->silhouettePanel().renderSize(), &m_window);
    if (dialog.exec() != QDialog::Accepted)
        return;
    const auto target = chooseFile(&m_window, tr("Export PNG"), tr("PNG images (*.png)"), ".png");
    if (target)
        tell(exportReviewPng(*review, target->path, dialog.picture(), target->overwrite, &m_window),
             target->path);
}

void ExportActions::exportReport() {
    ReviewWidget* review = reviewOrSayWhy();
    if (!review)
        return;
    ReportExportDialog dialog(review->silhouettePanel().renderSize(), &m_window);
    if (dialog.exec() != QDialog::Accepted)
        return;
    const auto target =
        chooseFile(&m_window, tr("Export report"), tr("PDF documents (*.pdf)"), ".pdf");
    if (target)
        tell(exportReviewReport(*review, target->path, dialog.options(), target->overwrite,
                                &m_window),
             target->path);
}

void ExportActions::exportSecondaryCapture() {
    ReviewWidget* review = reviewOrSayWhy();
    if (!review)
        return;
    if (!review->source().dicom) {
        tell(tr("A Secondary Capture joins the source's study, and %1 is not a DICOM series")
                 .arg(review->source().title),
             {});
        return;
    }
    PictureExportDialog dialog(tr("Export Secondary Capture"),
                               review->silhouettePanel().renderSize(), &m_window);
    if (dialog.exec() != QDialog::Accepted)
        return;
    const auto target = chooseFolder(&m_window, tr("Folder for the Secondary Capture"));
    if (target)
        tell(exportReviewSecondaryCapture(*review, target->path, dialog.picture(),
                                          target->overwrite, &m_window),
             tr("a Secondary Capture into %1").arg(target->path));
}

} // namespace lw::gui
