// The workstation's window end to end: import the bundled demo study through the browser and open
// its series in a review; open paths directly; cancel or replace an open (nothing of it shown);
// errors (a series whose files have gone, a path that does not exist) are shown, never a crash;
// settings apply to open reviews.
#include "browser/study_browser.h"
#include "gui_test_support.h"
#include "review/review_panel.h"
#include "review/review_widget.h"
#include "shell/main_window.h"
#include "shell/review_export.h"
#include "window_test_support.h"

#include <QMimeData>
#include <QSignalSpy>
#include <QTabWidget>
#include <QtTest>
#include <filesystem>

using namespace lw::gui;
using lw::report::PanelLayout;

using namespace lw::test;

namespace {

// Imports a copy of the demo study into `window`'s database (in `dir`) and removes the second
// file of its series: opening that series fails at once, before the loader looks for a cancel.
// Returns the series' files, the removed one second; empty if the import found no series.
QStringList importSeriesMissingAFile(MainWindow& window, const QTemporaryDir& dir, QString& uid) {
    // A copy of the demo study, so a file can go missing without touching the original.
    const std::filesystem::path copy = dir.filePath("study").toStdString();
    std::filesystem::copy(demoStudy().toStdString(), copy);
    uid = importAndFindSeries(window, QString::fromStdString(copy.string()));
    if (uid.isEmpty())
        return {};
    const QStringList files = window.browser().database().seriesFiles(uid);
    if (files.size() < 3 || !QFile::remove(files[1]))
        return {};
    return files;
}

// What an open that is cancelled or replaced was opening.
enum class Opening { StudyThatLoads, MissingPath, SeriesMissingAFile };

} // namespace

Q_DECLARE_METATYPE(Opening)

class MainWindowTest : public QObject {
    Q_OBJECT
private slots:
    void openSeriesFromTheBrowser();
    void openPathDirectly_data();
    void openPathDirectly();
    void seriesWithMissingFilesSaysSo();
    void cancelOrReplaceOpening_data();
    void cancelOrReplaceOpening();
    void settingsApplyToOpenReviews();
    void droppingAFolderOnAReviewImportsIt();
    void exportPng_data();
    void exportPng();
    void exportIntoAMissingFolderSaysWhy();
    void exportDrawsHiddenLinesWhenAsked();
};

void MainWindowTest::openSeriesFromTheBrowser() {
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    window.resize(1200, 800);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    const QString uid = importAndFindSeries(window, demoStudy());
    QVERIFY(!uid.isEmpty());
    // Double-click on the series row is StudyBrowser::openSeriesRequested.
    QVERIFY(window.browser().selectSeries(uid));
    emit window.browser().openSeriesRequested(uid);
    QVERIFY(waitForReview(window));
    ReviewWidget* review = window.currentReview();
    QCOMPARE(review->source().seriesUid, uid);
    QVERIFY(review->source().title.contains("512x512x28"));
    QVERIFY(review->source().warnings.join(" ").contains("tilt"));
    QCOMPARE(review->iso(), 400.0); // the bone preset, nothing to click first
    QVERIFY(review->status().triangles > 10000);
    // grabImage paints the panels now, with the frame waitForReview saw arrive.
    const QImage iso = review->isoPanel().grabImage();
    QVERIFY(lw::test::pixelsDifferentFrom(iso, Qt::white) > iso.width() * iso.height() / 50);
    QVERIFY(lw::test::pixelsDifferentFrom(review->silhouettePanel().grabImage(), Qt::white, 100) >
            300);
}

void MainWindowTest::openPathDirectly_data() {
    QTest::addColumn<QString>("path");
    QTest::addColumn<bool>("opens");
    QTest::addColumn<QString>("reasonContains");
    QTest::addRow("phantom") << "phantom:48" << true << "";
    QTest::addRow("demo DICOM folder") << demoStudy() << true << "";
    QTest::addRow("missing path") << "/nonexistent/linework/study" << false
                                  << "/nonexistent/linework/study";
    QTest::addRow("bad phantom spec") << "phantom:1x2" << false << "phantom:1x2";
}

void MainWindowTest::openPathDirectly() {
    QFETCH(QString, path);
    QFETCH(bool, opens);
    QFETCH(QString, reasonContains);
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QSignalSpy failed(&window, &MainWindow::loadFailed);
    window.openPath(path);
    if (opens) {
        QVERIFY(waitForReview(window));
        QCOMPARE(window.reviews().size(), 1);
    } else {
        QVERIFY(failed.wait(30000));
        QVERIFY2(failed.front().front().toString().contains(reasonContains),
                 qPrintable(failed.front().front().toString()));
        QVERIFY(window.reviews().isEmpty());
        QVERIFY(!window.isLoading());
    }
}

