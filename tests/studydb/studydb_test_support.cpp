#include "studydb_test_support.h"

#include "dicom_test_writer.h"

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QSqlDatabase>
#include <QSqlError>
#include <QSqlQuery>
#include <QSqlRecord>
#include <QUuid>
#include <stdexcept>

namespace lw::studydb::test {

QString writeSeries(const QString& folder, SyntheticSeries series) {
    QDir().mkpath(folder);
    if (series.seriesUid.isEmpty())
        series.seriesUid = QString::fromStdString(dicom::test::makeTestUid());
    if (series.studyUid.isEmpty())
        series.studyUid = QString::fromStdString(dicom::test::makeTestUid());
    for (int i = 0; i < series.slicePositions.size(); ++i) {
        dicom::test::TestSlice slice;
        slice.rows = series.size;
        slice.columns = series.size;
        slice.pixels = dicom::test::rampPixels(series.size, series.size, -200 + 10 * i, 3);
        slice.position = glm::dvec3(0.0, 0.0, series.slicePositions[i]);
        slice.seriesUid = series.seriesUid.toStdString();
        slice.studyUid = series.studyUid.toStdString();
        slice.patientName = series.patientName.toStdString();
        slice.patientId = series.patientId.toStdString();
        slice.seriesDescription = series.description.toStdString();
        slice.instanceNumber = i + 1;
        dicom::test::writeTestSlice(
            QDir(folder).filePath(QStringLiteral("slice%1.dcm").arg(i)).toStdString(), slice);
    }
    return series.seriesUid;
}

namespace {

class RawConnection {
public:
    explicit RawConnection(const QString& path)
        : m_name(QStringLiteral("lw.test.") + QUuid::createUuid().toString(QUuid::WithoutBraces)) {
        QSqlDatabase db = QSqlDatabase::addDatabase(QStringLiteral("QSQLITE"), m_name);
        db.setDatabaseName(path);
        if (!db.open())
            throw std::runtime_error("cannot open " + path.toStdString());
    }
    ~RawConnection() {
        QSqlDatabase::database(m_name, false).close();
        QSqlDatabase::removeDatabase(m_name);
    }
    QSqlDatabase db() const { return QSqlDatabase::database(m_name); }

private:
    QString m_name;
};

} // namespace

QStringList snapshot(const QString& databasePath) {
    RawConnection connection(databasePath);
    QSqlQuery tables(connection.db());
    tables.exec(
        QStringLiteral("SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name"));
    QStringList rows;
    while (tables.next()) {
        const QString table = tables.value(0).toString();
        QSqlQuery query(connection.db());
        query.exec(QStringLiteral("SELECT * FROM %1").arg(table));
        while (query.next()) {
            QStringList fields{table};
            for (int i = 0; i < query.record().count(); ++i)
                fields.append(query.value(i).toString());
            rows.append(fields.join(QLatin1Char('|')));
        }
    }
    rows.sort();
    return rows;
}

void execRaw(const QString& databasePath, const QString& sql) {
    RawConnection connection(databasePath);
    QSqlQuery query(connection.db());
    if (!query.exec(sql))
        throw std::runtime_error(query.lastError().text().toStdString());
}

int userVersion(const QString& databasePath) {
    RawConnection connection(databasePath);
    QSqlQuery query(connection.db());
    if (!query.exec(QStringLiteral("PRAGMA user_version")) || !query.next())
        throw std::runtime_error("cannot read the user version of " + databasePath.toStdString());
    return query.value(0).toInt();
}

void loadSqlScript(const QString& databasePath, const QString& scriptPath) {
    QFile script(scriptPath);
    if (!script.open(QIODevice::ReadOnly | QIODevice::Text))
        throw std::runtime_error("cannot read " + scriptPath.toStdString());
    RawConnection connection(databasePath);
    QSqlQuery query(connection.db());
    const QStringList lines = QString::fromUtf8(script.readAll()).split(QLatin1Char('\n'));
    for (const QString& line : lines) {
        if (line.trimmed().isEmpty() || line.startsWith(QStringLiteral("--")))
            continue;
        if (!query.exec(line))
            throw std::runtime_error(scriptPath.toStdString() + ": " + line.toStdString() + ": " +
                                     query.lastError().text().toStdString());
    }
}

std::optional<QString> sharedDataDir() {
    QString dir = qEnvironmentVariable("LINEWORK_SHARED_DATA");
#ifdef LINEWORK_DEFAULT_SHARED_DATA
    if (dir.isEmpty())
        dir = QStringLiteral(LINEWORK_DEFAULT_SHARED_DATA);
#endif
    if (dir.isEmpty() || !QFileInfo(dir + QStringLiteral("/dicom")).isDir())
        return std::nullopt;
    return QFileInfo(dir).absoluteFilePath();
}

} // namespace lw::studydb::test
