// Study database and importer on synthetic series: schema and versions (a version 1 file
// migrated; a version 2 file's annotation documents migrated; a newer file refused), upsert on
// re-import, filter, remove, cancel (before and during the write), warnings and file errors,
// annotations per series.

#include "lw/annotation/annotation_json.h"
#include "lw/core/error.h"
#include "lw/studydb/study_database.h"
#include "lw/studydb/study_importer.h"
#include "lw/volume/volume.h"
#include "studydb_test_support.h"

#include <QDir>
#include <QFile>
#include <QSignalSpy>
#include <QStandardPaths>
#include <QTemporaryDir>
#include <QTest>
#include <algorithm>
#include <mutex>

using namespace lw;
using namespace lw::studydb;

class StudyDatabaseTest : public QObject {
    Q_OBJECT

private:
    QTemporaryDir m_dir;
    QString dbPath() const { return m_dir.filePath(QStringLiteral("studies.sqlite")); }
    QString folder(const QString& name) const { return m_dir.filePath(name); }

    static SeriesImport record(const QString& uid, const QString& patient,
                               const QString& studyDescription, const QString& seriesDescription,
                               const QString& date) {
        SeriesImport item;
        item.patient.patientId = patient + QStringLiteral("-ID");
        item.patient.name = patient;
        item.study.uid = QStringLiteral("study-") + uid;
        item.study.description = studyDescription;
        item.study.date = date;
        item.series.uid = uid;
        item.series.studyUid = item.study.uid;
        item.series.description = seriesDescription;
        item.series.modality = QStringLiteral("CT");
        item.files = {QStringLiteral("/nowhere/%1.dcm").arg(uid)};
        item.sopInstanceUids = {uid + QStringLiteral(".1")};
        return item;
    }

    // The same annotations, all placed in 3D.
    static void compareIn3D(const std::vector<annotation::Annotation>& read,
                            const std::vector<annotation::Annotation>& expected) {
        QCOMPARE(read.size(), expected.size());
        for (std::size_t i = 0; i < read.size(); ++i) {
            QVERIFY(read[i].kind == expected[i].kind);
            QVERIFY(read[i].anchors == expected[i].anchors);
            QCOMPARE(QString::fromStdString(read[i].text),
                     QString::fromStdString(expected[i].text));
            QVERIFY(!read[i].slice);
            QCOMPARE(QString::fromStdString(annotation::measurementText(read[i])),
                     QString::fromStdString(annotation::measurementText(expected[i])));
        }
    }

private slots:
    void initTestCase() {
        QStandardPaths::setTestModeEnabled(true);
        QVERIFY(m_dir.isValid());
    }
    void cleanup() {
        QFile::remove(dbPath());
        QFile::remove(dbPath() + QStringLiteral("-wal"));
        QFile::remove(dbPath() + QStringLiteral("-shm"));
    }

    void schemaIsCreatedAndVersioned() {
        {
            StudyDatabase db(dbPath());
            QCOMPARE(db.schemaVersion(), StudyDatabase::kSchemaVersion);
            QCOMPARE(db.seriesCount(), 0);
        }
        QVERIFY(QFile::exists(dbPath()));
        const QStringList rows = test::snapshot(dbPath());
        QVERIFY(rows.isEmpty());
        // Reopening an up-to-date file keeps it as it is.
        StudyDatabase again(dbPath());
        QCOMPARE(again.schemaVersion(), StudyDatabase::kSchemaVersion);
    }

    void defaultPathIsInTheAppDataFolder() {
        const QString path = StudyDatabase::defaultPath();
        QVERIFY(path.endsWith(QStringLiteral("/studies.sqlite")));
        QVERIFY(QFileInfo(path).absoluteDir().exists());
    }

    void newerSchemaIsRefused_data() {
        QTest::addColumn<int>("version");
        QTest::newRow("the next version") << StudyDatabase::kSchemaVersion + 1;
        QTest::newRow("far in the future") << 99;
    }

