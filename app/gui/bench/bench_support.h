#pragma once

// What the workstation's measuring tools share: settings and data in a temporary folder (never
// the user's), and waiting on the event loop for a condition.

#include <QCoreApplication>
#include <QDeadlineTimer>
#include <QTemporaryDir>
#include <QTimer>
#include <functional>

namespace lw::gui::bench {

// Before QApplication: QSettings and QStandardPaths under `home`.
inline void isolateUserFolders(const QTemporaryDir& home) {
    qputenv("XDG_CONFIG_HOME", (home.path() + "/config").toLocal8Bit());
    qputenv("XDG_DATA_HOME", (home.path() + "/data").toLocal8Bit());
}

// Runs the event loop until `done` or `timeoutMs`; false on timeout. It sleeps in the event loop
// and looks at `done` after each event (a result delivered, a paint, a timer), as the GUI tests'
// waitUntil: a loop that polled instead kept the UI thread busy on one of dev-2c's two cores,
// leaving the render worker and its helper (background priority) one core between them for the
// frames it measures, unlike a user's idle UI thread. `done` must be changed by the UI thread's
// events.
inline bool waitFor(const std::function<bool()>& done, int timeoutMs = 120000) {
    const QDeadlineTimer deadline(timeoutMs);
    QTimer wakeAtDeadline;
    wakeAtDeadline.setSingleShot(true);
    wakeAtDeadline.start(timeoutMs);
    while (!done()) {
        if (deadline.hasExpired())
            return false;
        QCoreApplication::processEvents(QEventLoop::AllEvents | QEventLoop::WaitForMoreEvents);
        QCoreApplication::sendPostedEvents(nullptr, QEvent::DeferredDelete);
    }
    return true;
}

} // namespace lw::gui::bench
