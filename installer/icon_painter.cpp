// Paints the Linework icon (the shapes of icons/linework.svg) at one size as a PNG, for the
// hicolor PNG sizes the package installs: `linework-icon-painter SIZE OUT.png`. Qt Gui only, so
// no SVG renderer is needed at build time.
#include <QImage>
#include <QPainter>
#include <QPainterPath>
#include <QRadialGradient>

#include <cstdio>
#include <cstdlib>

namespace {

void paintIcon(QPainter& painter) {
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(QColor("#4a4641"), 6));
    painter.setBrush(QColor("#f4f1ea"));
    painter.drawRoundedRect(QRectF(8, 8, 240, 240), 44, 44);

    // Shaded left half: arc from the vertex down the cheek to the jaw.
    QPainterPath shaded;
    shaded.moveTo(128, 34);
    shaded.arcTo(QRectF(48, 34, 160, 176), 90, 90);
    shaded.cubicTo(48, 160, 66, 186, 92, 198);
    shaded.lineTo(92, 222);
    shaded.lineTo(128, 222);
    shaded.closeSubpath();
    QRadialGradient bone(QPointF(0.38 * 256, 0.32 * 256), 0.75 * 256);
    bone.setColorAt(0, QColor("#fffaf0"));
    bone.setColorAt(1, QColor("#8f8676"));
    painter.setPen(Qt::NoPen);
    painter.setBrush(bone);
    painter.drawPath(shaded);

    // The silhouette on the right, mirrored.
    QPainterPath outline;
    outline.moveTo(128, 34);
    outline.arcTo(QRectF(48, 34, 160, 176), 90, -90);
    outline.cubicTo(208, 160, 190, 186, 164, 198);
    outline.lineTo(164, 222);
    outline.lineTo(128, 222);
    painter.setBrush(Qt::NoBrush);
    painter.setPen(QPen(QColor("#1b1b1b"), 7, Qt::SolidLine, Qt::RoundCap, Qt::RoundJoin));
    painter.drawPath(outline);

    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor("#5b544a"));
    painter.drawEllipse(QPointF(98, 128), 17, 14);
    painter.setBrush(Qt::NoBrush);
    painter.setPen(QPen(QColor("#1b1b1b"), 6));
    painter.drawEllipse(QPointF(158, 128), 17, 14);
    painter.setPen(QPen(QColor("#4a4641"), 3, Qt::DashLine));
    painter.drawLine(QPointF(128, 34), QPointF(128, 222));
}

} // namespace

int main(int argc, char* argv[]) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: linework-icon-painter SIZE OUT.png\n");
        return 2;
    }
    const int size = std::atoi(argv[1]);
    if (size < 8 || size > 1024) {
        std::fprintf(stderr, "linework-icon-painter: size %s: expected 8..1024\n", argv[1]);
        return 2;
    }
    QImage image(size, size, QImage::Format_ARGB32_Premultiplied);
    image.fill(Qt::transparent);
    QPainter painter(&image);
    painter.scale(size / 256.0, size / 256.0);
    paintIcon(painter);
    painter.end();
    if (!image.save(QString::fromLocal8Bit(argv[2]))) {
        std::fprintf(stderr, "linework-icon-painter: cannot write %s\n", argv[2]);
        return 1;
    }
    return 0;
}
