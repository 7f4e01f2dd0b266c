#pragma once

// Runs studydb::importStudies off the UI thread (a pool thread that opens its own database
// connection) and reports back on the thread that owns the worker.

#include "browser/background_job.h"
#include "lw/studydb/study_records.h"

#include <QString>

Q_DECLARE_METATYPE(lw::studydb::ImportSummary)

namespace lw::gui {

class ImportWorker : public BackgroundJob {
    Q_OBJECT

public:
    explicit ImportWorker(QString databasePath, QObject* parent = nullptr);
    // Cancels a running import and waits for it: the database connection of the pool thread
    // must be closed before the program goes on (or ends).
    ~ImportWorker() override;

    // Starts importing `inputPath`; false (and nothing started) when an import is running.
    // cancel() makes finished() follow with summary.cancelled set.
    bool start(const QString& inputPath);

signals:
    void progress(double fraction, const QString& message);
    void finished(const lw::studydb::ImportSummary& summary);
    void failed(const QString& message);
};

} // namespace lw::gui
