#pragma once

// Helpers shared by the study database tests: synthetic series on disk, a snapshot of every
// table (to prove a cancelled import changed nothing), and the shared data folder.

#include <QString>
#include <QStringList>
#include <optional>

namespace lw::studydb::test {

struct SyntheticSeries {
    QString seriesUid;
    QString description = QStringLiteral("synthetic");
    QString patientName = QStringLiteral("Test^Linework");
    QString patientId = QStringLiteral("LW-TEST");
    QString studyUid; // generated when empty
    QList<double> slicePositions{0.0, 1.0, 2.0, 3.0};
    int size = 16;
};

// Writes one file per slice into `folder` (created); returns the series UID.
QString writeSeries(const QString& folder, SyntheticSeries series);

// Every row of every table of the database file, as text, sorted: equal snapshots mean equal
// content. Uses its own connection.
QStringList snapshot(const QString& databasePath);

// Runs one SQL statement on the file through its own connection (to fake old or new files).
void execRaw(const QString& databasePath, const QString& sql);

// PRAGMA user_version of the file, read through its own connection (not StudyDatabase, which
// would migrate it).
int userVersion(const QString& databasePath);

// Runs an SQL script of one statement per line ("--" lines are comments) through one
// connection: a database file as an older Linework wrote it (tests/studydb/data).
void loadSqlScript(const QString& databasePath, const QString& scriptPath);

// ../shared/data or $LINEWORK_SHARED_DATA when it exists.
std::optional<QString> sharedDataDir();

} // namespace lw::studydb::test
