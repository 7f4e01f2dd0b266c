// The DICOM browser as a user drives it, on real widgets (xcb under xvfb-run) with real exports
// from ../shared/data: import a folder and a DICOMDIR and find the warnings in the tree, restart
// on the same database, search, cancel half way, remove, open. The database lives in a temporary
// folder and QStandardPaths is in test mode. Exits with the SKIP code without a display or data.

#include "browser/study_browser.h"
#include "browser/study_tree_model.h"
#include "lw/core/error.h"
#include "lw/studydb/study_database.h"

#include <QAbstractButton>
#include <QApplication>
#include <QDir>
#include <QDragEnterEvent>
#include <QFile>
#include <QFileInfo>
#include <QLineEdit>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <QTimer>
#include <QTreeView>
#include <QUrl>
#include <memory>

using namespace lw;
using gui::StudyBrowser;
using gui::StudyTreeModel;

namespace {

QString g_data;

constexpr int kImportTimeoutMs = 120000;
const QString kGeTilt = QStringLiteral("dicom/ct_head_ge_hispeed_tilt_varspacing");
const QString kPhilipsDicomdir =
    QStringLiteral("dicom/ct_headphantom_philips_dicomdir_export/DICOMDIR");

QString dataPath(const QString& relative) {
    return g_data + QLatin1Char('/') + relative;
}

// Every series row of the model as (uid, warning text).
QList<QPair<QString, QString>> seriesRows(const StudyTreeModel& model,
                                          const QModelIndex& parent = {}) {
    QList<QPair<QString, QString>> rows;
    for (int row = 0; row < model.rowCount(parent); ++row) {
        const QModelIndex index = model.index(row, 0, parent);
        if (model.seriesAt(index))
            rows.append({index.data(StudyTreeModel::SeriesUidRole).toString(),
                         index.data(StudyTreeModel::WarningTextRole).toString()});
        rows += seriesRows(model, index);
    }
    return rows;
}

} // namespace

class BrowserTest : public QObject {
    Q_OBJECT

private:
    QTemporaryDir m_dir;
    std::unique_ptr<StudyBrowser> m_browser;

    QString dbPath() const { return m_dir.filePath(QStringLiteral("studies.sqlite")); }

    StudyBrowser& openBrowser() {
        m_browser = std::make_unique<StudyBrowser>(dbPath());
        m_browser->resize(1200, 700);
        m_browser->show();
        if (!QTest::qWaitForWindowExposed(m_browser.get()))
            qWarning("browser window not exposed");
        return *m_browser;
    }

    // Imports through the widget and waits for importFinished; returns its summary.
    studydb::ImportSummary importAndWait(const QString& path) {
        QSignalSpy finished(m_browser.get(), &StudyBrowser::importFinished);
        m_browser->importPath(path);
        [&] { QVERIFY(finished.wait(kImportTimeoutMs)); }();
        return finished.isEmpty() ? studydb::ImportSummary{}
                                  : finished.takeFirst().at(0).value<studydb::ImportSummary>();
    }

