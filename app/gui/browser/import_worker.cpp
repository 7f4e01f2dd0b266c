#include "browser/import_worker.h"

#include "browser/background_task.h"
#include "lw/studydb/study_importer.h"

#include <QMetaObject>
#include <QPointer>

namespace lw::gui {

ImportWorker::ImportWorker(QString databasePath, QObject* parent)
    : QObject(parent), m_databasePath(std::move(databasePath)) {}

ImportWorker::~ImportWorker() {
    cancel();
    waitForDone();
}

bool ImportWorker::start(const QString& inputPath) {
    if (m_running)
        return false;
    m_running = true;
    m_cancel = std::make_shared<core::CancelToken>();
    const QString databasePath = m_databasePath;
    auto cancel = m_cancel;
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
    m_future = runInBackground(
        this,
        [databasePath, inputPath, onProgress, cancel] {
            return studydb::importStudies(databasePath, inputPath, onProgress, cancel);
        },
        [this](const studydb::ImportSummary& summary) {
            m_running = false;
            emit finished(summary);
        },
        [this] {
            // The importer reports a cancel in its summary; should one escape it, the same.
            m_running = false;
            studydb::ImportSummary summary;
            summary.cancelled = true;
            emit finished(summary);
        },
        [this](const QString& message) {
            m_running = false;
            emit failed(message);
        });
    return true;
}

void ImportWorker::cancel() {
    if (m_cancel)
        m_cancel->cancel();
}

void ImportWorker::waitForDone() {
    m_future.waitForFinished();
}

} // namespace lw::gui
