#include "lw/render/surface_sampling.h"

#include "lw/core/log.h"
#include "lw/volume/oversampling.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace lw::render {
namespace {
constexpr core::LogCategory kLog("lw.render");
} // namespace

std::string_view oversamplingName(Oversampling oversampling) {
    return oversampling == Oversampling::Auto ? "auto" : "off";
}

std::optional<Oversampling> parseOversampling(std::string_view name) {
    if (name == "auto")
        return Oversampling::Auto;
    if (name == "off")
        return Oversampling::Off;
    return std::nullopt;
}

glm::ivec3 oversamplingFactors(glm::ivec3 dims, const volume::VolumeGeometry& geometry,
                               Oversampling oversampling) {
    glm::ivec3 factors(1);
    if (oversampling == Oversampling::Off || dims.x < 1 || dims.y < 1 || dims.z < 1)
        return factors;
    const glm::dvec3 last(std::max(dims.x - 1, 0), std::max(dims.y - 1, 0),
                          std::max(dims.z - 1, 0));
    const double diagonal =
        glm::length(geometry.indexToPatient(last) - geometry.indexToPatient(glm::dvec3(0.0)));
    if (!(diagonal > 0.0))
        return factors;
    const double largestCell = diagonal / kOversamplingCellsPerDiagonal;
    const glm::dvec3 cell(geometry.spacingI(), geometry.spacingJ(), std::abs(geometry.sliceStep()));
    for (int axis = 0; axis < 3; ++axis) {
        if (dims[axis] < 2 || !(cell[axis] > largestCell))
            continue;
        const double needed = std::ceil(cell[axis] / largestCell);
        factors[axis] = int(std::min(needed, double(kMaxOversamplingFactor)));
    }
    return factors;
}

std::optional<volume::Volume> oversampledToRender(const volume::Volume& volume,
                                                  Oversampling oversampling, unsigned threads) {
    const glm::ivec3 factors = oversamplingFactors(volume.dims(), volume.geometry(), oversampling);
    if (factors == glm::ivec3(1))
        return std::nullopt;
    volume::Volume finer = volume::oversampled(volume, factors, threads);
    const glm::ivec3 dims = finer.dims();
    kLog.info("oversampled " + std::to_string(factors.x) + "x" + std::to_string(factors.y) + "x" +
              std::to_string(factors.z) + " for rendering (cells at most 1/" +
              std::to_string(int(kOversamplingCellsPerDiagonal)) + " of the diagonal): " +
              std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z));
    return finer;
}

std::shared_ptr<const volume::Volume> volumeToRender(std::shared_ptr<const volume::Volume> volume,
                                                     Oversampling oversampling, unsigned threads) {
    if (!volume)
        return volume;
    std::optional<volume::Volume> finer = oversampledToRender(*volume, oversampling, threads);
    if (!finer)
        return volume;
    return std::make_shared<const volume::Volume>(std::move(*finer));
}

} // namespace lw::render
