// Issue 10, "nothing lost": a real process (lw_studydb_kill_driver: an import into the study
// database, then a PNG and a PDF export) is killed with SIGKILL at random points (fixed seed):
// a quarter anywhere in the run, the others within the three short windows where a kill could
// do harm (the import's database transaction, the PNG's and the PDF's atomic write), timed from
// the driver's announcement that the window begins. After every kill
//  - the database (when the process got as far as creating it) opens, passes
//    PRAGMA integrity_check and foreign_key_check, and shows the import whole or not at all: the
//    schema complete or absent, every series or none, each with all its files, no patient
//    without a study and no study without a series (one transaction per import);
//  - the application's own StudyDatabase opens it;
//  - every file under a final export name is complete (the PNG byte for byte as in an
//    uninterrupted run, the PDF from %PDF- to %%EOF). What else may be there are the atomic
//    writes' hidden temporaries (.review.png.tmpNNN): they are left behind; the next write of the
//    same file removes them once they are stale (core_tests, AtomicWriteRemovesStale...).
// Input: the bundled demo CT (resources/demo), so it runs everywhere.
#include "lw/studydb/study_database.h"

#include <QDir>
#include <QElapsedTimer>
#include <QFile>
#include <QProcess>
#include <QRegularExpression>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QTemporaryDir>
#include <QtTest>
#include <random>

namespace {

constexpr int kRuns = 32;
constexpr unsigned kSeed = 20261123;

// Where a run is killed: `delayMs` after the driver announces `after` ("" : after the start).
struct KillPlan {
    QString after;
    qint64 delayMs = -1; // never
};

// The windows the kills aim at, each from its announcement to the next phase's.
const QStringList kWindows = {"write database", "write png", "write pdf"};

struct Reference {
    qint64 milliseconds = 0;
    QMap<QString, qint64> windowMilliseconds; // kWindows' lengths in an uninterrupted run
    int seriesCount = 0;
    QByteArray png;
};

struct Outcome {
    int leftoverTemporaries = 0;
};

QString demoInput() {
    return QStringLiteral(LINEWORK_KILL_DEMO);
}

// What the driver announced: its phases and when each began (ms after the start).
struct DriverRun {
    QStringList phases;
    int exitCode = -1; // of a run not killed: a sanitizer's finding makes it non-zero
    QString errors;
    QList<qint64> startedAt;
    QString lastPhase() const { return phases.isEmpty() ? "starting" : phases.last(); }
};

// Runs the driver in `folder` (database in db/, exports in out/) and kills it with SIGKILL as
// `plan` says.
DriverRun runDriver(const QString& folder, const KillPlan& plan) {
    QDir(folder).mkpath("db");
    QDir(folder).mkpath("out");
    QProcess driver;
    QElapsedTimer clock;
    clock.start();
    driver.start(QStringLiteral(LINEWORK_KILL_DRIVER),
                 {folder + "/db/studies.sqlite", demoInput(), folder + "/out"});
    DriverRun run;
    qint64 killAt = plan.delayMs >= 0 && plan.after.isEmpty() ? plan.delayMs : -1;
    const auto collect = [&] {
        while (driver.canReadLine()) {
            run.phases.append(QString::fromLocal8Bit(driver.readLine()).trimmed());
            run.startedAt.append(clock.elapsed());
            if (plan.delayMs >= 0 && run.phases.last() == plan.after)
                killAt = run.startedAt.last() + plan.delayMs;
        }
    };
    while (driver.state() != QProcess::NotRunning) {
        const qint64 left = killAt < 0 ? 20 : killAt - clock.elapsed();
        if (left <= 0) {
            driver.kill();
            driver.waitForFinished();
            break;
        }
        driver.waitForReadyRead(int(std::min<qint64>(left, 20)));
        collect();
    }
    collect();
    run.exitCode = driver.exitStatus() == QProcess::NormalExit ? driver.exitCode() : -1;
    run.errors = QString::fromLocal8Bit(driver.readAllStandardError());
    return run;
}

// One SQL answer as text ("" when the query gives no row).
QString scalar(QSqlDatabase& db, const QString& sql) {
    QSqlQuery query(db);
    if (!query.exec(sql) || !query.next())
        return {};
    return query.value(0).toString();
}

// The checks the file header lists for the database; false with the reason in `why`.
bool databaseIsWholeOrEmpty(const QString& path, int expectedSeries, QString& why) {
    const QString connection = "kill-check-" + path;
    bool ok = false;
    {
        QSqlDatabase db = QSqlDatabase::addDatabase("QSQLITE", connection);
        db.setDatabaseName(path);
        if (!db.open()) {
            why = "does not open: " + db.lastError().text();
        } else if (const QString integrity = scalar(db, "PRAGMA integrity_check");
                   integrity != "ok") {
            why = "integrity_check: " + integrity;
        } else if (const QString dangling = scalar(db, "PRAGMA foreign_key_check");
                   !dangling.isEmpty()) {
            why = "a row refers to a missing parent in " + dangling;
        } else if (scalar(db, "PRAGMA user_version") == "0") {
            ok = scalar(db, "SELECT count(*) FROM sqlite_master") == "0";
            why = "no schema version but tables: half a schema";
        } else {
            const int series = scalar(db, "SELECT count(*) FROM series").toInt();
            const QString incomplete = scalar(
                db, "SELECT count(*) FROM series s WHERE file_count != (SELECT count(*) FROM "
                    "series_files f WHERE f.series_ref = s.id) OR file_count = 0");
            const QString orphans = scalar(
                db, "SELECT (SELECT count(*) FROM patients p WHERE NOT EXISTS (SELECT 1 FROM "
                    "studies s WHERE s.patient_ref = p.id)) + (SELECT count(*) FROM studies s "
                    "WHERE NOT EXISTS (SELECT 1 FROM series r WHERE r.study_ref = s.id))");
            ok = (series == 0 || series == expectedSeries) && incomplete == "0" && orphans == "0";
            why = QString("%1 series of %2, %3 without all their files, %4 empty parents")
                      .arg(series)
                      .arg(expectedSeries)
                      .arg(incomplete, orphans);
        }
    }
    QSqlDatabase::removeDatabase(connection);
    return ok;
}

// Every file of the export folder: complete under its final name, or a hidden temporary.
bool exportsAreWholeOrHidden(const QString& folder, const QByteArray& png, Outcome& outcome,
                             QString& why) {
    static const QRegularExpression temporary(R"(^\.(review\.png|report\.pdf)\.tmp\d+$)");
    for (const QString& name : QDir(folder).entryList(QDir::Files | QDir::Hidden)) {
        QFile file(folder + "/" + name);
        file.open(QIODevice::ReadOnly);
        const QByteArray bytes = file.readAll();
        if (temporary.match(name).hasMatch()) {
            ++outcome.leftoverTemporaries;
            continue;
        }
        const bool whole = name == "review.png" ? bytes == png
                           : name == "report.pdf"
                               ? bytes.startsWith("%PDF-") && bytes.trimmed().endsWith("%%EOF")
                               : false;
        if (!whole) {
            why = name + QString(" (%1 bytes) is not a complete export").arg(bytes.size());
            return false;
        }
    }
    return true;
}

} // namespace

