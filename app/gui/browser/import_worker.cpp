#include "browser/import_worker.h"

#include "lw/studydb/study_importer.h"

#include <QMetaObject>
#include <QPointer>

namespace lw::gui {

ImportWorker::ImportWorker(QString databasePath, QObject* parent)
    : BackgroundJob(std::move(databasePath), parent) {}

ImportWorker::~ImportWorker() {
    cancelAndWait();
}

bool ImportWorker::start(const QString& inputPath) {
    // Progress travels back as queued calls on this object: Qt drops them if it is gone by then,
    // and the destructor waits for the pool thread, so `this` is never used after deletion.
    QPointer<ImportWorker> self(this);
    const auto onProgress = [self](double fraction, const std::string& message) {
        QMetaObject::invokeMethod(
            self.data(),
            [self, fraction, text = QString::fromStdString(message)] {
                emit self->progress(fraction, text);
            },
            Qt::QueuedConnection);
    };
    return startRun(
        [databasePath = databasePath(), inputPath,
         onProgress](const std::shared_ptr<core::CancelToken>& cancel) {
            return studydb::importStudies(databasePath, inputPath, onProgress, cancel);
        },
        [this](const studydb::ImportSummary& summary) { emit finished(summary); },
        [this] {
            // The importer reports a cancel in its summary; should one escape it, the same.
            studydb::ImportSummary summary;
            summary.cancelled = true;
            emit finished(summary);
        },
        [this](const QString& message) { emit failed(message); });
}

} // namespace lw::gui
