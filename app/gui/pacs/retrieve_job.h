#pragma once

// One retrieve of a remote series or study, off the UI thread: lw::pacs::retrieve into the
// managed store (resumable: only missing instances travel), then what arrived is registered in
// the study database (studydb::registerRetrievedFolder, as `linework-cli pacs get` does), also
// after a cancel or a transfer that stopped halfway, so the database lists exactly the files
// that are there.

#include "browser/background_job.h"
#include "lw/pacs/retrieve.h"

#include <QString>

namespace lw::gui {

struct RetrieveOutcome {
    QString nodeName;
    QString studyUid;
    QString seriesUid; // empty: the whole study
    int instances = 0, transferred = 0, skipped = 0, failed = 0;
    bool cancelled = false;
    QString message; // empty when everything arrived and was registered
    bool complete() const { return message.isEmpty() && transferred + skipped == instances; }
};

// cancel() is thread-safe: the module checks the token after each arriving instance and sends
// C-CANCEL.
class RetrieveJob : public BackgroundJob {
    Q_OBJECT
public:
    explicit RetrieveJob(QString databasePath, QObject* parent = nullptr);
    // Cancels a running retrieve and waits for it (its database connection must close first).
    ~RetrieveJob() override;

    // False (nothing started) while a retrieve runs.
    bool start(const pacs::PacsNode& node, const pacs::RetrieveRequest& request,
               const pacs::CallOptions& options);

signals:
    // Emitted on the retrieve's thread after each arriving instance (queued to the UI thread by
    // default; a direct connection runs before the module checks the cancel token).
    void instanceArrived(int done, int toTransfer);
    // On the UI thread: what arrived and was registered, or why not all of it.
    void finished(const lw::gui::RetrieveOutcome& outcome);
    // On the UI thread: nothing could start (the PACS is down, refused, no disk space); the node
    // and the reason in words.
    void failed(const QString& message);
};

} // namespace lw::gui

Q_DECLARE_METATYPE(lw::gui::RetrieveOutcome)
