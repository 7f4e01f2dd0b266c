#include "shell/export_dialogs.h"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QPlainTextEdit>
#include <QSpinBox>

namespace lw::gui {

PictureExportDialog::PictureExportDialog(const QString& title, QSize screenPanelSize,
                                         QWidget* parent)
    : QDialog(parent) {
    setWindowTitle(title);
    m_layout = new QComboBox;
    m_layout->setObjectName("exportLayout");
    // In the order of report::PanelLayout.
    m_layout->addItems(
        {tr("Both panels side by side"), tr("Iso-surface panel"), tr("Silhouette panel")});
    m_width = new QSpinBox;
    m_height = new QSpinBox;
    for (QSpinBox* box : {m_width, m_height}) {
        box->setRange(16, 8192);
        box->setSuffix(tr(" px"));
    }
    m_width->setValue(2 * screenPanelSize.width());
    m_height->setValue(2 * screenPanelSize.height());
    auto* size = new QHBoxLayout;
    size->addWidget(m_width);
    size->addWidget(new QLabel(QStringLiteral("×")));
    size->addWidget(m_height);
    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    auto* outer = new QVBoxLayout(this);
    m_form = new QFormLayout;
    m_form->addRow(tr("Picture:"), m_layout);
    m_form->addRow(tr("Size of each panel:"), size);
    m_form->addRow(new QLabel(tr("The panels are rendered again at this size; lines, "
                                 "annotations and text grow with it.")));
    outer->addLayout(m_form);
    outer->addWidget(buttons);
}

ExportPicture PictureExportDialog::picture() const {
    return {{m_width->value(), m_height->value()}, report::PanelLayout(m_layout->currentIndex())};
}

ReportExportDialog::ReportExportDialog(QSize screenPanelSize, QWidget* parent, const QString& title)
    : PictureExportDialog(title.isEmpty() ? tr("Export report") : title, screenPanelSize, parent) {
    setObjectName("reportExportDialog");
    m_comment = new QPlainTextEdit;
    m_comment->setObjectName("reportComment");
    m_comment->setPlaceholderText(tr("Findings, comparison, recommendation…"));
    m_anonymise = new QCheckBox(tr("Anonymise (leave out the patient's name, ID, birth date, "
                                   "sex and the accession number)"));
    m_anonymise->setObjectName("reportAnonymise");
    form().addRow(tr("Comment:"), m_comment);
    form().addRow(m_anonymise);
}

ReportOptions ReportExportDialog::options() const {
    return {picture(), m_comment->toPlainText(), m_anonymise->isChecked()};
}

SendToPacsDialog::SendToPacsDialog(const QStringList& nodeNames, QSize screenPanelSize,
                                   QWidget* parent)
    : ReportExportDialog(screenPanelSize, parent, tr("Send to PACS")) {
    setObjectName("sendToPacsDialog");
    m_node = new QComboBox;
    m_node->setObjectName("sendToPacsNode");
    m_node->addItems(nodeNames);
    form().insertRow(0, tr("PACS:"), m_node);
    form().insertRow(1, new QLabel(tr("The Secondary Capture and the report (as DICOM "
                                      "Encapsulated PDF) join the patient's study.")));
}

int SendToPacsDialog::nodeIndex() const {
    return m_node->currentIndex();
}

} // namespace lw::gui
