#pragma once

// What an export shows and at which size (the file or folder is asked for afterwards): the PNG
// and the Secondary Capture ask for the picture; the PDF report also for a comment and whether
// to leave the patient out; "Send to PACS" also for the node.

#include "shell/review_export.h"

#include <QDialog>

class QCheckBox;
class QComboBox;
class QFormLayout;
class QPlainTextEdit;
class QSpinBox;

namespace lw::gui {

class PictureExportDialog : public QDialog {
    Q_OBJECT
public:
    // `screenPanelSize`: a panel on screen; the default is twice that (print resolution).
    PictureExportDialog(const QString& title, QSize screenPanelSize, QWidget* parent = nullptr);
    ExportPicture picture() const;

protected:
    // Rows go above the buttons.
    QFormLayout& form() { return *m_form; }

private:
    QFormLayout* m_form = nullptr;
    QComboBox* m_layout = nullptr;
    QSpinBox* m_width = nullptr;
    QSpinBox* m_height = nullptr;
};

class ReportExportDialog : public PictureExportDialog {
    Q_OBJECT
public:
    explicit ReportExportDialog(QSize screenPanelSize, QWidget* parent = nullptr,
                                const QString& title = QString());
    ReportOptions options() const;

private:
    QPlainTextEdit* m_comment = nullptr;
    QCheckBox* m_anonymise = nullptr;
};

// "Send to PACS": which node (by its name in the node file), then the report's picture and
// comment. Anonymising stays offered so that choosing it is answered with why it is refused.
class SendToPacsDialog : public ReportExportDialog {
    Q_OBJECT
public:
    SendToPacsDialog(const QStringList& nodeNames, QSize screenPanelSize,
                     QWidget* parent = nullptr);
    int nodeIndex() const;

private:
    QComboBox* m_node = nullptr;
};

} // namespace lw::gui
