#include "lw/studydb/study_database.h"

#include "lw/annotation/annotation_json.h"
#include "lw/core/error.h"

#include <QDir>
#include <QFileInfo>
#include <QHash>
#include <QRegularExpression>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QStandardPaths>
#include <QUuid>
#include <QVariant>

namespace lw::studydb {

namespace {

std::string str(const QString& text) {
    return text.toStdString();
}

// Creation order matters for the foreign keys; ON DELETE CASCADE removes files and messages
// with their series.
const char* const kSchemaV1[] = {
    "CREATE TABLE patients ("
    " id INTEGER PRIMARY KEY,"
    " patient_key TEXT NOT NULL UNIQUE,"
    " patient_id TEXT NOT NULL, name TEXT NOT NULL, birth_date TEXT, sex TEXT)",
    "CREATE TABLE studies ("
    " id INTEGER PRIMARY KEY,"
    " uid TEXT NOT NULL UNIQUE,"
    " patient_ref INTEGER NOT NULL REFERENCES patients(id) ON DELETE CASCADE,"
    " study_id TEXT, description TEXT, date TEXT, time TEXT, accession TEXT)",
    "CREATE TABLE series ("
    " id INTEGER PRIMARY KEY,"
    " uid TEXT NOT NULL UNIQUE,"
    " study_ref INTEGER NOT NULL REFERENCES studies(id) ON DELETE CASCADE,"
    " modality TEXT, description TEXT, number INTEGER,"
    " slice_count INTEGER NOT NULL DEFAULT 0, file_count INTEGER NOT NULL DEFAULT 0,"
    " dim_x INTEGER, dim_y INTEGER, dim_z INTEGER,"
    " spacing_x REAL, spacing_y REAL, spacing_z REAL,"
    " tilt_degrees REAL, uneven_gaps INTEGER NOT NULL DEFAULT 0, min_gap REAL, max_gap REAL,"
    " missing_slices INTEGER NOT NULL DEFAULT 0, volume_count INTEGER NOT NULL DEFAULT 0,"
    " thumbnail BLOB, source_root TEXT, imported_at TEXT)",
    "CREATE TABLE series_files ("
    " id INTEGER PRIMARY KEY,"
    " series_ref INTEGER NOT NULL REFERENCES series(id) ON DELETE CASCADE,"
    " path TEXT NOT NULL, sop_uid TEXT)",
    "CREATE INDEX series_files_series ON series_files(series_ref)",
    "CREATE TABLE series_messages ("
    " id INTEGER PRIMARY KEY,"
    " series_ref INTEGER NOT NULL REFERENCES series(id) ON DELETE CASCADE,"
    " kind TEXT NOT NULL CHECK (kind IN ('warning', 'error')),"
    " file TEXT, text TEXT NOT NULL)",
    "CREATE INDEX series_messages_series ON series_messages(series_ref)",
    "CREATE TABLE import_log ("
    " id INTEGER PRIMARY KEY,"
    " imported_at TEXT NOT NULL, source_root TEXT, file TEXT, reason TEXT NOT NULL)",
};

// Version 2 adds the annotations, one JSON document per series UID (no foreign key: they outlive
// the series' row, see seriesAnnotations).
const char* const kSchemaV2Additions[] = {
    "CREATE TABLE series_annotations ("
    " series_uid TEXT PRIMARY KEY,"
    " json TEXT NOT NULL, updated_at TEXT NOT NULL)",
};

const char* kindName(SeriesMessage::Kind kind) {
    return kind == SeriesMessage::Kind::Error ? "error" : "warning";
}

QString patientKey(const PatientRecord& patient) {
    // Patient ID alone is not unique across sites (and often empty in anonymised data).
    return patient.patientId + QChar(0x1f) + patient.name;
}

QVariant optionalInt(const std::optional<int>& value) {
    return value ? QVariant(*value) : QVariant(QMetaType(QMetaType::Int));
}

bool containsAll(const QStringList& words, const QStringList& fields) {
    for (const QString& word : words) {
        bool found = false;
        for (const QString& field : fields)
            if (field.contains(word, Qt::CaseInsensitive)) {
                found = true;
                break;
            }
        if (!found)
            return false;
    }
    return true;
}

bool inDateRange(const QString& studyDate, const StudyFilter& filter) {
    if (filter.from.isNull() && filter.to.isNull())
        return true;
    const QDate date = parseDicomDate(studyDate);
    if (!date.isValid())
        return false;
    return (filter.from.isNull() || date >= filter.from) &&
           (filter.to.isNull() || date <= filter.to);
}

} // namespace

// Rolls back unless commit() was reached, so every early return or exception leaves the file as
// it was.
class StudyDatabase::Transaction {
public:
    Transaction(QSqlDatabase db, const QString& path) : m_db(std::move(db)), m_path(path) {
        if (!m_db.transaction())
            throw core::Error(str(m_path),
                              "cannot start a transaction: " + str(m_db.lastError().text()));
    }
    ~Transaction() {
        if (!m_done)
            m_db.rollback();
    }
    void commit() {
        if (!m_db.commit()) {
            const QString reason = m_db.lastError().text();
            m_db.rollback();
            m_done = true;
            throw core::Error(str(m_path), "cannot commit: " + str(reason));
        }
        m_done = true;
    }

private:
    QSqlDatabase m_db;
    QString m_path;
    bool m_done = false;
};

namespace {

void exec(QSqlQuery& query, const QString& path, const char* what) {
    if (!query.exec())
        throw core::Error(str(path), std::string(what) + ": " + str(query.lastError().text()));
}

void exec(QSqlQuery& query, const QString& sql, const QString& path, const char* what) {
    if (!query.exec(sql))
        throw core::Error(str(path), std::string(what) + ": " + str(query.lastError().text()));
}

} // namespace

StudyDatabase::StudyDatabase(const QString& path)
    : m_path(path), m_connectionName(QStringLiteral("lw.studydb.") +
                                     QUuid::createUuid().toString(QUuid::WithoutBraces)) {
    try {
        open();
        migrate();
    } catch (...) {
        QSqlDatabase::database(m_connectionName, false).close();
        QSqlDatabase::removeDatabase(m_connectionName);
        throw;
    }
}

StudyDatabase::~StudyDatabase() {
    {
        // The handle must be gone before removeDatabase, or Qt warns the connection is in use.
        QSqlDatabase db = QSqlDatabase::database(m_connectionName, false);
        db.close();
    }
    QSqlDatabase::removeDatabase(m_connectionName);
}

QString StudyDatabase::defaultPath() {
    const QString folder = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation);
    QDir().mkpath(folder);
    return folder + QStringLiteral("/studies.sqlite");
}

