#include "lw/report/pdf_report.h"

#include <QBuffer>
#include <QFont>
#include <QFontMetricsF>
#include <QPageLayout>
#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>
#include <algorithm>
#include <cstdio>

namespace lw::report {
namespace {

constexpr int kDpi = 300;

QString text(const std::string& value) {
    return QString::fromStdString(value);
}

// DICOM DA "YYYYMMDD" as "YYYY-MM-DD"; anything else as stored.
QString dicomDate(const std::string& date) {
    if (date.size() == 8 && std::all_of(date.begin(), date.end(), ::isdigit))
        return text(date.substr(0, 4) + "-" + date.substr(4, 2) + "-" + date.substr(6, 2));
    return text(date);
}

// The non-empty parts, two spaces apart.
QString joined(const QStringList& parts) {
    QStringList kept;
    for (const QString& part : parts)
        if (!part.trimmed().isEmpty())
            kept.push_back(part.trimmed());
    return kept.join("  ");
}

QString pointText(const glm::dvec3& p) {
    char buffer[96];
    std::snprintf(buffer, sizeof buffer, "(%.1f, %.1f, %.1f)", p.x, p.y, p.z);
    return QString::fromLatin1(buffer);
}

void drawFooter(QPainter& painter, QRectF area, const ReportInfo& info, int page) {
    QFont font = painter.font();
    font.setPointSizeF(8);
    painter.setFont(font);
    const QString footer = QObject::tr("Created %1 with Linework %2 — page %3 of 2")
                               .arg(info.created.toString(Qt::ISODate), text(info.softwareVersion))
                               .arg(page);
    painter.setPen(Qt::darkGray);
    painter.drawText(area, Qt::AlignLeft | Qt::AlignBottom, footer);
    painter.setPen(Qt::black);
}

double drawTitle(QPainter& painter, QRectF area, const QString& title) {
    QFont font = painter.font();
    font.setPointSizeF(16);
    font.setBold(true);
    painter.setFont(font);
    const double height = QFontMetricsF(font, painter.device()).height() * 1.4;
    painter.drawText(area, Qt::AlignLeft | Qt::AlignTop, title);
    return height;
}

// A table: each row's cells in columns of `widths` (fractions of the area's width), wrapped at
// word boundaries; the first row bold when `headed`. Returns the height used.
double drawTable(QPainter& painter, QRectF area, const std::vector<double>& widths,
                 const std::vector<QStringList>& rows, bool headed) {
    QFont font = painter.font();
    font.setPointSizeF(10);
    font.setBold(false);
    const double gap = QFontMetricsF(font, painter.device()).height() * 0.25;
    double y = area.top();
    for (std::size_t r = 0; r < rows.size(); ++r) {
        QFont rowFont = font;
        rowFont.setBold(headed && r == 0);
        painter.setFont(rowFont);
        double x = area.left(), rowHeight = 0.0;
        for (std::size_t c = 0; c < widths.size() && c < std::size_t(rows[r].size()); ++c) {
            const QRectF cell(x, y, area.width() * widths[c] - gap, area.bottom() - y);
            const int flags = Qt::AlignLeft | Qt::AlignTop | Qt::TextWordWrap;
            const QRectF used = painter.boundingRect(cell, flags, rows[r][int(c)]);
            painter.drawText(cell, flags, rows[r][int(c)]);
            rowHeight = std::max(rowHeight, used.height());
            x += area.width() * widths[c];
        }
        y += rowHeight + gap;
    }
    return y - area.top();
}

void drawPicture(QPainter& painter, QRectF area, const QImage& picture) {
    if (picture.isNull())
        return;
    QSizeF size = picture.size();
    size.scale(area.size(), Qt::KeepAspectRatio);
    // No more pixels than the page can show at its resolution: a 4096-pixel export is not
    // embedded at full size in a 180 mm wide picture.
    const QImage embedded =
        picture.width() > size.width() * 1.05
            ? picture.scaled(size.toSize(), Qt::KeepAspectRatio, Qt::SmoothTransformation)
            : picture;
    painter.drawImage(QRectF(area.topLeft(), size), embedded);
    painter.setPen(QPen(Qt::lightGray, 2));
    painter.drawRect(QRectF(area.topLeft(), size));
    painter.setPen(Qt::black);
}

std::vector<QStringList> annotationRows(const std::vector<annotation::Annotation>& annotations) {
    std::vector<QStringList> rows = {{QObject::tr("#"), QObject::tr("Type"), QObject::tr("Text"),
                                      QObject::tr("Measurement"), QObject::tr("Points (LPS, mm)")}};
    for (std::size_t i = 0; i < annotations.size(); ++i) {
        const annotation::Annotation& item = annotations[i];
        QString points;
        for (const glm::dvec3& anchor : item.anchors)
            points += (points.isEmpty() ? "" : " ") + pointText(anchor);
        rows.push_back({QString::number(i + 1), QString(annotation::kindName(item.kind)),
                        text(item.text), text(annotation::measurementText(item)), points});
    }
    return rows;
}

void drawCommentAndMeasurements(QPainter& painter, QRectF body, const ReportInfo& info,
                                const std::vector<annotation::Annotation>& annotations) {
    double y = body.top();
    y += drawTitle(painter, QRectF(body.left(), y, body.width(), body.height()),
                   QObject::tr("Annotations and measurements"));
    const QRectF below(body.left(), y, body.width(), body.bottom() - y);
    if (annotations.empty())
        y += drawTable(painter, below, {1.0}, {{QObject::tr("none")}}, false);
    else
        y += drawTable(painter, below, {0.05, 0.1, 0.22, 0.18, 0.45}, annotationRows(annotations),
                       true);
    y += drawTitle(painter, QRectF(body.left(), y + 40, body.width(), body.height()),
                   QObject::tr("Comment")) +
         40;
    QFont font = painter.font();
    font.setPointSizeF(10);
    font.setBold(false);
    painter.setFont(font);
    painter.drawText(QRectF(body.left(), y, body.width(), body.bottom() - y),
                     Qt::AlignLeft | Qt::AlignTop | Qt::TextWordWrap,
                     info.comment.empty() ? QObject::tr("(none)") : text(info.comment));
}

} // namespace

std::vector<std::pair<QString, QString>> reportHeaderRows(const ReportInfo& info) {
    std::vector<std::pair<QString, QString>> rows;
    if (info.identity) {
        const input::DicomIdentity& id = *info.identity;
        if (info.anonymise) {
            rows.emplace_back(QObject::tr("Patient"), QObject::tr("(anonymised)"));
        } else {
            rows.emplace_back(QObject::tr("Patient"), text(id.patientName));
            rows.emplace_back(QObject::tr("Patient ID"), text(id.patientId));
            rows.emplace_back(QObject::tr("Birth date, sex"),
                              joined({dicomDate(id.patientBirthDate), text(id.patientSex)}));
            rows.emplace_back(QObject::tr("Accession"), text(id.accessionNumber));
        }
        rows.emplace_back(QObject::tr("Study"),
                          joined({dicomDate(id.studyDate), text(id.studyDescription)}));
        rows.emplace_back(QObject::tr("Series"),
                          joined({id.seriesNumber ? QString::number(*id.seriesNumber) : QString(),
                                  text(id.modality), text(id.seriesDescription)}));
    } else {
        rows.emplace_back(QObject::tr("Source"), text(info.sourceDescription));
    }
    rows.emplace_back(QObject::tr("Rendering"), text(info.method));
    rows.emplace_back(QObject::tr("Date"), info.created.toString("yyyy-MM-dd HH:mm"));
    return rows;
}

QByteArray renderPdfReport(const ReportInfo& info, const QImage& picture,
                           const std::vector<annotation::Annotation>& annotations) {
    QByteArray bytes;
    QBuffer buffer(&bytes);
    buffer.open(QIODevice::WriteOnly);
    QPdfWriter writer(&buffer);
    writer.setResolution(kDpi);
    writer.setPageLayout(QPageLayout(QPageSize(QPageSize::A4), QPageLayout::Portrait,
                                     QMarginsF(18, 18, 18, 18), QPageLayout::Millimeter));
    writer.setTitle(QObject::tr("Linework report"));
    writer.setCreator(QString("Linework %1").arg(text(info.softwareVersion)));
    QPainter painter(&writer);
    // No shaping, hence no ligatures: "finding" stays f-i in the PDF's text layer, so searching
    // and copying the report finds it (a ligature extracts as U+FB01).
    QFont font = painter.font();
    font.setStyleStrategy(QFont::PreferNoShaping);
    painter.setFont(font);
    const QRectF page(QPointF(0, 0), QSizeF(writer.width(), writer.height()));

    double y = drawTitle(painter, page, QObject::tr("Linework report"));
    std::vector<QStringList> header;
    for (const auto& [label, value] : reportHeaderRows(info))
        header.push_back({label, value});
    y += drawTable(painter, QRectF(0, y, page.width(), page.height() - y), {0.22, 0.78}, header,
                   false);
    y += 60;
    drawPicture(painter, QRectF(0, y, page.width(), page.height() * 0.9 - y), picture);
    drawFooter(painter, page, info, 1);

    writer.newPage();
    drawCommentAndMeasurements(painter, page.adjusted(0, 0, 0, -100), info, annotations);
    drawFooter(painter, page, info, 2);
    painter.end();
    return bytes;
}

} // namespace lw::report
