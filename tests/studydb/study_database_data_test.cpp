// The importer on real exports from ../shared/data (SOURCES.md): a GE head CT with an 18.5°
// gantry tilt and uneven gaps, a Philips DICOMDIR export with 338 of 433 referenced files held
// back, and a small series with a missing slice. Exits with the SKIP code without the data.

#include "lw/studydb/study_database.h"
#include "lw/studydb/study_importer.h"
#include "studydb_test_support.h"

#include <QCoreApplication>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>

using namespace lw;
using namespace lw::studydb;

namespace {
QString g_data;
}

class StudyDatabaseDataTest : public QObject {
    Q_OBJECT

private:
    QTemporaryDir m_dir;
    QString dbPath() const { return m_dir.filePath(QStringLiteral("studies.sqlite")); }

    QList<SeriesRecord> allSeries() const {
        StudyDatabase db(dbPath());
        QList<SeriesRecord> result;
        for (const PatientRecord& patient : db.patients())
            for (const StudyRecord& study : patient.studies)
                result.append(study.series);
        return result;
    }

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QVERIFY(m_dir.isValid());
    }
    void cleanup() {
        for (const char* suffix : {"", "-wal", "-shm"})
            QFile::remove(dbPath() + QLatin1String(suffix));
    }

    void warningsAreStored_data() {
        QTest::addColumn<QString>("input");
        QTest::addColumn<int>("slices");
        QTest::addColumn<bool>("tilted");
        QTest::addColumn<QString>("warning"); // must occur in the warnings
        QTest::newRow("GE tilt + uneven gaps")
            << QStringLiteral("dicom/ct_head_ge_hispeed_tilt_varspacing") << 28 << true
            << QStringLiteral("uneven slice gaps");
        QTest::newRow("dicom2nifti missing slice")
            << QStringLiteral("dicom-odd/series_defects_dicom2nifti/sliceincrement") << -1 << false
            << QStringLiteral("missing");
    }

    void warningsAreStored() {
        QFETCH(QString, input);
        QFETCH(int, slices);
        QFETCH(bool, tilted);
        QFETCH(QString, warning);
        const QString path = g_data + QLatin1Char('/') + input;
        if (!QFileInfo::exists(path))
            QSKIP(qPrintable(path + QStringLiteral(" is not in the shared data")));
        const ImportSummary summary = importStudies(dbPath(), path);
        QCOMPARE(summary.seriesAdded, 1);
        const QList<SeriesRecord> series = allSeries();
        QCOMPARE(series.size(), 1);
        const SeriesRecord& record = series[0];
        if (slices > 0)
            QCOMPARE(record.sliceCount, slices);
        const QString warnings = record.warnings().join(QLatin1Char('\n'));
        QVERIFY2(warnings.contains(warning), qPrintable(warnings));
        if (tilted) {
            QVERIFY2(qAbs(record.tiltDegrees - 18.5) < 0.5,
                     qPrintable(QString::number(record.tiltDegrees)));
            QVERIFY2(warnings.contains(QStringLiteral("tilt")), qPrintable(warnings));
        }
        // Each fact once: the importer's own wording beside the assembler's listed the tilt and
        // the gaps twice in the browser.
        for (const QString& fact :
             {QStringLiteral("tilt"), QStringLiteral("slice gaps"), QStringLiteral("missing")})
            QVERIFY2(record.warnings().filter(fact).size() <= 1, qPrintable(warnings));
        QVERIFY(!record.thumbnail().isNull());
        QCOMPARE(record.fileCount, StudyDatabase(dbPath()).seriesFiles(record.uid).size());
    }

    void dicomdirExport() {
        const QString dicomdir =
            g_data + QStringLiteral("/dicom/ct_headphantom_philips_dicomdir_export/DICOMDIR");
        const ImportSummary first = importStudies(dbPath(), dicomdir);
        QVERIFY(!first.cancelled);
        QVERIFY2(first.seriesAdded >= 4, qPrintable(QString::number(first.seriesAdded)));
        StudyDatabase db(dbPath());
        QCOMPARE(db.studyCount(), 2);
        const int count = db.seriesCount();

        // The 54-slice STEREOTAXIS series, tilted -18.5°.
        const QList<SeriesRecord> series = allSeries();
        const auto stereo = std::find_if(series.begin(), series.end(),
                                         [](const SeriesRecord& s) { return s.sliceCount == 54; });
        QVERIFY(stereo != series.end());
        QVERIFY2(stereo->warnings().join(QLatin1Char(' ')).contains(QStringLiteral("tilt")),
                 qPrintable(stereo->warnings().join(QLatin1Char('\n'))));
        QVERIFY(!stereo->thumbnail().isNull());

        // The held-back files are reported: on their series or in the import log.
        int missingReported = 0;
        for (const SeriesRecord& s : series)
            for (const QString& text : s.warnings())
                missingReported += text.contains(QStringLiteral("missing")) ? 1 : 0;
        for (const ImportProblem& problem : db.importLog())
            missingReported += problem.reason.contains(QStringLiteral("missing")) ? 1 : 0;
        QVERIFY(missingReported > 0);

        const ImportSummary again = importStudies(dbPath(), dicomdir);
        QCOMPARE(again.seriesAdded, 0);
        QCOMPARE(again.seriesUpdated, first.seriesAdded);
        QCOMPARE(db.seriesCount(), count);
    }
};

int main(int argc, char** argv) {
    QCoreApplication app(argc, argv);
    const std::optional<QString> data = test::sharedDataDir();
    if (!data) {
        qWarning("SKIP: ../shared/data (LINEWORK_SHARED_DATA) not found");
        return LINEWORK_SKIP_CODE;
    }
    g_data = *data;
    StudyDatabaseDataTest test;
    return QTest::qExec(&test, argc, argv);
}
#include "study_database_data_test.moc"