    // A database from a newer Linework is refused and left exactly as it was.
    void newerSchemaIsRefused() {
        QFETCH(int, version);
        {
            StudyDatabase db(dbPath());
            db.setSeriesAnnotations(QStringLiteral("1.2.3"), QStringLiteral("{\"version\": 9}"));
        }
        test::execRaw(dbPath(), QStringLiteral("PRAGMA user_version = %1").arg(version));
        const QStringList before = test::snapshot(dbPath());
        try {
            StudyDatabase db(dbPath());
            QFAIL("a newer schema was accepted");
        } catch (const core::Error& error) {
            QCOMPARE(QString::fromStdString(error.subject()), dbPath());
            QVERIFY2(QString::fromStdString(error.reason())
                         .contains(QStringLiteral("schema version %1, newer than this Linework "
                                                  "understands (%2)")
                                       .arg(version)
                                       .arg(StudyDatabase::kSchemaVersion)),
                     error.what());
        }
        QCOMPARE(test::snapshot(dbPath()), before);
        QCOMPARE(test::userVersion(dbPath()), version);
    }

    void notADatabaseIsRefused() {
        QFile file(dbPath());
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write(QByteArray(4096, 'x'));
        file.close();
        QVERIFY_THROWS_EXCEPTION(core::Error, StudyDatabase db(dbPath()));
    }

    void reimportUpdatesInsteadOfDuplicating() {
        const QString root = folder(QStringLiteral("reimport"));
        const QString a = test::writeSeries(root + QStringLiteral("/a"), {});
        test::SyntheticSeries second;
        second.description = QStringLiteral("second");
        const QString b = test::writeSeries(root + QStringLiteral("/b"), second);

        const ImportSummary first = importStudies(dbPath(), root);
        QCOMPARE(first.seriesAdded, 2);
        QCOMPARE(first.seriesUpdated, 0);
        QVERIFY(!first.cancelled);
        QCOMPARE(first.filesExamined, std::size_t(8));

        const ImportSummary again = importStudies(dbPath(), root);
        QCOMPARE(again.seriesAdded, 0);
        QCOMPARE(again.seriesUpdated, 2);

        StudyDatabase db(dbPath());
        QCOMPARE(db.seriesCount(), 2);
        QCOMPARE(db.studyCount(), 2);
        QCOMPARE(db.patientCount(), 1);
        QCOMPARE(db.seriesFiles(a).size(), 4);
        QCOMPARE(db.seriesFiles(b).size(), 4);
        for (const QString& file : db.seriesFiles(a))
            QVERIFY2(file.startsWith(root), qPrintable(file)); // referenced in place
        const std::optional<SeriesRecord> record = db.series(a);
        QVERIFY(record);
        QCOMPARE(record->sliceCount, 4);
        QCOMPARE(record->dims, (std::array<int, 3>{16, 16, 4}));
        QCOMPARE(record->spacing[2], 1.0);
        QCOMPARE(record->volumeCount, 1);
        QVERIFY(record->warnings().isEmpty());
        const QImage thumbnail = record->thumbnail();
        QVERIFY(!thumbnail.isNull());
        QCOMPARE(thumbnail.size(), QSize(kThumbnailSize, kThumbnailSize));
    }

