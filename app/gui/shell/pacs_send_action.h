#pragma once

// The review's "Send to PACS…" (File menu and toolbar): asks for the node of the node file and
// the report's picture, sends through PacsSender with a busy indication over the window, then
// says what the PACS accepted per object. Disabled, with a tooltip saying why, while the node
// file lists no node (refresh() reads it again: when the File menu opens, when another review
// becomes current).

#include "shell/pacs_send.h"

#include <QObject>
#include <QPointer>
#include <QString>
#include <functional>

class QAction;
class QMainWindow;
class QProgressDialog;

namespace lw::gui {

class ReviewWidget;

class PacsSendAction : public QObject {
    Q_OBJECT
public:
    // `nodeFile`: the node file's path, asked for at each use.
    PacsSendAction(QMainWindow& window, std::function<ReviewWidget*()> currentReview,
                   std::function<QString()> nodeFile);

    QAction* action() const { return m_action; }
    PacsSender& sender() { return *m_sender; }

public slots:
    void refresh();
    void send();

private:
    void showResult(const PacsSendResult& result);

    QMainWindow& m_window;
    std::function<ReviewWidget*()> m_currentReview;
    std::function<QString()> m_nodeFile;
    QAction* m_action = nullptr;
    PacsSender* m_sender = nullptr;
    QPointer<QProgressDialog> m_busy; // deletes itself when closed
};

} // namespace lw::gui
