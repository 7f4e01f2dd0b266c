#pragma once

// The File menu's exports of the current review: PNG (Ctrl+E), PDF report (Ctrl+Shift+E) and
// DICOM Secondary Capture. Each asks what to export, then where (a file dialog that confirms
// replacing an existing file, or a folder), runs it (review_export.h) and says how it went: in
// the status bar when written, in a message box naming the file and the reason when not.

#include <QObject>
#include <QString>
#include <functional>

class QAction;
class QMainWindow;

namespace lw::gui {

class ReviewWidget;

class ExportActions : public QObject {
    Q_OBJECT
public:
    ExportActions(QMainWindow& window, std::function<ReviewWidget*()> currentReview);

    QAction* pngAction() const { return m_png; }
    QAction* reportAction() const { return m_report; }
    QAction* secondaryCaptureAction() const { return m_secondaryCapture; }

public slots:
    void exportPng();
    void exportReport();
    void exportSecondaryCapture();

private:
    ReviewWidget* reviewOrSayWhy() const;
    void tell(const QString& error, const QString& written) const;

    QMainWindow& m_window;
    std::function<ReviewWidget*()> m_currentReview;
    QAction* m_png = nullptr;
    QAction* m_report = nullptr;
    QAction* m_secondaryCapture = nullptr;
};

} // namespace lw::gui