    void filter_data() {
        QTest::addColumn<QString>("text");
        QTest::addColumn<QDate>("from");
        QTest::addColumn<QDate>("to");
        QTest::addColumn<QStringList>("expected");
        const QStringList all{QStringLiteral("s1"), QStringLiteral("s2"), QStringLiteral("s3")};
        QTest::newRow("everything") << QString() << QDate() << QDate() << all;
        QTest::newRow("patient name, any case")
            << QStringLiteral("müller") << QDate() << QDate()
            << QStringList{QStringLiteral("s1"), QStringLiteral("s2")};
        QTest::newRow("patient id")
            << QStringLiteral("john-id") << QDate() << QDate() << QStringList{QStringLiteral("s3")};
        QTest::newRow("study description")
            << QStringLiteral("THORAX") << QDate() << QDate() << QStringList{QStringLiteral("s3")};
        QTest::newRow("series description")
            << QStringLiteral("bone") << QDate() << QDate() << QStringList{QStringLiteral("s2")};
        QTest::newRow("two words, both must match")
            << QStringLiteral("Müller head") << QDate() << QDate()
            << QStringList{QStringLiteral("s1"), QStringLiteral("s2")};
        QTest::newRow("no match") << QStringLiteral("nobody") << QDate() << QDate()
                                  << QStringList{};
        QTest::newRow("from") << QString() << QDate(2020, 1, 1) << QDate()
                              << QStringList{QStringLiteral("s3")};
        QTest::newRow("to") << QString() << QDate() << QDate(2019, 12, 31)
                            << QStringList{QStringLiteral("s1"), QStringLiteral("s2")};
        QTest::newRow("day inclusive") << QString() << QDate(2021, 5, 6) << QDate(2021, 5, 6)
                                       << QStringList{QStringLiteral("s3")};
        QTest::newRow("text and date")
            << QStringLiteral("müller") << QDate(2020, 1, 1) << QDate() << QStringList{};
    }

    void filter() {
        QFETCH(QString, text);
        QFETCH(QDate, from);
        QFETCH(QDate, to);
        QFETCH(QStringList, expected);
        StudyDatabase db(dbPath());
        ImportBatch batch;
        batch.series = {
            record(QStringLiteral("s1"), QStringLiteral("Müller^Anna"), QStringLiteral("Head"),
                   QStringLiteral("soft"), QStringLiteral("20190304")),
            record(QStringLiteral("s2"), QStringLiteral("Müller^Anna"), QStringLiteral("Head"),
                   QStringLiteral("Bone 1mm"), QStringLiteral("20190304")),
            record(QStringLiteral("s3"), QStringLiteral("Doe^John"), QStringLiteral("Thorax"),
                   QStringLiteral("lung"), QStringLiteral("20210506"))};
        batch.series[1].study.uid = batch.series[0].study.uid; // s1 and s2: one study
        batch.series[1].series.studyUid = batch.series[0].study.uid;
        const WriteResult written = db.write(batch);
        QCOMPARE(written.seriesAdded, 3);

        QStringList found;
        for (const PatientRecord& patient : db.patients({text, from, to}))
            for (const StudyRecord& study : patient.studies)
                for (const SeriesRecord& series : study.series)
                    found.append(series.uid);
        found.sort();
        QCOMPARE(found, expected);
        QCOMPARE(db.studyCount(), 2);
        QCOMPARE(db.patientCount(), 2);
    }

    void removeSeriesKeepsTheFiles() {
        const QString root = folder(QStringLiteral("remove"));
        test::SyntheticSeries other;
        other.patientId = QStringLiteral("OTHER");
        other.patientName = QStringLiteral("Other^Patient");
        const QString a = test::writeSeries(root + QStringLiteral("/a"), {});
        const QString b = test::writeSeries(root + QStringLiteral("/b"), other);
        importStudies(dbPath(), root);

        StudyDatabase db(dbPath());
        const QStringList files = db.seriesFiles(b);
        QCOMPARE(files.size(), 4);
        QVERIFY(db.removeSeries(b));
        QVERIFY(!db.removeSeries(b));
        QCOMPARE(db.seriesCount(), 1);
        QVERIFY(!db.series(b));
        QVERIFY(db.series(a));
        QVERIFY(db.seriesFiles(b).isEmpty());
        // The now empty study and patient went with it; the files on disk did not.
        QCOMPARE(db.studyCount(), 1);
        QCOMPARE(db.patientCount(), 1);
        for (const QString& file : files)
            QVERIFY2(QFile::exists(file), qPrintable(file));
        for (const QString& row : test::snapshot(dbPath()))
            QVERIFY2(!row.contains(b), qPrintable(row));
    }

