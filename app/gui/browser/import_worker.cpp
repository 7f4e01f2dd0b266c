#include "browser/import_worker.h"

#include "lw/core/error.h"
#include "lw/studydb/study_importer.h"

#include <QMetaObject>
#include <QPointer>
#include <QtConcurrent/QtConcurrentRun>

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
    // Results travel back as queued calls on this object: Qt drops them if it is gone by then,
    // and the destructor waits for the pool thread, so `this` is never used after deletion.
    QPointer<ImportWorker> self(this);
    m_future = QtConcurrent::run([self, databasePath, inputPath, cancel] {
        const auto post = [self](auto call) {
            QMetaObject::invokeMethod(self.data(), std::move(call), Qt::QueuedConnection);
        };
        const auto onProgress = [self, post](double fraction, const std::string& message) {
            const QString text = QString::fromStdString(message);
            post([self, fraction, text] { emit self->progress(fraction, text); });
        };
        try {
            const studydb::ImportSummary summary =
                studydb::importStudies(databasePath, inputPath, onProgress, cancel);
            post([self, summary] {
                self->m_running = false;
                emit self->finished(summary);
            });
        } catch (const core::Error& error) {
            const QString message = QStringLiteral("%1: %2").arg(
                QString::fromStdString(error.subject()), QString::fromStdString(error.reason()));
            post([self, message] {
                self->m_running = false;
                emit self->failed(message);
            });
        } catch (const std::exception& error) {
            const QString message = QString::fromStdString(error.what());
            post([self, message] {
                self->m_running = false;
                emit self->failed(message);
            });
        }
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
