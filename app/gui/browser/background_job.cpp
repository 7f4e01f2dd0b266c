#include "browser/background_job.h"

namespace lw::gui {

BackgroundJob::BackgroundJob(QString databasePath, QObject* parent)
    : QObject(parent), m_databasePath(std::move(databasePath)) {
    m_pool.setMaxThreadCount(1);
}

void BackgroundJob::cancel() {
    if (m_cancel)
        m_cancel->cancel();
}

void BackgroundJob::waitForDone() {
    m_future.waitForFinished();
}

void BackgroundJob::cancelAndWait() {
    cancel();
    waitForDone();
}

} // namespace lw::gui
