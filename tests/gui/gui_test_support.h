#pragma once

// Shared set-up for the Qt GUI tests (label gui): real widgets on a real X server (xvfb-run in
// the test command), settings and data directories isolated in a temporary folder, the GL
// format the workstation asks for, and SKIP (exit 77) when there is no display.

#include "review/review_panel.h"

#include <QApplication>
#include <QDeadlineTimer>
#include <QImage>
#include <QSettings>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

namespace lw::test {

constexpr int kGuiSkipCode = 77;

// Where ../shared/data is (LINEWORK_SHARED_DATA from CTest), or an empty string.
inline QString sharedDataPath() {
    const char* path = std::getenv("LINEWORK_SHARED_DATA");
    if (!path || !QFileInfo::exists(QString::fromLocal8Bit(path)))
        return {};
    return QString::fromLocal8Bit(path);
}

inline QString sourcePath() {
    const char* path = std::getenv("LINEWORK_SOURCE_DIR");
    return path ? QString::fromLocal8Bit(path) : QString();
}

// Waits until `done()` holds; false if it still does not after `timeoutMs`. Unlike
// QTest::qWaitFor, which naps 10 ms between looks while what arrives meanwhile waits, it sleeps
// in the event loop: each event (a worker's result, a paint) is handled when it comes and the
// condition looked at again; a timer wakes it at the deadline. The condition must be one that
// the UI thread's events change (a result delivered, a signal), not a flag another thread sets.
template <typename Condition> bool waitUntil(Condition done, int timeoutMs) {
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

// Pixels of `image` whose colour differs from `background` by more than `tolerance` in a channel.
inline int pixelsDifferentFrom(const QImage& image, QColor background, int tolerance = 8) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    int count = 0;
    for (int y = 0; y < rgb.height(); ++y) {
        const auto* row = reinterpret_cast<const QRgb*>(rgb.constScanLine(y));
        for (int x = 0; x < rgb.width(); ++x)
            if (std::abs(qRed(row[x]) - background.red()) > tolerance ||
                std::abs(qGreen(row[x]) - background.green()) > tolerance ||
                std::abs(qBlue(row[x]) - background.blue()) > tolerance)
                ++count;
    }
    return count;
}

// Whether the annotations' burnt-in orange (report::OverlayStyle) is within `radius` pixels of
// `at`: where the camera puts an anchor, the annotation must be drawn.
inline bool annotationColourNear(const QImage& image, QPointF at, int radius = 4) {
    for (int y = int(at.y()) - radius; y <= int(at.y()) + radius; ++y)
        for (int x = int(at.x()) - radius; x <= int(at.x()) + radius; ++x)
            if (image.valid(x, y)) {
                const QColor c = image.pixelColor(x, y);
                if (c.red() > 190 && c.green() > 40 && c.green() < 130 && c.blue() < 60)
                    return true;
            }
    return false;
}

// Makes `window` the active window, for tests whose keys go through window shortcuts (Ctrl+Z,
// a tool's letter). Asking the X server is not enough: without a window manager it ignores a
// focus request whose timestamp predates its last focus change (an earlier test's window
// closing), and nothing asks again, so qWaitForWindowActive fails by luck. Shortcuts consult
// Qt's own active window, which this sets directly and then checks.
inline bool makeActiveForKeys(QWidget& window) {
    QApplication::setActiveWindow(&window);
    return QApplication::activeWindow() == &window;
}

// Runs a Qt Test class the way the workstation starts: isolated settings and data folders, an
// OpenGL 4.5 core default format, SKIP without a display.
template <typename TestClass> int runGuiTest(int argc, char** argv, bool needsData = false) {
    if (std::getenv("DISPLAY") == nullptr && std::getenv("WAYLAND_DISPLAY") == nullptr) {
        std::fprintf(stderr, "SKIP: no display (run under xvfb-run)\n");
        return kGuiSkipCode;
    }
    if (needsData && sharedDataPath().isEmpty()) {
        std::fprintf(stderr, "SKIP: ../shared/data is missing\n");
        return kGuiSkipCode;
    }
    QTemporaryDir home;
    // Settings, the study database and caches go to the temporary folder, never the user's.
    qputenv("XDG_CONFIG_HOME", (home.path() + "/config").toLocal8Bit());
    qputenv("XDG_DATA_HOME", (home.path() + "/data").toLocal8Bit());
    qputenv("XDG_CACHE_HOME", (home.path() + "/cache").toLocal8Bit());
    qputenv("QT_QPA_PLATFORM", "xcb");
    QStandardPaths::setTestModeEnabled(true);
    // Test mode alone puts QSettings in ~/.qttest, shared by every test process and every run:
    // one test's stored settings (the settings dialog's) became another's starting ones.
    for (const QSettings::Format format : {QSettings::NativeFormat, QSettings::IniFormat})
        QSettings::setPath(format, QSettings::UserScope, home.path() + "/config");
    gui::requestCoreProfileFormat();
    QApplication app(argc, argv);
    QApplication::setOrganizationName("LineworkTest");
    QApplication::setApplicationName("linework-test");
    TestClass test;
    return QTest::qExec(&test, argc, argv);
}

} // namespace lw::test

#define LW_GUI_TEST_MAIN(TestClass)                                                                \
    int main(int argc, char** argv) {                                                              \
        return lw::test::runGuiTest<TestClass>(argc, argv);                                        \
    }
#define LW_GUI_DATA_TEST_MAIN(TestClass)                                                           \
    int main(int argc, char** argv) {                                                              \
        return lw::test::runGuiTest<TestClass>(argc, argv, true);                                  \
    }