void MainWindowTest::seriesWithMissingFilesSaysSo() {
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QString uid;
    const QStringList files = importSeriesMissingAFile(window, dir, uid);
    QVERIFY(!files.isEmpty());
    QSignalSpy failed(&window, &MainWindow::loadFailed);
    window.openSeries(uid);
    QVERIFY(failed.wait(30000));
    const QString reason = failed.front().front().toString();
    QVERIFY2(reason.contains("missing") && reason.contains(files[1]), qPrintable(reason));
    QVERIFY(window.reviews().isEmpty());
    // The other source files are untouched.
    QVERIFY(QFile::exists(files[0]) && QFile::exists(files[2]));
}

void MainWindowTest::cancelOrReplaceOpening_data() {
    QTest::addColumn<Opening>("opening");
    QTest::addColumn<bool>("replaced"); // false: Cancel; true: a newer open replaces it
    for (const bool replaced : {false, true}) {
        const char* how = replaced ? "replaced" : "cancelled";
        QTest::addRow("%s: a study that loads", how) << Opening::StudyThatLoads << replaced;
        QTest::addRow("%s: a missing path", how) << Opening::MissingPath << replaced;
        QTest::addRow("%s: a series missing a file", how)
            << Opening::SeriesMissingAFile << replaced;
    }
}

// An open that is cancelled, or replaced by a newer one, ends without a review or an error of
// its own, whatever its worker finishes with (a volume, a stop at its first cancel check, a
// failure that comes before any check): the test waits until that worker has ended and its
// outcome was dropped (loadDiscarded), then looks.
void MainWindowTest::cancelOrReplaceOpening() {
    QFETCH(Opening, opening);
    QFETCH(bool, replaced);
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    QString uid;
    if (opening == Opening::SeriesMissingAFile)
        QVERIFY(!importSeriesMissingAFile(window, dir, uid).isEmpty());
    QSignalSpy discarded(&window, &MainWindow::loadDiscarded);
    QSignalSpy opened(&window, &MainWindow::reviewOpened);
    QSignalSpy failed(&window, &MainWindow::loadFailed);
    if (opening == Opening::SeriesMissingAFile)
        window.openSeries(uid);
    else
        window.openPath(opening == Opening::StudyThatLoads ? demoStudy()
                                                           : "/nonexistent/linework/study");
    QVERIFY(window.isLoading());
    if (replaced) {
        window.openPath("phantom:32");
        QVERIFY(waitForReview(window));
    } else {
        window.cancelLoading();
        QVERIFY(!window.isLoading());
    }
    QVERIFY(discarded.count() == 1 || discarded.wait(60000));
    QCOMPARE(discarded.count(), 1);
    QCOMPARE(failed.count(), 0);
    QCOMPARE(opened.count(), replaced ? 1 : 0);
    QCOMPARE(window.reviews().size(), replaced ? 1 : 0);
    if (!replaced) { // and the window still works
        window.openPath("phantom:32");
        QVERIFY(waitForReview(window));
    }
    QCOMPARE(window.reviews().size(), 1);
    QVERIFY(window.currentReview()->source().title.startsWith("phantom"));
}

void MainWindowTest::settingsApplyToOpenReviews() {
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, "phantom:48"));
    ReviewSettings settings = window.settings();
    settings.method = lw::render::SilhouetteMethod::RayCastVisibility;
    settings.background = QColor(20, 20, 40);
    const std::uint64_t frames = window.currentReview()->status().framesShown;
    window.applySettings(settings);
    QCOMPARE(window.currentReview()->settings().method,
             lw::render::SilhouetteMethod::RayCastVisibility);
    QVERIFY(QTest::qWaitFor(
        [&] {
            return window.currentReview()->status().framesShown > frames &&
                   !window.currentReview()->isBusy();
        },
        30000));
    QVERIFY(window.currentReview()->statusText().startsWith("Method 2"));
    const QImage silhouette = window.currentReview()->silhouettePanel().grabImage();
    QCOMPARE(silhouette.pixelColor(2, 2).rgb(), QColor(20, 20, 40).rgb());
}

