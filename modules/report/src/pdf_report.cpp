#include "lw/report/pdf_report.h"

#include "lw/render/silhouette_methods.h"
#include "lw/report/export_image.h"

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

void drawFooter(QPainter& painter, QRectF area, const ReportInfo& info, int page, int pages) {
    QFont font = painter.font();
    font.setPointSizeF(8);
    font.setBold(false);
    painter.setFont(font);
    const QString footer = QObject::tr("Created %1 with Linework %2 — page %3 of %4")
                               .arg(info.created.toString(Qt::ISODate), text(info.softwareVersion))
                               .arg(page)
                               .arg(pages);
    painter.setPen(Qt::darkGray);
    painter.drawText(area, Qt::AlignLeft | Qt::AlignBottom, footer);
    painter.setPen(Qt::black);
}

// What flows down the pages: a title, a table row (cells in columns of `widths`, fractions of
// the width, wrapped at word boundaries) or a paragraph. Each is measured before it is drawn,
// so the pages, and with them "page i of N", are known first.
struct Block {
    enum class Kind { Title, Row, Paragraph };
    Kind kind = Kind::Paragraph;
    QStringList cells;
    bool bold = false;
    std::vector<double> widths{1.0};
};

QFont blockFont(const QPainter& painter, const Block& block) {
    QFont font = painter.font();
    font.setPointSizeF(block.kind == Block::Kind::Title ? 16 : 10);
    font.setBold(block.bold || block.kind == Block::Kind::Title);
    return font;
}

// Lays the block out at `topLeft` across `width` and returns its height; draws it when `draw`.
double layoutBlock(QPainter& painter, QPointF topLeft, double width, const Block& block,
                   bool draw) {
    painter.setFont(blockFont(painter, block));
    const double line = QFontMetricsF(painter.font(), painter.device()).height();
    if (block.kind == Block::Kind::Title) {
        if (draw)
            painter.drawText(QRectF(topLeft, QSizeF(width, line * 1.4)), Qt::AlignLeft,
                             block.cells.value(0));
        return line * 1.5;
    }
    const double gap = line * 0.25;
    const int flags = Qt::AlignLeft | Qt::AlignTop | Qt::TextWordWrap;
    double x = topLeft.x(), height = 0.0;
    for (std::size_t c = 0; c < block.widths.size() && c < std::size_t(block.cells.size()); ++c) {
        const QRectF cell(x, topLeft.y(), width * block.widths[c] - gap, 1e6);
        const QString& value = block.cells[int(c)];
        height = std::max(height, painter.boundingRect(cell, flags, value).height());
        if (draw)
            painter.drawText(cell, flags, value);
        x += width * block.widths[c];
    }
    return height + gap;
}

double drawBlocks(QPainter& painter, QPointF topLeft, double width,
                  const std::vector<Block>& blocks) {
    double y = topLeft.y();
    for (const Block& block : blocks)
        y += layoutBlock(painter, {topLeft.x(), y}, width, block, true);
    return y - topLeft.y();
}

// Greedy pages of `area`'s height; a table continued on a new page repeats its header row.
std::vector<std::vector<Block>> paginate(QPainter& painter, QRectF area,
                                         const std::vector<Block>& blocks) {
    std::vector<std::vector<Block>> pages(1);
    double y = area.top();
    const Block* tableHeader = nullptr;
    for (const Block& block : blocks) {
        const double height = layoutBlock(painter, {area.left(), y}, area.width(), block, false);
        if (y + height > area.bottom() && !pages.back().empty()) {
            pages.emplace_back();
            y = area.top();
            if (block.kind == Block::Kind::Row && tableHeader && &block != tableHeader) {
                pages.back().push_back(*tableHeader);
                y += layoutBlock(painter, {area.left(), y}, area.width(), *tableHeader, false);
            }
        }
        if (block.kind != Block::Kind::Row)
            tableHeader = nullptr;
        else if (block.bold)
            tableHeader = &block;
        pages.back().push_back(block);
        y += height;
    }
    return pages;
}