class StudyDbKillTest : public QObject {
    Q_OBJECT

private slots:
    void initTestCase();
    void killedAnywhereLeavesNothingHalfDone();

private:
    Reference m_reference;
};

// An uninterrupted run: how long the whole takes, what it imports and the PNG it writes.
void StudyDbKillTest::initTestCase() {
    QVERIFY2(QFile::exists(demoInput()), qPrintable(demoInput()));
    QTemporaryDir dir;
    const DriverRun run = runDriver(dir.path(), {});
    QVERIFY2(run.exitCode == 0, qPrintable(run.errors));
    QCOMPARE(run.phases, QStringList({"import", "write database", "thumbnail", "export png",
                                      "write png", "export pdf", "write pdf", "done"}));
    m_reference.milliseconds = run.startedAt.last();
    for (const QString& window : kWindows) {
        const qsizetype at = run.phases.indexOf(window);
        m_reference.windowMilliseconds[window] = run.startedAt[at + 1] - run.startedAt[at];
    }
    const lw::studydb::StudyDatabase database(dir.path() + "/db/studies.sqlite");
    m_reference.seriesCount = database.seriesCount();
    QVERIFY(m_reference.seriesCount > 0);
    QFile png(dir.path() + "/out/review.png");
    QVERIFY(png.open(QIODevice::ReadOnly));
    m_reference.png = png.readAll();
    qInfo("uninterrupted: %lld ms (writing the database %lld ms, the PNG %lld ms, the PDF %lld "
          "ms), %d series",
          m_reference.milliseconds, m_reference.windowMilliseconds["write database"],
          m_reference.windowMilliseconds["write png"], m_reference.windowMilliseconds["write pdf"],
          m_reference.seriesCount);
}

void StudyDbKillTest::killedAnywhereLeavesNothingHalfDone() {
    std::mt19937 random(kSeed);
    for (int run = 0; run < kRuns; ++run) {
        QTemporaryDir dir;
        // Run 0, 4, 8 ... anywhere up to a little past the end; the others within a window (a
        // little past it too, where the announcement came late).
        KillPlan plan;
        plan.after = run % 4 == 0 ? QString() : kWindows[run % 4 - 1];
        const qint64 span = plan.after.isEmpty() ? m_reference.milliseconds
                                                 : m_reference.windowMilliseconds[plan.after] + 2;
        // Squared: early in the window more often, where a later (warm) run writes faster.
        const double u = std::uniform_real_distribution<double>(0.0, 1.0)(random);
        plan.delayMs = qint64(double(span) * 1.1 * u * u);
        const QString phase = runDriver(dir.path(), plan).lastPhase();
        const QString where = QString("run %1, killed %2 ms after %3, during \"%4\"")
                                  .arg(run)
                                  .arg(plan.delayMs)
                                  .arg(plan.after.isEmpty() ? "the start" : plan.after, phase);
        QString why;
        const QString databasePath = dir.path() + "/db/studies.sqlite";
        if (QFile::exists(databasePath)) {
            QVERIFY2(databaseIsWholeOrEmpty(databasePath, m_reference.seriesCount, why),
                     qPrintable(where + ": the database: " + why));
            QVERIFY(lw::studydb::StudyDatabase(databasePath).schemaVersion() > 0);
        }
        Outcome outcome;
        QVERIFY2(exportsAreWholeOrHidden(dir.path() + "/out", m_reference.png, outcome, why),
                 qPrintable(where + ": " + why));
        qInfo("%s: checked, %d temporaries left", qPrintable(where), outcome.leftoverTemporaries);
    }
}

QTEST_GUILESS_MAIN(StudyDbKillTest)
#include "kill_test.moc"
