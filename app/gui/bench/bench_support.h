#pragma once

// What the workstation's measuring tools share: settings and data in a temporary folder (never
// the user's), and waiting on the event loop for a condition.

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QTemporaryDir>
#include <functional>

namespace lw::gui::bench {

// Before QApplication: QSettings and QStandardPaths under `home`.
inline void isolateUserFolders(const QTemporaryDir& home) {
    qputenv("XDG_CONFIG_HOME", (home.path() + "/config").toLocal8Bit());
    qputenv("XDG_DATA_HOME", (home.path() + "/data").toLocal8Bit());
}

// Runs the event loop until `done` or `timeoutMs`; false on timeout.
inline bool waitFor(const std::function<bool()>& done, int timeoutMs = 120000) {
    QElapsedTimer timer;
    timer.start();
    while (!done()) {
        if (timer.elapsed() > timeoutMs)
            return false;
        QCoreApplication::processEvents(QEventLoop::AllEvents, 5);
    }
    return true;
}

} // namespace lw::gui::bench