void StudyDatabase::open() {
    if (!QSqlDatabase::isDriverAvailable(QStringLiteral("QSQLITE")))
        throw core::Error(str(m_path), "the Qt SQLite driver (QSQLITE) is not installed");
    const QFileInfo info(m_path);
    if (!info.absoluteDir().exists() && !QDir().mkpath(info.absolutePath()))
        throw core::Error(str(m_path), "cannot create the folder " + str(info.absolutePath()));
    QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), m_connectionName);
    db.setDatabaseName(m_path);
    // The UI connection and an import worker's connection wait for each other's locks.
    db.setConnectOptions(QStringLiteral("QSQLITE_BUSY_TIMEOUT=10000"));
    if (!db.open())
        throw core::Error(str(m_path),
                          "cannot open the study database: " + str(db.lastError().text()));
    QSqlQuery query(db);
    // A file that is not SQLite fails here, on the first real read.
    exec(query, QStringLiteral("PRAGMA foreign_keys = ON"), m_path, "not a usable study database");
    if (!query.exec(QStringLiteral("PRAGMA journal_mode = WAL")))
        throw core::Error(str(m_path),
                          "not a usable study database: " + str(query.lastError().text()));
}

int StudyDatabase::schemaVersion() const {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    exec(query, QStringLiteral("PRAGMA user_version"), m_path, "cannot read the schema version");
    return query.next() ? query.value(0).toInt() : 0;
}

