#include "review/slice_image.h"

#include <QObject>
#include <algorithm>
#include <cmath>

namespace lw::gui {
namespace {

QString sided(double value, const char* negative, const char* positive) {
    return QStringLiteral("%1 %2")
        .arg(QLatin1String(value < 0 ? negative : positive))
        .arg(std::abs(value), 0, 'f', 1);
}

} // namespace

WindowLevel windowPreset(WindowPreset preset) {
    switch (preset) {
    case WindowPreset::Bone:
        return {1800.0, 400.0};
    case WindowPreset::SoftTissue:
        return {400.0, 40.0};
    case WindowPreset::Lung:
        return {1500.0, -600.0};
    case WindowPreset::Brain:
        return {80.0, 40.0};
    }
    return {};
}

QString windowPresetName(WindowPreset preset) {
    switch (preset) {
    case WindowPreset::Bone:
        return QObject::tr("Bone");
    case WindowPreset::SoftTissue:
        return QObject::tr("Soft tissue");
    case WindowPreset::Lung:
        return QObject::tr("Lung");
    case WindowPreset::Brain:
        return QObject::tr("Brain");
    }
    return {};
}

QImage windowedImage(const volume::SliceImage& slice, WindowLevel window) {
    const glm::ivec2 size = slice.geometry.size;
    QImage image(size.x, size.y, QImage::Format_Grayscale8);
    volume::windowToGrey(slice, window.width, window.level, image.bits(),
                         std::size_t(image.bytesPerLine()));
    return image;
}

QString patientPointText(glm::dvec3 p) {
    return QObject::tr("%1 · %2 · %3 mm")
        .arg(sided(p.x, "R", "L"), sided(p.y, "A", "P"), sided(p.z, "I", "S"));
}

QString slicePositionText(volume::SliceOrientation orientation, double position) {
    // The normals of slice_plane.h: axial +z (superior), coronal +y (posterior), sagittal +x
    // (the patient's left).
    switch (orientation) {
    case volume::SliceOrientation::Axial:
        return QObject::tr("%1 mm").arg(sided(position, "I", "S"));
    case volume::SliceOrientation::Coronal:
        return QObject::tr("%1 mm").arg(sided(position, "A", "P"));
    case volume::SliceOrientation::Sagittal:
        return QObject::tr("%1 mm").arg(sided(position, "R", "L"));
    }
    return {};
}

QString sliceOrientationTitle(volume::SliceOrientation orientation) {
    switch (orientation) {
    case volume::SliceOrientation::Axial:
        return QObject::tr("Axial");
    case volume::SliceOrientation::Coronal:
        return QObject::tr("Coronal");
    case volume::SliceOrientation::Sagittal:
        return QObject::tr("Sagittal");
    }
    return {};
}

} // namespace lw::gui
