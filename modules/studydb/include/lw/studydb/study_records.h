#pragma once

// Plain records read from and written to the study database. Qt value types only, so the browser
// model can hold them and a worker thread can hand them over without touching the database.

#include <QByteArray>
#include <QDate>
#include <QDateTime>
#include <QImage>
#include <QList>
#include <QString>
#include <QStringList>
#include <array>
#include <optional>

namespace lw::studydb {

// A warning about a series (tilt, uneven gaps, ...) or a file of it that could not be used.
struct SeriesMessage {
    enum class Kind { Warning, Error };
    Kind kind = Kind::Warning;
    QString file; // empty for a warning about the whole series
    QString text;

    bool operator==(const SeriesMessage&) const = default;
};

struct SeriesRecord {
    QString uid;
    QString studyUid;
    QString modality;
    QString description;
    std::optional<int> number;
    QString studyDate; // DICOM DA (yyyyMMdd) of the study, may be empty
    QString studyTime;
    int sliceCount = 0;                           // frames of the largest volume
    int fileCount = 0;                            // image files referenced in place
    std::array<int, 3> dims{0, 0, 0};             // columns, rows, slices of the largest volume
    std::array<double, 3> spacing{0.0, 0.0, 0.0}; // mm
    double tiltDegrees = 0.0;
    bool unevenGaps = false;
    double minGap = 0.0;
    double maxGap = 0.0;
    int missingSlices = 0;
    int volumeCount = 0;
    QByteArray thumbnailPng; // empty when the middle slice could not be decoded
    QString sourceRoot;      // the folder or DICOMDIR it was imported from
    QDateTime importedAt;
    QList<SeriesMessage> messages;

    QStringList warnings() const;            // texts of the Warning messages
    QList<SeriesMessage> fileErrors() const; // the Error messages (file + reason)
    QImage thumbnail() const;                // null when there is none
};

struct StudyRecord {
    QString uid;
    QString studyId;
    QString description;
    QString date; // yyyyMMdd
    QString time;
    QString accessionNumber;
    QList<SeriesRecord> series;
};

struct PatientRecord {
    QString patientId;
    QString name; // DICOM PN as stored (components separated by '^')
    QString birthDate;
    QString sex;
    QList<StudyRecord> studies;
};

// What the browser shows. Every whitespace-separated word of `text` must occur (case-insensitive)
// in the patient name, patient id, study description or series description; the dates bound
// the study date (inclusive). Studies without a date pass only when no range is set.
struct StudyFilter {
    QString text;
    QDate from; // null: open
    QDate to;   // null: open

    bool isEmpty() const { return text.trimmed().isEmpty() && from.isNull() && to.isNull(); }
};

// A file the importer could not use and could not attribute to a series.
struct ImportProblem {
    QString file;
    QString reason;
};

struct ImportSummary {
    int seriesAdded = 0;
    int seriesUpdated = 0;
    std::size_t filesExamined = 0;
    QList<ImportProblem> errors; // import-level (also in the import log table)
    int seriesWithWarnings = 0;
    bool cancelled = false; // nothing was written
};

// DICOM DA / PN helpers for display.
QDate parseDicomDate(const QString& da);
QString displayName(const QString& personName);

} // namespace lw::studydb