    void annotationsAreKeptPerSeries() {
        const QString json =
            QStringLiteral("{\"version\": 1, \"annotations\": [{\"type\": \"ruler\", "
                           "\"points\": [[0, 0, 0], [0, 10.5, 0]]}]}");
        {
            StudyDatabase db(dbPath());
            db.write({QString(),
                      {record(QStringLiteral("1.2.3"), QStringLiteral("P"), QStringLiteral("s"),
                              QStringLiteral("x"), QStringLiteral("20240101"))},
                      {}});
            QVERIFY(!db.seriesAnnotations(QStringLiteral("1.2.3")));
            db.setSeriesAnnotations(QStringLiteral("1.2.3"), QStringLiteral("first"));
            db.setSeriesAnnotations(QStringLiteral("1.2.3"), json); // replaced, not added
            // A series opened without importing it has no row, and keeps its annotations too.
            db.setSeriesAnnotations(QStringLiteral("9.9.9"), QStringLiteral("{}"));
        }
        StudyDatabase fresh(dbPath()); // a new connection reads what was committed
        QCOMPARE(fresh.seriesAnnotations(QStringLiteral("1.2.3")), std::optional<QString>(json));
        QCOMPARE(fresh.seriesAnnotations(QStringLiteral("9.9.9")),
                 std::optional<QString>(QStringLiteral("{}")));
        // Forgetting the series in the index keeps the radiologist's work for a re-import.
        QVERIFY(fresh.removeSeries(QStringLiteral("1.2.3")));
        QCOMPARE(fresh.seriesAnnotations(QStringLiteral("1.2.3")), std::optional<QString>(json));
    }

    void migrationFromVersion1KeepsTheData() {
        test::loadSqlScript(dbPath(),
                            QStringLiteral(LINEWORK_STUDYDB_TEST_DATA "/studies_schema_v1.sql"));
        const QStringList before = test::snapshot(dbPath());
        QCOMPARE(before.size(), 12); // 1 patient, 1 study, 2 series, 6 files, 1 message, 1 log
        const QString bone = QStringLiteral("1.2.826.0.1.3680043.10.1001.1");
        {
            StudyDatabase db(dbPath());
            QCOMPARE(db.schemaVersion(), StudyDatabase::kSchemaVersion);
            QCOMPARE(test::snapshot(dbPath()), before); // every row as it was
            const std::optional<SeriesRecord> series = db.series(bone);
            QVERIFY(series);
            QCOMPARE(series->description, QStringLiteral("bone"));
            QCOMPARE(series->tiltDegrees, 12.0);
            QCOMPARE(series->warnings(), QStringList{QStringLiteral("gantry tilt 12 degrees")});
            QCOMPARE(db.seriesFiles(bone).size(), 3);
            QCOMPARE(db.importLog().size(), 1);
            QVERIFY(!db.seriesAnnotations(bone));
            db.setSeriesAnnotations(bone, QStringLiteral("{}")); // the new table works
        }
        StudyDatabase again(dbPath()); // already migrated: opened as it is
        QCOMPARE(again.schemaVersion(), StudyDatabase::kSchemaVersion);
        QCOMPARE(again.seriesAnnotations(bone), std::optional<QString>(QStringLiteral("{}")));
        QCOMPARE(again.seriesCount(), 2);
    }