void StudyDatabase::migrate() {
    const int version = schemaVersion();
    if (version > kSchemaVersion)
        throw core::Error(str(m_path), "the study database has schema version " +
                                           std::to_string(version) +
                                           ", newer than this Linework understands (" +
                                           std::to_string(kSchemaVersion) +
                                           "); use a newer Linework or another database file");
    if (version == kSchemaVersion)
        return;
    QSqlDatabase db = QSqlDatabase::database(m_connectionName);
    Transaction transaction(db, m_path);
    // Each step takes the file from one version to the next, in the same transaction: an older
    // database keeps its rows and gains what is new.
    if (version < 1)
        createSchemaV1();
    if (version < 2)
        migrateToV2();
    if (version < 3)
        migrateToV3();
    QSqlQuery query(db);
    exec(query, QStringLiteral("PRAGMA user_version = %1").arg(kSchemaVersion), m_path,
         "cannot set the schema version");
    transaction.commit();
}

void StudyDatabase::createSchemaV1() {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    for (const char* statement : kSchemaV1)
        exec(query, QString::fromLatin1(statement), m_path, "cannot create the schema");
}

void StudyDatabase::migrateToV2() {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    for (const char* statement : kSchemaV2Additions)
        exec(query, QString::fromLatin1(statement), m_path, "cannot add the annotations table");
}

// Version 3: annotations may lie on slices (annotation file version 2). Each stored document is
// read and written again as version 2, so the file holds one format; the annotations themselves
// are unchanged (a version-1 document holds 3D annotations only, and the writer's ten
// significant digits read back as written). A document that does not read is left as it is:
// the review names its problem when the series is opened, as before, and nothing is lost. The
// time of the user's last save (updated_at) is kept.
void StudyDatabase::migrateToV3() {
    QSqlDatabase db = QSqlDatabase::database(m_connectionName);
    QSqlQuery rows(db);
    exec(rows, QStringLiteral("SELECT series_uid, json FROM series_annotations"), m_path,
         "cannot read the annotations to migrate");
    QList<std::pair<QString, QString>> rewritten;
    while (rows.next()) {
        const QString uid = rows.value(0).toString();
        try {
            const std::vector<annotation::Annotation> annotations =
                annotation::parseAnnotationsJson(rows.value(1).toString().toStdString(),
                                                 "the annotations of series " + str(uid));
            rewritten.append(
                {uid, QString::fromStdString(annotation::annotationsToJson(annotations))});
        } catch (const core::Error&) {
            continue; // kept as it is (see above)
        }
    }
    QSqlQuery update(db);
    update.prepare(QStringLiteral("UPDATE series_annotations SET json = ? WHERE series_uid = ?"));
    for (const auto& [uid, json] : rewritten) {
        update.bindValue(0, json);
        update.bindValue(1, uid);
        exec(update, m_path, "cannot migrate the annotations of a series");
    }
}

int StudyDatabase::seriesCount() const {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    exec(query, QStringLiteral("SELECT COUNT(*) FROM series"), m_path, "cannot count series");
    return query.next() ? query.value(0).toInt() : 0;
}

int StudyDatabase::patientCount() const {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    exec(query, QStringLiteral("SELECT COUNT(*) FROM patients"), m_path, "cannot count patients");
    return query.next() ? query.value(0).toInt() : 0;
}

int StudyDatabase::studyCount() const {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    exec(query, QStringLiteral("SELECT COUNT(*) FROM studies"), m_path, "cannot count studies");
    return query.next() ? query.value(0).toInt() : 0;
}

QList<ImportProblem> StudyDatabase::importLog() const {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    exec(query, QStringLiteral("SELECT file, reason FROM import_log ORDER BY id DESC"), m_path,
         "cannot read the import log");
    QList<ImportProblem> result;
    while (query.next())
        result.append({query.value(0).toString(), query.value(1).toString()});
    return result;
}

// ---- reading -------------------------------------------------------------------------------

