#pragma once

// Runs studydb::importStudies off the UI thread (a QtConcurrent pool thread that opens its own
// database connection) and reports back on the thread that owns the worker.

#include "lw/core/progress.h"
#include "lw/studydb/study_records.h"

#include <QFuture>
#include <QObject>
#include <QString>
#include <memory>

Q_DECLARE_METATYPE(lw::studydb::ImportSummary)

namespace lw::gui {

class ImportWorker : public QObject {
    Q_OBJECT

public:
    explicit ImportWorker(QString databasePath, QObject* parent = nullptr);
    // Cancels a running import and waits for it: the database connection of the pool thread
    // must be closed before the program goes on (or ends).
    ~ImportWorker() override;

    bool isRunning() const { return m_running; }
    // Starts importing `inputPath`; false (and nothing started) when an import is running.
    bool start(const QString& inputPath);
    // Asks the running import to stop; finished() follows with summary.cancelled set.
    void cancel();
    // Blocks until the background work is done (its signals are still queued afterwards).
    void waitForDone();

signals:
    void progress(double fraction, const QString& message);
    void finished(const lw::studydb::ImportSummary& summary);
    void failed(const QString& message);

private:
    QString m_databasePath;
    std::shared_ptr<core::CancelToken> m_cancel;
    QFuture<void> m_future;
    bool m_running = false;
};

} // namespace lw::gui