    // A schema 2 file (annotation documents of file version 1) opened by schema 3: every row of
    // the index as it was, each document rewritten as file version 2 holding the same
    // annotations, placed in 3D; the user's save times kept.
    void migrationFromVersion2KeepsTheAnnotations() {
        test::loadSqlScript(dbPath(),
                            QStringLiteral(LINEWORK_STUDYDB_TEST_DATA "/studies_schema_v2.sql"));
        // A document an older Linework could store but nothing reads: kept as it is.
        test::execRaw(dbPath(), QStringLiteral("INSERT INTO series_annotations VALUES"
                                               "('9.9.9', 'not JSON', '2026-11-24T10:00:00Z')"));
        const QStringList before = test::snapshot(dbPath());
        QCOMPARE(before.size(), 15); // the 12 rows of version 1 and 3 annotation documents
        const QString bone = QStringLiteral("1.2.826.0.1.3680043.10.1001.1");
        const QString soft = QStringLiteral("1.2.826.0.1.3680043.10.1001.2");
        {
            StudyDatabase db(dbPath());
            QCOMPARE(db.schemaVersion(), StudyDatabase::kSchemaVersion);
        }
        QCOMPARE(test::userVersion(dbPath()), 3);
        const QStringList after = test::snapshot(dbPath());
        QCOMPARE(after.size(), before.size());
        for (int i = 0; i < before.size(); ++i) {
            if (before[i].startsWith(QStringLiteral("series_annotations|")))
                continue;
            QCOMPARE(after[i], before[i]); // the index untouched
        }
        StudyDatabase db(dbPath());
        QCOMPARE(db.seriesAnnotations(QStringLiteral("9.9.9")),
                 std::optional<QString>(QStringLiteral("not JSON")));
        struct Expected {
            QString uid;
            std::vector<annotation::Annotation> annotations;
        };
        const std::vector<Expected> expected = {
            {bone,
             {{annotation::AnnotationKind::Ruler, {{-35.6, -82.1, 54.1}, {75.2, 17.1, 48.9}}, {}},
              {annotation::AnnotationKind::Label, {{-11.4, -42.8, 2.1}}, "Orbit"},
              {annotation::AnnotationKind::Angle,
               {{-58.4, -44.7, 2.7}, {51.1, -60.1, -4.7}, {75.2, 17.1, 48.9}},
               {}}}},
            {soft,
             {{annotation::AnnotationKind::Arrow,
               {{60.0, -80.0, 150.0}, {7.3, -36.3, 109.3}},
               "Slice step"}}},
        };
        for (const Expected& series : expected) {
            const std::optional<QString> json = db.seriesAnnotations(series.uid);
            QVERIFY(json);
            QVERIFY2(json->contains(QStringLiteral("\"version\": 2")), qPrintable(*json));
            compareIn3D(annotation::parseAnnotationsJson(json->toStdString(), "migrated"),
                        series.annotations);
            if (QTest::currentTestFailed())
                return;
        }
        const QString boneRow = QStringLiteral("series_annotations|") + bone + QLatin1Char('|');
        const auto row = std::find_if(after.begin(), after.end(),
                                      [&](const QString& r) { return r.startsWith(boneRow); });
        QVERIFY(row != after.end());
        QCOMPARE(row->section(QLatin1Char('|'), -1),
                 QStringLiteral("2026-11-24T09:12:40Z")); // the user's save time, kept
    }

    // A migration that fails half-way (here: the second document's rewrite refused by a trigger)
    // leaves the file as the older Linework wrote it, version and rows.
    void failedMigrationLeavesTheFileAsItWas() {
        test::loadSqlScript(dbPath(),
                            QStringLiteral(LINEWORK_STUDYDB_TEST_DATA "/studies_schema_v2.sql"));
        test::execRaw(dbPath(), QStringLiteral("CREATE TRIGGER refuse_second BEFORE UPDATE ON "
                                               "series_annotations WHEN old.series_uid LIKE '%.2' "
                                               "BEGIN SELECT RAISE(ABORT, 'disk full'); END"));
        const QStringList before = test::snapshot(dbPath());
        try {
            StudyDatabase db(dbPath());
            QFAIL("the migration did not fail");
        } catch (const core::Error& error) {
            QVERIFY2(QString::fromStdString(error.reason()).contains(QStringLiteral("disk full")),
                     error.what());
        }
        QCOMPARE(test::userVersion(dbPath()), 2);
        QCOMPARE(test::snapshot(dbPath()), before); // the first document not rewritten either
        test::execRaw(dbPath(), QStringLiteral("DROP TRIGGER refuse_second"));
        StudyDatabase db(dbPath()); // and it migrates once it can
        QCOMPARE(db.schemaVersion(), StudyDatabase::kSchemaVersion);
    }