namespace {

const char* const kSeriesColumns =
    "s.id, s.uid, st.uid, s.modality, s.description, s.number, st.date, st.time, s.slice_count,"
    " s.file_count, s.dim_x, s.dim_y, s.dim_z, s.spacing_x, s.spacing_y, s.spacing_z,"
    " s.tilt_degrees, s.uneven_gaps, s.min_gap, s.max_gap, s.missing_slices, s.volume_count,"
    " s.thumbnail, s.source_root, s.imported_at";
constexpr int kSeriesColumnCount = 25;

SeriesRecord readSeries(const QSqlQuery& q, int first) {
    SeriesRecord r;
    int c = first + 1; // column `first` is the row id
    r.uid = q.value(c++).toString();
    r.studyUid = q.value(c++).toString();
    r.modality = q.value(c++).toString();
    r.description = q.value(c++).toString();
    const QVariant number = q.value(c++);
    if (!number.isNull())
        r.number = number.toInt();
    r.studyDate = q.value(c++).toString();
    r.studyTime = q.value(c++).toString();
    r.sliceCount = q.value(c++).toInt();
    r.fileCount = q.value(c++).toInt();
    for (int& d : r.dims)
        d = q.value(c++).toInt();
    for (double& s : r.spacing)
        s = q.value(c++).toDouble();
    r.tiltDegrees = q.value(c++).toDouble();
    r.unevenGaps = q.value(c++).toBool();
    r.minGap = q.value(c++).toDouble();
    r.maxGap = q.value(c++).toDouble();
    r.missingSlices = q.value(c++).toInt();
    r.volumeCount = q.value(c++).toInt();
    r.thumbnailPng = q.value(c++).toByteArray();
    r.sourceRoot = q.value(c++).toString();
    r.importedAt = QDateTime::fromString(q.value(c++).toString(), Qt::ISODate);
    return r;
}

QHash<qint64, QList<SeriesMessage>> readMessages(QSqlDatabase db, const QString& path,
                                                 std::optional<qint64> seriesRef) {
    QSqlQuery query(db);
    query.prepare(QStringLiteral("SELECT series_ref, kind, file, text FROM series_messages") +
                  (seriesRef ? QStringLiteral(" WHERE series_ref = ?") : QString()) +
                  QStringLiteral(" ORDER BY id"));
    if (seriesRef)
        query.addBindValue(*seriesRef);
    exec(query, path, "cannot read series messages");
    QHash<qint64, QList<SeriesMessage>> result;
    while (query.next()) {
        SeriesMessage message;
        message.kind = query.value(1).toString() == QLatin1String("error")
                           ? SeriesMessage::Kind::Error
                           : SeriesMessage::Kind::Warning;
        message.file = query.value(2).toString();
        message.text = query.value(3).toString();
        result[query.value(0).toLongLong()].append(message);
    }
    return result;
}

} // namespace

QList<PatientRecord> StudyDatabase::patients(const StudyFilter& filter) const {
    QSqlDatabase db = QSqlDatabase::database(m_connectionName);
    QSqlQuery query(db);
    query.setForwardOnly(true);
    const QString sql =
        QStringLiteral(
            "SELECT %1, p.id, p.patient_id, p.name, p.birth_date, p.sex, st.id, st.study_id,"
            " st.description, st.accession"
            " FROM series s JOIN studies st ON s.study_ref = st.id"
            " JOIN patients p ON st.patient_ref = p.id"
            " ORDER BY p.name, p.patient_id, p.id, st.date, st.time, st.id, s.number, s.id")
            .arg(QLatin1String(kSeriesColumns));
    exec(query, sql, m_path, "cannot read the studies");
    const QHash<qint64, QList<SeriesMessage>> messages = readMessages(db, m_path, std::nullopt);
    const QStringList words =
        filter.text.split(QRegularExpression(QStringLiteral("\\s+")), Qt::SkipEmptyParts);

    QList<PatientRecord> result;
    qint64 lastPatient = -1, lastStudy = -1;
    while (query.next()) {
        SeriesRecord series = readSeries(query, 0);
        int c = kSeriesColumnCount;
        const qint64 patientRef = query.value(c++).toLongLong();
        PatientRecord patient;
        patient.patientId = query.value(c++).toString();
        patient.name = query.value(c++).toString();
        patient.birthDate = query.value(c++).toString();
        patient.sex = query.value(c++).toString();
        const qint64 studyRef = query.value(c++).toLongLong();
        StudyRecord study;
        study.uid = series.studyUid;
        study.studyId = query.value(c++).toString();
        study.description = query.value(c++).toString();
        study.date = series.studyDate;
        study.time = series.studyTime;
        study.accessionNumber = query.value(c++).toString();

        const QStringList fields{displayName(patient.name), patient.name, patient.patientId,
                                 study.description, series.description};
        if (!containsAll(words, fields) || !inDateRange(study.date, filter))
            continue;
        series.messages = messages.value(query.value(0).toLongLong());
        if (patientRef != lastPatient) {
            result.append(patient);
            lastPatient = patientRef;
            lastStudy = -1;
        }
        if (studyRef != lastStudy) {
            result.last().studies.append(study);
            lastStudy = studyRef;
        }
        result.last().studies.last().series.append(std::move(series));
    }
    return result;
}

