#include "lw/studydb/study_records.h"

namespace lw::studydb {

QStringList SeriesRecord::warnings() const {
    QStringList result;
    for (const SeriesMessage& message : messages)
        if (message.kind == SeriesMessage::Kind::Warning)
            result.append(message.text);
    return result;
}

QList<SeriesMessage> SeriesRecord::fileErrors() const {
    QList<SeriesMessage> result;
    for (const SeriesMessage& message : messages)
        if (message.kind == SeriesMessage::Kind::Error)
            result.append(message);
    return result;
}

QImage SeriesRecord::thumbnail() const {
    QImage image;
    if (!thumbnailPng.isEmpty())
        image.loadFromData(thumbnailPng, "PNG");
    return image;
}

QDate parseDicomDate(const QString& da) {
    // Old ACR-NEMA style dates carry dots (yyyy.MM.dd).
    QString digits = da.trimmed();
    digits.remove(QLatin1Char('.'));
    return QDate::fromString(digits, QStringLiteral("yyyyMMdd"));
}

QString displayName(const QString& personName) {
    // PN: family^given^middle^prefix^suffix; show "Family, Given Middle".
    const QStringList parts = personName.split(QLatin1Char('^'));
    if (parts.size() < 2)
        return personName.trimmed();
    QStringList rest;
    for (int i = 1; i < parts.size(); ++i)
        if (!parts[i].trimmed().isEmpty())
            rest.append(parts[i].trimmed());
    if (rest.isEmpty())
        return parts[0].trimmed();
    return parts[0].trimmed() + QStringLiteral(", ") + rest.join(QLatin1Char(' '));
}

} // namespace lw::studydb
