#pragma once

// "Send to PACS": the review's Secondary Capture and its PDF report as DICOM Encapsulated PDF,
// both new series of the source's study, written into a temporary folder and then stored on a
// PACS node by C-STORE on a pool thread (modules/pacs blocks); what the PACS answered per object
// comes back in finished(). Refused before anything is written when the report is anonymised
// (it would no longer belong to the patient's study) or the review is not of a DICOM series.
// The rendering shows the exports' progress dialog; the caller shows a busy indication until
// finished(). A C-STORE cannot be cancelled (modules/pacs's storeFiles takes no cancel token);
// each of its messages is bounded by the call's timeout.

#include "lw/pacs/pacs_client.h"
#include "lw/pacs/pacs_node.h"
#include "shell/review_export.h"

#include <QFutureWatcher>
#include <QObject>
#include <QString>
#include <QTemporaryDir>
#include <memory>
#include <vector>

namespace lw::gui {

class ReviewWidget;

struct PacsSendRequest {
    pacs::PacsNode node;
    pacs::CallOptions call; // the workstation's AE title, the timeout
    ReportOptions report;   // the picture, the comment; anonymise is refused
};

// What the PACS answered for one object.
struct PacsSendOutcome {
    QString object; // "Secondary Capture", "Report (Encapsulated PDF)"
    QString answer; // the PACS's status in words: "stored", "refused: ..."
    bool stored = false;
};

struct PacsSendResult {
    QString node;                         // "name (AET@HOST:PORT)"
    std::vector<PacsSendOutcome> objects; // none when no association was made
    QString error;                        // why nothing was sent; empty when it was
    bool allStored() const;
    // One line per object ("Secondary Capture: stored"), or the error.
    QString summary() const;
};

class PacsSender : public QObject {
    Q_OBJECT
public:
    explicit PacsSender(QObject* parent = nullptr);
    ~PacsSender() override; // waits for a store still running (bounded by its timeout)

    // Renders and writes the objects, then starts the C-STORE and returns "": finished() follows.
    // Returns why instead when refused or when writing failed; finished() does not follow then.
    // Also refused while a send is running.
    QString start(ReviewWidget& review, const PacsSendRequest& request,
                  QWidget* progressParent = nullptr);
    bool isSending() const { return m_watcher.isRunning(); }

signals:
    void finished(const lw::gui::PacsSendResult& result);

private:
    QString writeObjects(ReviewWidget& review, const ReportOptions& options,
                         QWidget* progressParent);

    std::unique_ptr<QTemporaryDir> m_folder;            // the objects, until the store is done
    std::vector<std::pair<QString, QString>> m_objects; // (what, file)
    QFutureWatcher<PacsSendResult> m_watcher;
};

} // namespace lw::gui

Q_DECLARE_METATYPE(lw::gui::PacsSendResult)
