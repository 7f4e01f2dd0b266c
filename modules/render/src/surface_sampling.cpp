#include "lw/render/surface_sampling.h"

#include "lw/core/log.h"
#include "lw/volume/oversampling.h"
#include "lw/volume/slice_distance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

namespace lw::render {
namespace {
constexpr core::LogCategory kLog("lw.render");

// A number as the log shows it (300.5, not 300.500000).
std::string shortNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// The shape-based field's limit: one slice step along the normal (volume/slice_distance.h).
double distanceLimit(const volume::Volume& volume) {
    return kThickSliceDistanceLimitSteps * std::abs(volume.geometry().sliceStepAlongNormal());
}

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

std::string_view thickSlicesName(ThickSlices thickSlices) {
    return thickSlices == ThickSlices::Smooth ? "smooth" : "linear";
}

std::optional<ThickSlices> parseThickSlices(std::string_view name) {
    if (name == "smooth")
        return ThickSlices::Smooth;
    if (name == "linear")
        return ThickSlices::Linear;
    return std::nullopt;
}

bool hasThickSlices(glm::ivec3 dims, const volume::VolumeGeometry& geometry) {
    const double pixel = std::min(geometry.spacingI(), geometry.spacingJ());
    return dims.z >= 3 && pixel > 0.0 &&
           std::abs(geometry.sliceStepAlongNormal()) >= kThickSliceOverPixel * pixel;
}

SamplingPlan samplingPlan(glm::ivec3 dims, const volume::VolumeGeometry& geometry,
                          VolumeSampling sampling) {
    SamplingPlan plan;
    plan.factors = oversamplingFactors(dims, geometry, sampling.oversampling);
    if (sampling.thickSlices == ThickSlices::Smooth && hasThickSlices(dims, geometry)) {
        plan.factors.z = std::max(plan.factors.z, kThickSliceFactor);
        plan.shapeBased = true;
        plan.alongSlices = volume::SliceInterpolation::MonotoneCubic;
    }
    return plan;
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
                                                  VolumeSampling sampling, double iso,
                                                  unsigned threads) {
    const SamplingPlan plan = samplingPlan(volume.dims(), volume.geometry(), sampling);
    if (plan.asLoaded())
        return std::nullopt;
    const auto start = std::chrono::steady_clock::now();
    volume::Volume finer =
        plan.shapeBased ? volume::oversampled(volume::signedSliceDistance(
                                                  volume, iso, distanceLimit(volume), threads),
                                              plan.factors, threads, plan.alongSlices)
                        : volume::oversampled(volume, plan.factors, threads, plan.alongSlices);
    const glm::ivec3 dims = finer.dims();
    const glm::ivec3 factors = plan.factors;
    kLog.info(
        "oversampled " + std::to_string(factors.x) + "x" + std::to_string(factors.y) + "x" +
        std::to_string(factors.z) + " for rendering (cells at most 1/" +
        std::to_string(int(kOversamplingCellsPerDiagonal)) + " of the diagonal" +
        (plan.shapeBased ? "; thick slices by shape-based interpolation at " + shortNumber(iso)
                         : std::string()) +
        "): " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
        std::to_string(dims.z) + " in " +
        std::to_string(
            int(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                    .count())) +
        " ms");
    return finer;
}

std::shared_ptr<const volume::Volume> volumeToRender(std::shared_ptr<const volume::Volume> volume,
                                                     VolumeSampling sampling, double iso,
                                                     unsigned threads) {
    if (!volume)
        return volume;
    std::optional<volume::Volume> finer = oversampledToRender(*volume, sampling, iso, threads);
    if (!finer)
        return volume;
    return std::make_shared<const volume::Volume>(std::move(*finer));
}

} // namespace lw::render
