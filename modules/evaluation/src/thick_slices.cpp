#include "lw/evaluation/thick_slices.h"

#include "lw/core/error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

namespace lw::evaluation {
namespace {

template <typename T> T meanValue(double sum, int count) {
    const double mean = sum / double(count);
    if constexpr (std::is_floating_point_v<T>)
        return T(mean);
    else
        return T(std::lround(mean)); // the mean of T values lies between them: no clamp
}

// Slab s holds thin slices s * stride .. s * stride + slicesPerSlab - 1.
volume::VolumeGeometry slabGeometry(const volume::VolumeGeometry& thin, int slabs,
                                    int slicesPerSlab, int stride) {
    std::vector<glm::dvec3> positions;
    positions.reserve(std::size_t(slabs));
    for (int slab = 0; slab < slabs; ++slab) {
        glm::dvec3 sum(0.0);
        for (int s = 0; s < slicesPerSlab; ++s)
            sum += thin.indexToPatient({0.0, 0.0, double(slab * stride + s)});
        positions.push_back(sum / double(slicesPerSlab));
    }
    return volume::VolumeGeometry::fromSlicePositions(thin.axisI(), thin.axisJ(), thin.spacingI(),
                                                      thin.spacingJ(), positions);
}

// The mean of each slab of `slicesPerSlab` thin slices, a slab starting every `stride` slices.
volume::Volume slabMeans(const volume::Volume& thin, int slicesPerSlab, int stride) {
    if (slicesPerSlab < 1)
        throw core::Error("thick slices", "slices per slab must be at least 1");
    const glm::ivec3 dims = thin.dims();
    const int slabs = dims.z >= slicesPerSlab ? (dims.z - slicesPerSlab) / stride + 1 : 0;
    if (slabs < 2)
        throw core::Error("thick slices", std::to_string(dims.z) +
                                              " slices make fewer than two "
                                              "slabs of " +
                                              std::to_string(slicesPerSlab));
    volume::Volume thick({dims.x, dims.y, slabs}, thin.voxelType(),
                         slabGeometry(thin.geometry(), slabs, slicesPerSlab, stride));
    thick.setValueMapping(thin.valueMapping());
    thick.setDescription(thin.description());
    const std::size_t plane = std::size_t(dims.x) * std::size_t(dims.y);
    volume::dispatchVoxelType(thin.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        const T* source = thin.dataAs<T>();
        T* target = thick.dataAs<T>();
        std::vector<double> sum(plane);
        for (int slab = 0; slab < slabs; ++slab) {
            std::fill(sum.begin(), sum.end(), 0.0);
            for (int s = 0; s < slicesPerSlab; ++s) {
                const T* slice = source + plane * std::size_t(slab * stride + s);
                for (std::size_t v = 0; v < plane; ++v)
                    sum[v] += double(slice[v]);
            }
            T* out = target + plane * std::size_t(slab);
            for (std::size_t v = 0; v < plane; ++v)
                out[v] = meanValue<T>(sum[v], slicesPerSlab);
        }
    });
    return thick;
}

} // namespace

volume::Volume thickSlabsOf(const volume::Volume& thin, int slicesPerSlab) {
    return slabMeans(thin, slicesPerSlab, slicesPerSlab);
}

volume::Volume slabMeansAtEverySlice(const volume::Volume& thin, int slicesPerSlab) {
    return slabMeans(thin, slicesPerSlab, 1);
}

void addVoxelNoise(volume::Volume& volume, double sigma, unsigned seed) {
    if (!(sigma >= 0.0))
        throw core::Error("noise", "sigma must be at least 0");
    if (sigma == 0.0)
        return;
    // Stored units: the mapping's slope scales real noise into them.
    const double storedSigma = sigma / std::abs(volume.valueMapping().slope);
    std::mt19937 random(seed);
    std::normal_distribution<double> noise(0.0, storedSigma);
    volume::dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        T* data = volume.dataAs<T>();
        for (std::size_t v = 0; v < volume.voxelCount(); ++v) {
            const double value = double(data[v]) + noise(random);
            if constexpr (std::is_floating_point_v<T>)
                data[v] = T(value);
            else
                data[v] = T(std::clamp(std::round(value), double(std::numeric_limits<T>::min()),
                                       double(std::numeric_limits<T>::max())));
        }
    });
}

} // namespace lw::evaluation
