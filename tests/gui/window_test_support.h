#pragma once

// What the main window tests share: the bundled demo study, an isolated study database, opening
// a path or importing a folder and waiting for the review.

#include "browser/study_browser.h"
#include "gui_test_support.h"
#include "review/review_widget.h"
#include "shell/main_window.h"

#include <QPointer>
#include <QSignalSpy>
#include <QTemporaryDir>
#include <QTest>

namespace lw::test {

inline QString demoStudy() {
    return sourcePath() + "/resources/demo/ct_head_ge_tilt";
}

// Waits for the review that the open call just made brings (MainWindow::reviewOpened: a new tab,
// or the tab of a series that was open already) and for its first frame -- not for whichever
// review is current, which right after an open can still be the one open before it. Call it
// right after openPath / openSeries: the review arrives through the event loop, which has not
// run yet.
inline bool waitForReview(gui::MainWindow& window, int timeoutMs = 60000) {
    QPointer<gui::ReviewWidget> opened;
    bool arrived = false;
    const QMetaObject::Connection connection =
        QObject::connect(&window, &gui::MainWindow::reviewOpened, [&](gui::ReviewWidget* review) {
            opened = review;
            arrived = true;
        });
    const bool shown = waitUntil(
        [&] { return arrived && opened && opened->status().framesShown > 0 && !opened->isBusy(); },
        timeoutMs);
    QObject::disconnect(connection);
    return shown;
}

inline QString importAndFindSeries(gui::MainWindow& window, const QString& path) {
    QSignalSpy finished(&window.browser(), &gui::StudyBrowser::importFinished);
    window.browser().importPath(path);
    if (!finished.wait(60000))
        return {};
    for (const auto& patient : window.browser().database().patients())
        for (const auto& study : patient.studies)
            for (const auto& series : study.series)
                if (series.sliceCount > 1)
                    return series.uid;
    return {};
}

// Shows the window and opens `path` in a review, waiting for its first frame.
inline bool showAndOpen(gui::MainWindow& window, const QString& path) {
    window.show();
    if (!QTest::qWaitForWindowExposed(&window))
        return false;
    window.openPath(path);
    return waitForReview(window);
}

inline gui::MainWindowOptions isolatedOptions(const QTemporaryDir& dir) {
    gui::MainWindowOptions options;
    options.databasePath = dir.filePath("studies.sqlite");
    return options;
}

} // namespace lw::test
