#include "lw/studydb/study_importer.h"
#include "lw/volume/volume.h"

#include <algorithm>
#include <vector>

namespace lw::studydb {

namespace {

// Soft-tissue window, what a radiologist expects to recognise a CT series by.
constexpr double kCtWindowLow = 40.0 - 400.0 / 2.0;
constexpr double kCtWindowHigh = 40.0 + 400.0 / 2.0;

std::pair<double, double> percentileWindow(std::vector<double> values) {
    if (values.empty())
        return {0.0, 1.0};
    const auto at = [&values](double fraction) {
        const auto n = std::size_t(fraction * double(values.size() - 1));
        std::nth_element(values.begin(), values.begin() + std::ptrdiff_t(n), values.end());
        return values[n];
    };
    const double low = at(0.01);
    const double high = at(0.99);
    return {low, high > low ? high : low + 1.0};
}

} // namespace

QImage makeThumbnail(const volume::Volume& volume, bool isCt, int size) {
    const glm::ivec3 dims = volume.dims();
    if (volume.isEmpty() || dims.x <= 0 || dims.y <= 0)
        return {};
    const int z = dims.z / 2;
    std::vector<double> values(std::size_t(dims.x) * std::size_t(dims.y));
    for (int y = 0; y < dims.y; ++y)
        for (int x = 0; x < dims.x; ++x)
            values[std::size_t(y) * std::size_t(dims.x) + std::size_t(x)] =
                volume.valueMapping().toReal(volume.storedValue(x, y, z));
    const auto [low, high] =
        isCt ? std::pair{kCtWindowLow, kCtWindowHigh} : percentileWindow(values);

    QImage image(dims.x, dims.y, QImage::Format_Grayscale8);
    for (int y = 0; y < dims.y; ++y) {
        uchar* line = image.scanLine(y);
        for (int x = 0; x < dims.x; ++x) {
            const double v = values[std::size_t(y) * std::size_t(dims.x) + std::size_t(x)];
            line[x] = uchar(std::clamp((v - low) / (high - low) * 255.0 + 0.5, 0.0, 255.0));
        }
    }
    // Scale by the physical size so anisotropic pixels are not distorted.
    const double spacingX = volume.geometry().spacingI() > 0.0 ? volume.geometry().spacingI() : 1.0;
    const double spacingY = volume.geometry().spacingJ() > 0.0 ? volume.geometry().spacingJ() : 1.0;
    QSize target = QSizeF(dims.x * spacingX, dims.y * spacingY)
                       .scaled(size, size, Qt::KeepAspectRatio)
                       .toSize();
    target = target.expandedTo(QSize(1, 1));
    return image.scaled(target, Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
}

} // namespace lw::studydb