std::optional<SeriesRecord> StudyDatabase::series(const QString& seriesUid) const {
    QSqlDatabase db = QSqlDatabase::database(m_connectionName);
    QSqlQuery query(db);
    query.prepare(QStringLiteral("SELECT %1 FROM series s JOIN studies st ON s.study_ref = st.id"
                                 " WHERE s.uid = ?")
                      .arg(QLatin1String(kSeriesColumns)));
    query.addBindValue(seriesUid);
    exec(query, m_path, "cannot read the series");
    if (!query.next())
        return std::nullopt;
    SeriesRecord record = readSeries(query, 0);
    const qint64 ref = query.value(0).toLongLong();
    record.messages = readMessages(db, m_path, ref).value(ref);
    return record;
}

QStringList StudyDatabase::seriesFiles(const QString& seriesUid) const {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    query.prepare(
        QStringLiteral("SELECT f.path FROM series_files f JOIN series s ON f.series_ref = s.id"
                       " WHERE s.uid = ? ORDER BY f.id"));
    query.addBindValue(seriesUid);
    exec(query, m_path, "cannot read the files of the series");
    QStringList result;
    while (query.next())
        result.append(query.value(0).toString());
    return result;
}

// ---- writing -------------------------------------------------------------------------------

WriteResult StudyDatabase::write(const ImportBatch& batch, core::Progress* progress) {
    QSqlDatabase db = QSqlDatabase::database(m_connectionName);
    Transaction transaction(db, m_path);
    WriteResult result;
    if (progress)
        progress->setTotal(std::size_t(batch.series.size()) + 1, "Writing the study database");
    for (const SeriesImport& import : batch.series) {
        if (progress)
            progress->throwIfCancelled();
        const qint64 patientRef = upsertPatient(import.patient);
        const qint64 studyRef = upsertStudy(import.study, patientRef);
        if (upsertSeries(import, studyRef, batch.sourceRoot))
            ++result.seriesAdded;
        else
            ++result.seriesUpdated;
        if (progress)
            progress->step();
    }
    writeProblems(batch);
    // A re-import may move a study to another patient record.
    removeEmptyParents();
    // The last chance to cancel: after commit the import has happened.
    if (progress)
        progress->throwIfCancelled();
    transaction.commit();
    if (progress)
        progress->step();
    return result;
}

qint64 StudyDatabase::upsertPatient(const PatientRecord& patient) {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    query.prepare(QStringLiteral("INSERT INTO patients (patient_key, patient_id, name, birth_date, "
                                 "sex) VALUES (?, ?, ?, ?, ?)"
                                 " ON CONFLICT(patient_key) DO UPDATE SET birth_date = "
                                 "excluded.birth_date, sex = excluded.sex"
                                 " RETURNING id"));
    query.addBindValue(patientKey(patient));
    query.addBindValue(patient.patientId);
    query.addBindValue(patient.name);
    query.addBindValue(patient.birthDate);
    query.addBindValue(patient.sex);
    exec(query, m_path, "cannot write a patient");
    if (!query.next())
        throw core::Error(str(m_path), "cannot write patient " + str(patient.patientId));
    return query.value(0).toLongLong();
}