    // What the review saves for a ruler on a slice comes back as a ruler on that slice.
    void sliceAnnotationsAreStored() {
        annotation::Annotation onSlice{
            annotation::AnnotationKind::Ruler, {{0, 0, 118.5}, {42.3, 0, 118.5}}, {}};
        onSlice.slice = annotation::SlicePlacement{annotation::SliceOrientation::Axial, 118.5, 5.0};
        const QString uid = QStringLiteral("1.2.3");
        {
            StudyDatabase db(dbPath());
            db.setSeriesAnnotations(
                uid, QString::fromStdString(annotation::annotationsToJson({onSlice})));
        }
        StudyDatabase again(dbPath());
        const auto stored =
            annotation::parseAnnotationsJson(again.seriesAnnotations(uid)->toStdString(), "stored");
        QCOMPARE(stored.size(), std::size_t(1));
        QVERIFY(stored[0].slice);
        QVERIFY(stored[0].slice->orientation == annotation::SliceOrientation::Axial);
        QCOMPARE(stored[0].slice->spacingMm, 5.0);
        QCOMPARE(QString::fromStdString(annotation::measurementText(stored[0])),
                 QStringLiteral("42.3 mm \u00b7 axial 118.5 mm"));
    }

    void cancelLeavesTheDatabaseUnchanged_data() {
        QTest::addColumn<QString>("stage"); // the progress message that triggers the cancel
        QTest::newRow("before the import") << QString();
        QTest::newRow("while scanning") << QStringLiteral("DICOM headers");
        QTest::newRow("while reading series") << QStringLiteral("Reading series");
        QTest::newRow("while writing") << QStringLiteral("Writing the study database");
    }

    void cancelLeavesTheDatabaseUnchanged() {
        QFETCH(QString, stage);
        const QString root = folder(QStringLiteral("cancel"));
        test::writeSeries(root + QStringLiteral("/first"), {});
        importStudies(dbPath(), root + QStringLiteral("/first"));
        for (int i = 0; i < 3; ++i) {
            test::SyntheticSeries more;
            more.patientId = QStringLiteral("NEW-%1").arg(i);
            test::writeSeries(root + QStringLiteral("/more%1").arg(i), more);
        }
        const QStringList before = test::snapshot(dbPath());
        QVERIFY(!before.isEmpty());

        auto cancel = std::make_shared<core::CancelToken>();
        if (stage.isEmpty())
            cancel->cancel();
        QStringList messages;
        std::mutex mutex; // the scanner reports from several threads at once
        const auto onProgress = [&](double, const std::string& message) {
            std::lock_guard lock(mutex);
            messages.append(QString::fromStdString(message));
            if (!stage.isEmpty() &&
                QString::fromStdString(message).contains(stage, Qt::CaseInsensitive))
                cancel->cancel();
        };
        const ImportSummary summary = importStudies(dbPath(), root, onProgress, cancel);
        QVERIFY2(summary.cancelled, qPrintable(messages.join(QStringLiteral(" / "))));
        QCOMPARE(summary.seriesAdded, 0);
        QCOMPARE(test::snapshot(dbPath()), before);
        // And the same import without a cancel does write.
        QCOMPARE(importStudies(dbPath(), root).seriesAdded, 3);
    }

