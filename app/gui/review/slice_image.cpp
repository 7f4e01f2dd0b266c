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
    const float low = float(window.level - 0.5 * window.width);
    const float scale = float(255.0 / std::max(window.width, 1e-6));
    for (int y = 0; y < size.y; ++y) {
        uchar* row = image.scanLine(y);
        const float* values = slice.values.data() + std::size_t(y) * std::size_t(size.x);
        for (int x = 0; x < size.x; ++x) {
            const float grey = (values[x] - low) * scale; // NaN stays NaN: black below
            row[x] = grey > 0.0f ? uchar(std::min(grey, 255.0f) + 0.5f) : uchar(0);
        }
    }
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