qint64 StudyDatabase::upsertStudy(const StudyRecord& study, qint64 patientRef) {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    query.prepare(QStringLiteral(
        "INSERT INTO studies (uid, patient_ref, study_id, description, date, time, accession)"
        " VALUES (?, ?, ?, ?, ?, ?, ?)"
        " ON CONFLICT(uid) DO UPDATE SET patient_ref = excluded.patient_ref,"
        " study_id = excluded.study_id, description = excluded.description, date = excluded.date,"
        " time = excluded.time, accession = excluded.accession RETURNING id"));
    for (const QVariant& value :
         {QVariant(study.uid), QVariant(patientRef), QVariant(study.studyId),
          QVariant(study.description), QVariant(study.date), QVariant(study.time),
          QVariant(study.accessionNumber)})
        query.addBindValue(value);
    exec(query, m_path, "cannot write a study");
    if (!query.next())
        throw core::Error(str(m_path), "cannot write study " + str(study.uid));
    return query.value(0).toLongLong();
}

// Returns true when the series is new.
bool StudyDatabase::upsertSeries(const SeriesImport& import, qint64 studyRef,
                                 const QString& sourceRoot) {
    QSqlDatabase db = QSqlDatabase::database(m_connectionName);
    const SeriesRecord& s = import.series;
    QSqlQuery existing(db);
    existing.prepare(QStringLiteral("SELECT id FROM series WHERE uid = ?"));
    existing.addBindValue(s.uid);
    exec(existing, m_path, "cannot look up a series");
    const bool isNew = !existing.next();

    QSqlQuery query(db);
    query.prepare(QStringLiteral(
        "INSERT INTO series (uid, study_ref, modality, description, number, slice_count, "
        "file_count,"
        " dim_x, dim_y, dim_z, spacing_x, spacing_y, spacing_z, tilt_degrees, uneven_gaps, min_gap,"
        " max_gap, missing_slices, volume_count, thumbnail, source_root, imported_at)"
        " VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?, ?)"
        " ON CONFLICT(uid) DO UPDATE SET study_ref = excluded.study_ref, modality = "
        "excluded.modality,"
        " description = excluded.description, number = excluded.number,"
        " slice_count = excluded.slice_count, file_count = excluded.file_count,"
        " dim_x = excluded.dim_x, dim_y = excluded.dim_y, dim_z = excluded.dim_z,"
        " spacing_x = excluded.spacing_x, spacing_y = excluded.spacing_y,"
        " spacing_z = excluded.spacing_z, tilt_degrees = excluded.tilt_degrees,"
        " uneven_gaps = excluded.uneven_gaps, min_gap = excluded.min_gap,"
        " max_gap = excluded.max_gap, missing_slices = excluded.missing_slices,"
        " volume_count = excluded.volume_count, thumbnail = excluded.thumbnail,"
        " source_root = excluded.source_root, imported_at = excluded.imported_at RETURNING id"));
    const QVariantList values{s.uid,
                              studyRef,
                              s.modality,
                              s.description,
                              optionalInt(s.number),
                              s.sliceCount,
                              int(import.files.size()),
                              s.dims[0],
                              s.dims[1],
                              s.dims[2],
                              s.spacing[0],
                              s.spacing[1],
                              s.spacing[2],
                              s.tiltDegrees,
                              int(s.unevenGaps),
                              s.minGap,
                              s.maxGap,
                              s.missingSlices,
                              s.volumeCount,
                              s.thumbnailPng.isEmpty() ? QVariant(QMetaType(QMetaType::QByteArray))
                                                       : QVariant(s.thumbnailPng),
                              sourceRoot,
                              QDateTime::currentDateTimeUtc().toString(Qt::ISODate)};
    for (const QVariant& value : values)
        query.addBindValue(value);
    exec(query, m_path, "cannot write a series");
    if (!query.next())
        throw core::Error(str(m_path), "cannot write series " + str(s.uid));
    const qint64 seriesRef = query.value(0).toLongLong();
    query.finish();
    replaceChildren(import, seriesRef);
    return isNew;
}