    void geometryWarningsAreStored() {
        test::SyntheticSeries gappy;
        gappy.slicePositions = {0.0, 1.0, 2.0, 4.0, 5.0, 6.0};
        const QString uid = test::writeSeries(folder(QStringLiteral("gappy")), gappy);
        importStudies(dbPath(), folder(QStringLiteral("gappy")));
        StudyDatabase db(dbPath());
        const std::optional<SeriesRecord> record = db.series(uid);
        QVERIFY(record);
        QVERIFY(record->missingSlices == 1 || record->unevenGaps);
        QCOMPARE(record->maxGap, 2.0);
        QVERIFY2(!record->warnings().isEmpty(), "no warning for a missing slice");
        const QString text = record->warnings().join(QLatin1Char('\n'));
        QVERIFY2(text.contains(QStringLiteral("missing")) ||
                     text.contains(QStringLiteral("uneven")),
                 qPrintable(text));
    }

    void brokenFileIsAttachedToItsSeries() {
        const QString series = folder(QStringLiteral("broken"));
        const QString uid = test::writeSeries(series, {});
        QFile broken(series + QStringLiteral("/broken.dcm"));
        QVERIFY(broken.open(QIODevice::WriteOnly));
        broken.write(QByteArray(128, '\0') + QByteArray("DICM") + QByteArray(40, '\x7f'));
        broken.close();
        const ImportSummary summary = importStudies(dbPath(), series);
        QCOMPARE(summary.seriesAdded, 1);
        StudyDatabase db(dbPath());
        const QList<SeriesMessage> errors = db.series(uid)->fileErrors();
        QCOMPARE(errors.size(), 1);
        QCOMPARE(errors[0].file, broken.fileName());
        QVERIFY(!errors[0].text.isEmpty());
        QCOMPARE(db.seriesFiles(uid).size(), 4);
        QVERIFY(summary.errors.isEmpty());
    }

    void unreadableInputThrows() {
        QVERIFY_THROWS_EXCEPTION(core::Error,
                                 importStudies(dbPath(), folder(QStringLiteral("does-not-exist"))));
        StudyDatabase db(dbPath());
        QCOMPARE(db.seriesCount(), 0);
    }

    void thumbnailWindows_data() {
        QTest::addColumn<bool>("isCt");
        QTest::addColumn<int>("low");  // value of the left half, in HU / real units
        QTest::addColumn<int>("high"); // value of the right half
        QTest::addColumn<int>("expectedLeft");
        QTest::addColumn<int>("expectedRight");
        QTest::newRow("CT below and above W400/L40") << true << -1000 << 1000 << 0 << 255;
        QTest::newRow("CT at the level") << true << 40 << 40 << 128 << 128;
        QTest::newRow("MR percentile window") << false << 10 << 500 << 0 << 255;
    }

    void thumbnailWindows() {
        QFETCH(bool, isCt);
        QFETCH(int, low);
        QFETCH(int, high);
        QFETCH(int, expectedLeft);
        QFETCH(int, expectedRight);
        // 64 x 32 pixels of 0.5 x 1 mm: a 32 x 32 mm square, so the thumbnail is square too.
        volume::Volume slice({64, 32, 1}, volume::VoxelType::Int16,
                             volume::VolumeGeometry::regular({0, 0, 0}, {0.5, 1.0, 1.0}));
        slice.setValueMapping({1.0, -1024.0});
        auto* voxels = slice.dataAs<std::int16_t>();
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 64; ++x)
                voxels[slice.index(x, y, 0)] = std::int16_t((x < 32 ? low : high) + 1024);
        const QImage image = makeThumbnail(slice, isCt);
        QCOMPARE(image.size(), QSize(kThumbnailSize, kThumbnailSize));
        QVERIFY(qAbs(qGray(image.pixel(4, 64)) - expectedLeft) <= 1);
        QVERIFY(qAbs(qGray(image.pixel(kThumbnailSize - 4, 64)) - expectedRight) <= 1);
    }
};

QTEST_GUILESS_MAIN(StudyDatabaseTest)
#include "study_database_test.moc"
