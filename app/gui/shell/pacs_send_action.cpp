#include "shell/pacs_send_action.h"

#include "lw/core/error.h"
#include "review/review_panel.h"
#include "review/review_widget.h"
#include "shell/export_dialogs.h"

#include <QAction>
#include <QMainWindow>
#include <QMessageBox>
#include <QProgressDialog>
#include <QStatusBar>

namespace lw::gui {
namespace {

// The node file, or why it cannot be used (unreadable, or no node in it).
struct Nodes {
    pacs::PacsNodeFile file;
    QString whyNone;
};

Nodes readNodes(const QString& path) {
    Nodes nodes;
    try {
        nodes.file = pacs::readNodeFileOrDefaults(std::filesystem::path(path.toStdString()));
    } catch (const core::Error& error) {
        nodes.whyNone = QString::fromStdString(error.what());
        return nodes;
    }
    if (nodes.file.nodes.empty())
        nodes.whyNone =
            QObject::tr("No PACS node is configured: add one in Settings (%1)").arg(path);
    return nodes;
}

} // namespace

PacsSendAction::PacsSendAction(QMainWindow& window, std::function<ReviewWidget*()> currentReview,
                               std::function<QString()> nodeFile)
    : QObject(&window), m_window(window), m_currentReview(std::move(currentReview)),
      m_nodeFile(std::move(nodeFile)) {
    m_action = new QAction(tr("Send to &PACS…"), this);
    m_action->setObjectName("sendToPacsAction");
    connect(m_action, &QAction::triggered, this, &PacsSendAction::send);
    m_sender = new PacsSender(this);
    connect(m_sender, &PacsSender::finished, this, &PacsSendAction::showResult);
    refresh();
}

void PacsSendAction::refresh() {
    const Nodes nodes = readNodes(m_nodeFile());
    m_action->setEnabled(nodes.whyNone.isEmpty());
    m_action->setToolTip(nodes.whyNone.isEmpty()
                             ? tr("Store the Secondary Capture and the report (Encapsulated PDF) "
                                  "in the patient's study on the PACS")
                             : nodes.whyNone);
}

void PacsSendAction::send() {
    ReviewWidget* review = m_currentReview();
    const Nodes nodes = readNodes(m_nodeFile());
    QString refusal = !review ? tr("Open a review to send it to the PACS") : nodes.whyNone;
    if (refusal.isEmpty() && m_sender->isSending())
        refusal = tr("A send to the PACS is still running");
    if (!refusal.isEmpty()) {
        QMessageBox::warning(&m_window, tr("Send to PACS"), refusal);
        return;
    }
    QStringList names;
    for (const pacs::PacsNode& node : nodes.file.nodes)
        names << QString::fromStdString(node.name);
    SendToPacsDialog dialog(names, review->silhouettePanel().renderSize(), &m_window);
    if (dialog.exec() != QDialog::Accepted)
        return;
    PacsSendRequest request;
    request.node = nodes.file.nodes.at(std::size_t(dialog.nodeIndex()));
    request.call.callingAet = nodes.file.workstation.aet;
    request.report = dialog.options();
    if (const QString error = m_sender->start(*review, request, &m_window); !error.isEmpty()) {
        QMessageBox::warning(&m_window, tr("Send to PACS"), error);
        return;
    }
    // Busy until finished(): the C-STORE runs on a pool thread and cannot be cancelled.
    m_busy = new QProgressDialog(
        tr("Sending to %1…").arg(QString::fromStdString(pacs::describeNode(request.node))),
        QString(), 0, 0, &m_window);
    m_busy->setObjectName("sendToPacsBusy");
    m_busy->setWindowModality(Qt::WindowModal);
    m_busy->setMinimumDuration(300);
    m_busy->setAttribute(Qt::WA_DeleteOnClose);
}

void PacsSendAction::showResult(const PacsSendResult& result) {
    if (m_busy)
        m_busy->close();
    m_window.statusBar()->showMessage(result.allStored()
                                          ? tr("Sent to %1").arg(result.node)
                                          : tr("Sending to %1 failed").arg(result.node),
                                      8000);
    auto* box =
        new QMessageBox(result.allStored() ? QMessageBox::Information : QMessageBox::Warning,
                        tr("Send to PACS"), result.summary(), QMessageBox::Ok, &m_window);
    box->setObjectName("sendToPacsResult");
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
}

} // namespace lw::gui
