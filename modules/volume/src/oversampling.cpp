#include "lw/volume/oversampling.h"

#include "lw/core/error.h"
#include "lw/core/limits.h"
#include "lw/core/parallel.h"

#include <cmath>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace lw::volume {
namespace {

int oversampledCount(int n, int factor) {
    return n > 1 ? (n - 1) * factor + 1 : n;
}

// Where refined sample `index` falls between the original samples: the lower one and the
// weight of the upper one (0 on an original sample, which is then copied exactly).
struct Blend {
    int lower = 0;
    float upperWeight = 0.0f;
};

std::vector<Blend> blendsAlong(int originalCount, int factor) {
    std::vector<Blend> blends(std::size_t(oversampledCount(originalCount, factor)));
    for (std::size_t n = 0; n < blends.size(); ++n) {
        blends[n].lower = int(n) / factor;
        blends[n].upperWeight = float(int(n) % factor) / float(factor);
    }
    return blends;
}

template <typename T> T storedFrom(float value) {
    if constexpr (std::is_floating_point_v<T>)
        return T(value);
    else
        return T(std::lround(value)); // a blend of two T values lies between them: no clamp
}

// One refined slice: the two original slices it lies between blended into `plane` (float, the
// original in-plane size), then rows and columns refined from it.
template <typename T> struct SliceRefiner {
    const T* source;
    glm::ivec3 sourceDims;
    glm::ivec3 dims;
    const std::vector<Blend>& alongI;
    const std::vector<Blend>& alongJ;
    const std::vector<Blend>& alongK;
    T* target;

    void blendPlane(int k, std::vector<float>& plane) const {
        const std::size_t planeSize = std::size_t(sourceDims.x) * std::size_t(sourceDims.y);
        const Blend b = alongK[std::size_t(k)];
        const T* lower = source + planeSize * std::size_t(b.lower);
        const T* upper = b.upperWeight > 0.0f ? lower + planeSize : lower;
        for (std::size_t v = 0; v < planeSize; ++v)
            plane[v] = float(lower[v]) + b.upperWeight * (float(upper[v]) - float(lower[v]));
    }

    void refineRow(const std::vector<float>& plane, int j, std::vector<float>& row, T* out) const {
        const Blend b = alongJ[std::size_t(j)];
        const float* lower = plane.data() + std::size_t(sourceDims.x) * std::size_t(b.lower);
        const float* upper = b.upperWeight > 0.0f ? lower + sourceDims.x : lower;
        for (int i = 0; i < sourceDims.x; ++i)
            row[std::size_t(i)] = lower[i] + b.upperWeight * (upper[i] - lower[i]);
        for (int i = 0; i < dims.x; ++i) {
            const Blend c = alongI[std::size_t(i)];
            const float left = row[std::size_t(c.lower)];
            const float right = c.upperWeight > 0.0f ? row[std::size_t(c.lower) + 1] : left;
            out[i] = storedFrom<T>(left + c.upperWeight * (right - left));
        }
    }

    void operator()(std::size_t k) const {
        std::vector<float> plane(std::size_t(sourceDims.x) * std::size_t(sourceDims.y));
        std::vector<float> row(std::size_t(sourceDims.x));
        blendPlane(int(k), plane);
        T* slice = target + std::size_t(dims.x) * std::size_t(dims.y) * k;
        for (int j = 0; j < dims.y; ++j)
            refineRow(plane, j, row, slice + std::size_t(dims.x) * std::size_t(j));
    }
};

} // namespace

glm::ivec3 oversampledDims(glm::ivec3 dims, glm::ivec3 factors) {
    return {oversampledCount(dims.x, factors.x), oversampledCount(dims.y, factors.y),
            oversampledCount(dims.z, factors.z)};
}

Volume oversampled(const Volume& volume, glm::ivec3 factors, unsigned threads) {
    if (factors.x < 1 || factors.y < 1 || factors.z < 1)
        throw core::Error("oversampling", "factors must be at least 1");
    const glm::ivec3 dims = oversampledDims(volume.dims(), factors);
    core::ImportLimits().checkedBytes({std::size_t(dims.x), std::size_t(dims.y),
                                       std::size_t(dims.z), voxelSize(volume.voxelType())},
                                      "oversampling", "the oversampled volume");
    Volume result(dims, volume.voxelType(), volume.geometry().refined(factors, volume.dims().z));
    result.setValueMapping(volume.valueMapping());
    result.setDescription(volume.description());
    const std::vector<Blend> alongI = blendsAlong(volume.dims().x, factors.x);
    const std::vector<Blend> alongJ = blendsAlong(volume.dims().y, factors.y);
    const std::vector<Blend> alongK = blendsAlong(volume.dims().z, factors.z);
    dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        const SliceRefiner<T> refiner{
            volume.dataAs<T>(), volume.dims(), dims, alongI, alongJ, alongK, result.dataAs<T>()};
        core::parallelFor(std::size_t(dims.z), refiner, threads);
    });
    return result;
}

} // namespace lw::volume
