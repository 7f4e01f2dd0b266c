#pragma once

// What ImportWorker and RetrieveJob share: one run at a time, a cancel token per run, and a wait
// for the run that their destructors call (the run opens its own database connection, which must
// be closed before the program goes on, or ends). Runs go to the job's own one-thread pool, never
// to Qt's global pool, which Qt 6.4's painting waits on, and at background priority
// (README, "Background work stays out of the painting's way").

#include "browser/background_task.h"
#include "lw/core/progress.h"
#include "lw/core/thread_priority.h"

#include <QFuture>
#include <QObject>
#include <QString>
#include <QThreadPool>
#include <memory>

namespace lw::gui {

class BackgroundJob : public QObject {
    Q_OBJECT
public:
    bool isRunning() const { return m_running; }
    // Thread-safe: asks the running run to stop at its next check of the token.
    void cancel();
    // Blocks until the run is done (its outcome is still queued afterwards).
    void waitForDone();

protected:
    explicit BackgroundJob(QString databasePath, QObject* parent = nullptr);
    // For the derived destructors, first thing: the run may still emit their signals.
    void cancelAndWait();
    const QString& databasePath() const { return m_databasePath; }

    // Runs work(token) on the pool unless a run is going (then false, nothing started). Exactly
    // one of onDone(result), onCancelled(), onFailed(text) follows on this object's thread, with
    // isRunning() false already.
    template <typename Work, typename Done, typename Cancelled, typename Failed>
    bool startRun(Work work, Done onDone, Cancelled onCancelled, Failed onFailed) {
        if (m_running)
            return false;
        m_running = true;
        m_cancel = std::make_shared<core::CancelToken>();
        m_future = runInBackground(
            &m_pool, this,
            [work, cancel = m_cancel] {
                core::lowerCurrentThreadToBackground();
                return work(cancel);
            },
            [this, onDone](const auto& result) {
                m_running = false;
                onDone(result);
            },
            [this, onCancelled] {
                m_running = false;
                onCancelled();
            },
            [this, onFailed](const QString& message) {
                m_running = false;
                onFailed(message);
            });
        return true;
    }

private:
    QString m_databasePath;
    QThreadPool m_pool;
    std::shared_ptr<core::CancelToken> m_cancel;
    QFuture<void> m_future;
    bool m_running = false;
};

} // namespace lw::gui