void MainWindowTest::droppingAFolderOnAReviewImportsIt() {
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, "phantom:32"));
    QSignalSpy finished(&window.browser(), &StudyBrowser::importFinished);
    QMimeData data;
    data.setUrls({QUrl::fromLocalFile(demoStudy())});
    // As a drag does it: the window accepts the enter, then gets the drop.
    QDragEnterEvent enter(QPoint(50, 50), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(&window, &enter);
    QVERIFY(enter.isAccepted());
    QDropEvent drop(QPointF(50, 50), Qt::CopyAction, &data, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(&window, &drop);
    QVERIFY(finished.wait(60000));
    QCOMPARE(window.browser().database().seriesCount(), 1);
    QCOMPARE(window.findChild<QTabWidget*>("mainTabs")->currentIndex(), 0);
}

// The ink of a picture on white: the sum over its pixels of their darkness (0 white, 1 black),
// which an antialiased stroke spreads over its edge pixels without changing.
double inkOn(const QImage& image) {
    double ink = 0.0;
    for (int y = 0; y < image.height(); ++y)
        for (int x = 0; x < image.width(); ++x)
            ink += (255.0 - qGray(image.pixel(x, y))) / 255.0;
    return ink;
}

void MainWindowTest::exportPng_data() {
    QTest::addColumn<int>("layout");
    QTest::addColumn<int>("widthFactor"); // of the picture, in panels
    QTest::addRow("side by side") << int(PanelLayout::SideBySide) << 2;
    QTest::addRow("iso panel") << int(PanelLayout::IsoPanel) << 1;
    QTest::addRow("silhouette panel") << int(PanelLayout::SilhouettePanel) << 1;
}

void MainWindowTest::exportPng() {
    QFETCH(int, layout);
    QFETCH(int, widthFactor);
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, "phantom:48"));
    ReviewWidget& review = *window.currentReview();
    const QSize screen = review.silhouettePanel().renderSize();
    const QString path = dir.filePath("review.png");
    QCOMPARE(exportReviewPng(review, path, {screen * 2, PanelLayout(layout)}), QString());
    const QImage written(path);
    if (qEnvironmentVariableIsSet("LINEWORK_KEEP_EXPORT"))
        written.save(qEnvironmentVariable("LINEWORK_KEEP_EXPORT"));
    QCOMPARE(written.size(), QSize(widthFactor * 2 * screen.width(), 2 * screen.height()));
    QVERIFY(lw::test::pixelsDifferentFrom(written, Qt::white) > 500);
    if (PanelLayout(layout) == PanelLayout::SilhouettePanel) {
        // Re-rendered, not scaled, and the lines widen with the picture: twice the size gives
        // three to four times the ink of the antialiased strokes (twice as long, twice as wide;
        // 3.4 on this phantom by method 3, 3.0 by method 1), where strokes as thin as the small
        // picture's would give two.
        const QString small = dir.filePath("small.png");
        QCOMPARE(exportReviewPng(review, small, {screen, PanelLayout(layout)}), QString());
        const double thin = inkOn(QImage(small));
        const double wide = inkOn(written);
        QVERIFY2(wide > 2.6 * thin, qPrintable(QString("%1 vs %2").arg(wide).arg(thin)));
    }
}

void MainWindowTest::exportIntoAMissingFolderSaysWhy() {
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, "phantom:32"));
    const QString path = dir.filePath("no/such/folder/review.png");
    const QString error =
        exportReviewPng(*window.currentReview(), path, {QSize(200, 150), PanelLayout::SideBySide});
    QVERIFY2(error.contains(path), qPrintable(error));
    QVERIFY(!QFileInfo::exists(path));
}

// Settings -> "Hidden lines": the exported silhouette gains the phantom's hidden
// contours as grey dashes (mid-grey pixels that are not the visible lines' antialiased edges),
// and its visible lines stay what they were.
void MainWindowTest::exportDrawsHiddenLinesWhenAsked() {
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, "phantom:48"));
    ReviewWidget& review = *window.currentReview();
    const ExportPicture picture{review.silhouettePanel().renderSize() * 2,
                                PanelLayout::SilhouettePanel};
    const QString plainPath = dir.filePath("plain.png"), hiddenPath = dir.filePath("hidden.png");
    QCOMPARE(exportReviewPng(review, plainPath, picture), QString());
    ReviewSettings settings = window.settings();
    settings.hiddenLines = true;
    window.applySettings(settings);
    QVERIFY(review.settings().hiddenLines);
    QCOMPARE(exportReviewPng(review, hiddenPath, picture), QString());
    const QImage plain(plainPath), hidden(hiddenPath);
    QCOMPARE(plain.size(), hidden.size());
    int dashPixels = 0, darkPlain = 0, darkHidden = 0;
    for (int y = 0; y < plain.height(); ++y)
        for (int x = 0; x < plain.width(); ++x) {
            const int before = qGray(plain.pixel(x, y)), after = qGray(hidden.pixel(x, y));
            darkPlain += before < 100 ? 1 : 0;
            darkHidden += after < 100 ? 1 : 0;
            dashPixels += before > 250 && after < 235 ? 1 : 0; // grey where the plain is white
        }
    QVERIFY2(dashPixels > 100, qPrintable(QString::number(dashPixels)));
    // (Where a dash crosses a visible line their antialiased edges darken a few more pixels.)
    QVERIFY2(std::abs(darkHidden - darkPlain) <= darkPlain / 20,
             qPrintable(QString("%1 vs %2").arg(darkHidden).arg(darkPlain)));
}

LW_GUI_TEST_MAIN(MainWindowTest)
#include "main_window_test.moc"