void StudyDatabase::replaceChildren(const SeriesImport& import, qint64 seriesRef) {
    QSqlDatabase db = QSqlDatabase::database(m_connectionName);
    QSqlQuery query(db);
    for (const char* table : {"series_files", "series_messages"}) {
        query.prepare(
            QStringLiteral("DELETE FROM %1 WHERE series_ref = ?").arg(QLatin1String(table)));
        query.addBindValue(seriesRef);
        exec(query, m_path, "cannot replace the files of a series");
    }
    // Batch inserts: a 1000-slice series is one execBatch, not 1000 round trips.
    QVariantList refs, paths, sops;
    for (int i = 0; i < import.files.size(); ++i) {
        refs.append(seriesRef);
        paths.append(import.files[i]);
        sops.append(import.sopInstanceUids.value(i));
    }
    query.prepare(
        QStringLiteral("INSERT INTO series_files (series_ref, path, sop_uid) VALUES (?, ?, ?)"));
    query.addBindValue(refs);
    query.addBindValue(paths);
    query.addBindValue(sops);
    if (!refs.isEmpty() && !query.execBatch())
        throw core::Error(str(m_path),
                          "cannot write the files of a series: " + str(query.lastError().text()));
    for (const SeriesMessage& message : import.series.messages) {
        query.prepare(QStringLiteral(
            "INSERT INTO series_messages (series_ref, kind, file, text) VALUES (?, ?, ?, ?)"));
        query.addBindValue(seriesRef);
        query.addBindValue(QString::fromLatin1(kindName(message.kind)));
        query.addBindValue(message.file);
        query.addBindValue(message.text);
        exec(query, m_path, "cannot write the warnings of a series");
    }
}

void StudyDatabase::writeProblems(const ImportBatch& batch) {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    const QString now = QDateTime::currentDateTimeUtc().toString(Qt::ISODate);
    for (const ImportProblem& problem : batch.problems) {
        query.prepare(QStringLiteral(
            "INSERT INTO import_log (imported_at, source_root, file, reason) VALUES (?, ?, ?, ?)"));
        query.addBindValue(now);
        query.addBindValue(batch.sourceRoot);
        query.addBindValue(problem.file);
        query.addBindValue(problem.reason);
        exec(query, m_path, "cannot write the import log");
    }
}

void StudyDatabase::removeEmptyParents() {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    exec(query,
         QStringLiteral("DELETE FROM studies WHERE id NOT IN (SELECT study_ref FROM series)"),
         m_path, "cannot remove empty studies");
    exec(query,
         QStringLiteral("DELETE FROM patients WHERE id NOT IN (SELECT patient_ref FROM studies)"),
         m_path, "cannot remove empty patients");
}

bool StudyDatabase::removeSeries(const QString& seriesUid) {
    QSqlDatabase db = QSqlDatabase::database(m_connectionName);
    Transaction transaction(db, m_path);
    QSqlQuery query(db);
    query.prepare(QStringLiteral("DELETE FROM series WHERE uid = ?"));
    query.addBindValue(seriesUid);
    exec(query, m_path, "cannot remove the series");
    const bool removed = query.numRowsAffected() > 0;
    // Files and messages go with the series (ON DELETE CASCADE); empty parents go here.
    removeEmptyParents();
    transaction.commit();
    return removed;
}

// ---- annotations ---------------------------------------------------------------------------

std::optional<QString> StudyDatabase::seriesAnnotations(const QString& seriesUid) const {
    QSqlQuery query(QSqlDatabase::database(m_connectionName));
    query.prepare(QStringLiteral("SELECT json FROM series_annotations WHERE series_uid = ?"));
    query.addBindValue(seriesUid);
    exec(query, m_path, "cannot read the annotations of a series");
    if (!query.next())
        return std::nullopt;
    return query.value(0).toString();
}

void StudyDatabase::setSeriesAnnotations(const QString& seriesUid, const QString& json) {
    QSqlDatabase db = QSqlDatabase::database(m_connectionName);
    Transaction transaction(db, m_path);
    QSqlQuery query(db);
    query.prepare(QStringLiteral(
        "INSERT INTO series_annotations (series_uid, json, updated_at) VALUES (?, ?, ?)"
        " ON CONFLICT(series_uid) DO UPDATE SET json = excluded.json,"
        " updated_at = excluded.updated_at"));
    query.addBindValue(seriesUid);
    query.addBindValue(json);
    query.addBindValue(QDateTime::currentDateTimeUtc().toString(Qt::ISODate));
    if (!query.exec())
        throw core::Error(str(m_path), "cannot save the annotations of series " + str(seriesUid) +
                                           ": " + str(query.lastError().text()));
    transaction.commit();
}

} // namespace lw::studydb