void drawPicture(QPainter& painter, QRectF area, const QImage& picture, const PictureLines& lines) {
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
    if (!lines.lines.empty() || !lines.hidden.empty()) {
        // In the picture's pixels, scaled like it: paths in the PDF, not pixels.
        painter.save();
        painter.translate(area.topLeft());
        painter.scale(size.width() / picture.width(), size.height() / picture.height());
        strokeHiddenLines(painter, lines.hidden, lines.width);
        strokeLines(painter, lines.lines, lines.width, lines.colour);
        painter.restore();
    }
    painter.setPen(QPen(Qt::lightGray, 2));
    painter.drawRect(QRectF(area.topLeft(), size));
    painter.setPen(Qt::black);
}

// The measurement column holds a slice's plane too ("87.5° · sagittal -123.4 mm" on one line).
const std::vector<double> kAnnotationColumns = {0.05, 0.1, 0.18, 0.32, 0.35};

// The kind in the table: the annotation file's name for it, in the interface's language.
QString kindLabel(annotation::AnnotationKind kind) {
    switch (kind) {
    case annotation::AnnotationKind::Label:
        return QObject::tr("label");
    case annotation::AnnotationKind::Arrow:
        return QObject::tr("arrow");
    case annotation::AnnotationKind::Ruler:
        return QObject::tr("ruler");
    case annotation::AnnotationKind::Angle:
        return QObject::tr("angle");
    }
    return QString(annotation::kindName(kind));
}

// The pages after the first: the annotations table and the comment.
std::vector<Block> measurementBlocks(const ReportInfo& info,
                                     const std::vector<annotation::Annotation>& annotations) {
    using Kind = Block::Kind;
    std::vector<Block> blocks = {{Kind::Title, {QObject::tr("Annotations and measurements")}}};
    if (annotations.empty())
        blocks.push_back({Kind::Row, {QObject::tr("none")}});
    else
        blocks.push_back({Kind::Row,
                          {QObject::tr("#"), QObject::tr("Type"), QObject::tr("Text"),
                           QObject::tr("Measurement"), QObject::tr("Points (LPS, mm)")},
                          true,
                          kAnnotationColumns});
    for (std::size_t i = 0; i < annotations.size(); ++i) {
        const annotation::Annotation& item = annotations[i];
        QString points;
        for (const glm::dvec3& anchor : item.anchors)
            points += (points.isEmpty() ? "" : " ") + pointText(anchor);
        blocks.push_back({Kind::Row,
                          {QString::number(i + 1), kindLabel(item.kind), text(item.text),
                           text(annotation::measurementText(item)), points},
                          false,
                          kAnnotationColumns});
    }
    blocks.push_back({Kind::Paragraph, {QStringLiteral(" ")}}); // a blank line before the comment
    blocks.push_back({Kind::Title, {QObject::tr("Comment")}});
    blocks.push_back(
        {Kind::Paragraph, {info.comment.empty() ? QObject::tr("(none)") : text(info.comment)}});
    return blocks;
}

} // namespace

std::string describeRendering(render::SilhouetteMethod method, double iso,
                              const render::CameraSetup& view) {
    const render::SilhouetteMethodInfo& info = render::silhouetteMethodInfo(method);
    char text[256];
    std::snprintf(text, sizeof text,
                  "Linework silhouette method %d (%s, Morar et al. 2013), iso-value %g, "
                  "view azimuth %g, elevation %g",
                  info.number, std::string(info.name).c_str(), iso, view.azimuthDeg,
                  view.elevationDeg);
    return text;
}

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
                           const std::vector<annotation::Annotation>& annotations,
                           const PictureLines& lines) {
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
    const QRectF body = page.adjusted(0, 0, 0, -page.height() * 0.05); // above the footer
    const auto later = paginate(painter, body, measurementBlocks(info, annotations));
    const int pages = 1 + int(later.size());

    std::vector<Block> header = {{Block::Kind::Title, {QObject::tr("Linework report")}}};
    for (const auto& [label, value] : reportHeaderRows(info))
        header.push_back({Block::Kind::Row, {label, value}, false, {0.22, 0.78}});
    const double y = drawBlocks(painter, page.topLeft(), page.width(), header) + 60;
    drawPicture(painter, QRectF(0, y, page.width(), body.bottom() - y), picture, lines);
    drawFooter(painter, page, info, 1, pages);
    for (std::size_t i = 0; i < later.size(); ++i) {
        writer.newPage();
        drawBlocks(painter, page.topLeft(), page.width(), later[i]);
        drawFooter(painter, page, info, int(i) + 2, pages);
    }
    painter.end();
    return bytes;
}

} // namespace lw::report