    QTreeView* tree() const {
        return m_browser->findChild<QTreeView*>(QStringLiteral("studyTree"));
    }

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QVERIFY(m_dir.isValid());
    }

    void cleanup() {
        m_browser.reset();
        for (const char* suffix : {"", "-wal", "-shm"})
            QFile::remove(dbPath() + QLatin1String(suffix));
    }

    void importShowsWarningsInTheTree_data() {
        QTest::addColumn<QString>("input");
        QTest::addColumn<int>("minimumSeries");
        QTest::addColumn<QStringList>("warnings"); // each must occur in some series' warning text
        QTest::newRow("folder: GE head CT, tilt and uneven gaps")
            << kGeTilt << 1
            << QStringList{QStringLiteral("gantry tilt 18.5"), QStringLiteral("uneven slice gaps")};
        QTest::newRow("DICOMDIR export: tilt, held-back files")
            << kPhilipsDicomdir << 4
            << QStringList{QStringLiteral("gantry tilt"), QStringLiteral("missing")};
    }

    void importShowsWarningsInTheTree() {
        QFETCH(QString, input);
        QFETCH(int, minimumSeries);
        QFETCH(QStringList, warnings);
        StudyBrowser& browser = openBrowser();
        QSignalSpy started(&browser, &StudyBrowser::importStarted);
        QSignalSpy finished(&browser, &StudyBrowser::importFinished);
        browser.importPath(dataPath(input));
        QCOMPARE(started.size(), 1);
        QVERIFY(browser.findChild<QProgressBar*>(QStringLiteral("importProgress"))->isVisible());
        QVERIFY(browser.findChild<QPushButton*>(QStringLiteral("cancelImportButton"))->isVisible());
        QVERIFY(finished.wait(kImportTimeoutMs));
        QVERIFY(!browser.findChild<QProgressBar*>(QStringLiteral("importProgress"))->isVisible());
        const auto summary = finished.at(0).at(0).value<studydb::ImportSummary>();
        QVERIFY(!summary.cancelled);
        QVERIFY2(summary.seriesAdded >= minimumSeries,
                 qPrintable(QString::number(summary.seriesAdded)));

        const auto rows = seriesRows(browser.model());
        QCOMPARE(int(rows.size()), browser.database().seriesCount());
        QString allWarnings;
        for (const auto& row : rows)
            allWarnings += row.second + QLatin1Char('\n');
        for (const QString& warning : warnings)
            QVERIFY2(allWarnings.contains(warning) || browser.messageText().contains(warning),
                     qPrintable(warning + QStringLiteral(" not in:\n") + allWarnings +
                                browser.messageText()));
        // The warning column counts them and its tooltip lists them; series rows have thumbnails.
        const QModelIndex first = browser.model().indexOfSeries(rows[0].first);
        const QModelIndex warningCell = first.siblingAtColumn(StudyTreeModel::WarningsColumn);
        QCOMPARE(warningCell.data(Qt::ToolTipRole).toString(), rows[0].second);
        if (input == kGeTilt) {
            QVERIFY(first.data(StudyTreeModel::WarningCountRole).toInt() >= 2);
            QVERIFY(!first.data(Qt::DecorationRole).value<QIcon>().isNull());
            QCOMPARE(first.siblingAtColumn(StudyTreeModel::SlicesColumn).data().toInt(), 28);
        }
    }

    void restartFindsTheSeriesAgain() {
        openBrowser();
        QVERIFY(importAndWait(dataPath(kGeTilt)).seriesAdded == 1);
        const QString uid = seriesRows(m_browser->model()).value(0).first;
        QVERIFY(!uid.isEmpty());
        m_browser.reset(); // "quit"
        StudyBrowser& again = openBrowser();
        QVERIFY(again.model().indexOfSeries(uid).isValid());
        QCOMPARE(again.model().seriesRowCount(), 1);
        QCOMPARE(again.database().seriesFiles(uid).size(), 28);
        // Importing the same folder again updates rather than duplicates.
        const studydb::ImportSummary summary = importAndWait(dataPath(kGeTilt));
        QCOMPARE(summary.seriesAdded, 0);
        QCOMPARE(summary.seriesUpdated, 1);
        QCOMPARE(again.model().seriesRowCount(), 1);
    }

    void searchFiltersLive_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<bool>("shown");
        QTest::newRow("empty") << QString() << true;
        QTest::newRow("no such patient") << QStringLiteral("no-such-patient") << false;
        QTest::newRow("series description, other case") << QStringLiteral("std") << true;
    }

    void searchFiltersLive() {
        QFETCH(QString, text);
        QFETCH(bool, shown);
        StudyBrowser& browser = openBrowser();
        importAndWait(dataPath(kPhilipsDicomdir));
        const int all = browser.model().seriesRowCount();
        QVERIFY(all >= 4);
        auto* search = browser.findChild<QLineEdit*>(QStringLiteral("searchEdit"));
        QVERIFY(search);
        search->setFocus();
        QTest::keyClicks(search, text);
        const int visible = browser.model().seriesRowCount();
        if (!shown)
            QCOMPARE(visible, 0);
        else if (text.isEmpty())
            QCOMPARE(visible, all);
        else
            QVERIFY2(visible > 0 && visible < all,
                     qPrintable(QStringLiteral("%1 of %2").arg(visible).arg(all)));
        search->clear();
        QCOMPARE(browser.model().seriesRowCount(), all);
    }

    void cancelHalfWayLeavesTheDatabaseConsistent() {
        StudyBrowser& browser = openBrowser();
        importAndWait(dataPath(kGeTilt));
        const int before = browser.database().seriesCount();
        QCOMPARE(before, 1);

        // The whole dicom folder takes far longer than the first progress report: cancel there,
        // with the button the user would press.
        QSignalSpy finished(&browser, &StudyBrowser::importFinished);
        auto* cancel = browser.findChild<QPushButton*>(QStringLiteral("cancelImportButton"));
        auto* progress = browser.findChild<QProgressBar*>(QStringLiteral("importProgress"));
        bool clicked = false;
        connect(progress, &QProgressBar::valueChanged, this, [&] {
            if (!clicked && cancel->isVisible()) {
                clicked = true;
                QTest::mouseClick(cancel, Qt::LeftButton);
            }
        });
        browser.importPath(dataPath(QStringLiteral("dicom")));
        QVERIFY(finished.wait(kImportTimeoutMs));
        QVERIFY(clicked);
        QVERIFY(finished.at(0).at(0).value<studydb::ImportSummary>().cancelled);
        QVERIFY2(browser.messageText().isEmpty() ||
                     !browser.messageText().contains(QStringLiteral("failed")),
                 qPrintable(browser.messageText()));

        // Nothing half-written: the same series, each with all its files.
        studydb::StudyDatabase check(dbPath());
        QCOMPARE(check.seriesCount(), before);
        QCOMPARE(browser.model().seriesRowCount(), before);
        for (const auto& row : seriesRows(browser.model()))
            QCOMPARE(check.seriesFiles(row.first).size(), check.series(row.first)->fileCount);
        QVERIFY(check.importLog().isEmpty());
    }

    void removeAsksAndKeepsTheFiles() {
        StudyBrowser& browser = openBrowser();
        importAndWait(dataPath(kGeTilt));
        const QString uid = seriesRows(browser.model()).value(0).first;
        const QStringList files = browser.database().seriesFiles(uid);
        QVERIFY(browser.selectSeries(uid));
        auto* remove = browser.findChild<QPushButton*>(QStringLiteral("removeSeriesButton"));
        QVERIFY(remove->isEnabled());

        QString question;
        QTimer::singleShot(200, this, [&] {
            auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
            if (!box)
                return;
            question = box->text();
            box->button(QMessageBox::Yes)->click();
        });
        QTest::mouseClick(remove, Qt::LeftButton);
        QVERIFY2(question.contains(QStringLiteral("files on disk are kept")), qPrintable(question));
        QCOMPARE(browser.database().seriesCount(), 0);
        QCOMPARE(browser.model().seriesRowCount(), 0);
        for (const QString& file : files)
            QVERIFY2(QFileInfo::exists(file), qPrintable(file));
    }

    void enterOpensTheSeries() {
        StudyBrowser& browser = openBrowser();
        importAndWait(dataPath(kGeTilt));
        const QString uid = seriesRows(browser.model()).value(0).first;
        QVERIFY(browser.selectSeries(uid));
        QSignalSpy open(&browser, &StudyBrowser::openSeriesRequested);
        tree()->setFocus();
        QTest::keyClick(tree(), Qt::Key_Return);
        QCOMPARE(open.size(), 1);
        QCOMPARE(open.at(0).at(0).toString(), uid);
    }

    void dropAFolderImportsIt() {
        StudyBrowser& browser = openBrowser();
        QSignalSpy finished(&browser, &StudyBrowser::importFinished);
        QMimeData mime;
        mime.setUrls({QUrl::fromLocalFile(dataPath(kGeTilt))});
        QDragEnterEvent enter(QPoint(50, 50), Qt::CopyAction, &mime, Qt::LeftButton,
                              Qt::NoModifier);
        QApplication::sendEvent(&browser, &enter);
        QVERIFY(enter.isAccepted());
        QDropEvent drop(QPointF(50, 50), Qt::CopyAction, &mime, Qt::LeftButton, Qt::NoModifier);
        QApplication::sendEvent(&browser, &drop);
        QVERIFY(finished.wait(kImportTimeoutMs));
        QCOMPARE(browser.model().seriesRowCount(), 1);
    }

    void unusableDatabaseIsShownNotFatal() {
        QFile file(dbPath());
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write(QByteArray(4096, 'x'));
        file.close();
        StudyBrowser& browser = openBrowser();
        QVERIFY(!browser.hasDatabase());
        QVERIFY2(browser.messageText().contains(dbPath()), qPrintable(browser.messageText()));
        QVERIFY_THROWS_EXCEPTION(core::Error, browser.database());
        browser.importPath(dataPath(kGeTilt)); // refused with a message, no crash
        QVERIFY(!browser.isImporting());
    }
};

int main(int argc, char** argv) {
    if (qEnvironmentVariableIsEmpty("DISPLAY")) {
        fprintf(stderr, "SKIP: no DISPLAY (run under xvfb-run)\n");
        return LINEWORK_SKIP_CODE;
    }
    QString data = qEnvironmentVariable("LINEWORK_SHARED_DATA");
    if (data.isEmpty())
        data = QStringLiteral(LINEWORK_DEFAULT_SHARED_DATA);
    if (!QFileInfo(data + QStringLiteral("/dicom")).isDir()) {
        fprintf(stderr, "SKIP: ../shared/data (LINEWORK_SHARED_DATA) not found\n");
        return LINEWORK_SKIP_CODE;
    }
    g_data = QFileInfo(data).absoluteFilePath();
    qputenv("QT_QPA_PLATFORM", "xcb");
    QApplication app(argc, argv);
    BrowserTest test;
    return QTest::qExec(&test, argc, argv);
}
#include "browser_test.moc"
