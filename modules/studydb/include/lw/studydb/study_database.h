#pragma once

// The local study database: SQLite through Qt SQL. It indexes studies whose files stay where
// they are (paths, never copies) and never modifies or deletes a source file.
//
// Each instance owns its own, uniquely named Qt SQL connection. Connections are thread-affine:
// a worker thread opens its own StudyDatabase on the same file (WAL + busy timeout let the UI
// connection and the worker connection coexist).

#include "lw/core/progress.h"
#include "lw/studydb/study_records.h"

#include <QString>
#include <QStringList>
#include <memory>
#include <optional>

namespace lw::studydb {

// One series as the importer hands it to the database, with its patient and study.
struct SeriesImport {
    PatientRecord patient; // studies left empty
    StudyRecord study;     // series left empty
    SeriesRecord series;   // messages included
    QStringList files;
    QStringList sopInstanceUids; // parallel to files
};

struct ImportBatch {
    QString sourceRoot;
    QList<SeriesImport> series;
    QList<ImportProblem> problems; // import-level errors for the import log
};

struct WriteResult {
    int seriesAdded = 0;
    int seriesUpdated = 0;
};

class StudyDatabase {
public:
    // 1: patients, studies, series, their files and messages, the import log.
    // 2: the annotations of a series (series_annotations).
    // 3: annotations may lie on slices (annotation file version 2, its "slice" member); the
    //    stored documents were rewritten as version 2. A Linework of schema 2 refuses the file
    //    as a whole instead of failing on each series whose annotations it cannot read.
    static constexpr int kSchemaVersion = 3;

    // Opens (creating when missing) and migrates the database at `path`. Throws core::Error
    // naming the file when it cannot be opened, is not a database, or was written by a newer
    // Linework (schema version above kSchemaVersion).
    explicit StudyDatabase(const QString& path);
    ~StudyDatabase();
    StudyDatabase(const StudyDatabase&) = delete;
    StudyDatabase& operator=(const StudyDatabase&) = delete;

    // <AppDataLocation>/studies.sqlite; the folder is created.
    static QString defaultPath();

    const QString& path() const { return m_path; }
    int schemaVersion() const;

    // The patient -> study -> series tree that passes `filter`, sorted by name, date, number.
    QList<PatientRecord> patients(const StudyFilter& filter = {}) const;
    std::optional<SeriesRecord> series(const QString& seriesUid) const;
    QStringList seriesFiles(const QString& seriesUid) const;
    int seriesCount() const;
    int patientCount() const;
    int studyCount() const;
    // Import-level problems of past imports, newest first.
    QList<ImportProblem> importLog() const;

    // Writes the batch in one transaction: upsert by UIDs, the series' files and messages
    // replaced. When `progress` is cancelled during the write, everything is rolled back and
    // core::Cancelled is thrown; any failure rolls back and throws core::Error.
    WriteResult write(const ImportBatch& batch, core::Progress* progress = nullptr);

    // Removes the series and any study / patient left empty. Source files are untouched.
    // Returns false when no such series exists.
    bool removeSeries(const QString& seriesUid);

    // The review's annotations of a series, as the annotation JSON (lw/annotation/
    // annotation_json.h, version 2 from schema 3 on) the GUI wrote; nullopt when none were ever
    // saved. Keyed by the series
    // UID, not the series row: they outlive removing the series from the index (a re-import
    // finds them again) and a series opened without importing keeps them too.
    std::optional<QString> seriesAnnotations(const QString& seriesUid) const;
    // Replaces them in one transaction (throws core::Error naming the file and the series).
    void setSeriesAnnotations(const QString& seriesUid, const QString& json);

private:
    class Transaction;
    void open();
    void migrate();
    void createSchemaV1();
    void migrateToV2();
    void migrateToV3();
    qint64 upsertPatient(const PatientRecord& patient);
    qint64 upsertStudy(const StudyRecord& study, qint64 patientRef);
    bool upsertSeries(const SeriesImport& import, qint64 studyRef, const QString& sourceRoot);
    void replaceChildren(const SeriesImport& import, qint64 seriesRef);
    void writeProblems(const ImportBatch& batch);
    void removeEmptyParents();

    QString m_path;
    QString m_connectionName;
};

} // namespace lw::studydb
