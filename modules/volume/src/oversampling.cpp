#include "lw/volume/oversampling.h"

#include "lw/core/error.h"
#include "lw/core/limits.h"
#include "lw/core/parallel.h"
#include "lw/kernels/slice_field_rules.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>
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

// Along the slices under SliceInterpolation::MonotoneCubic: the cubic Hermite segment between
// slices k and k + 1 at t, with Fritsch-Butland tangents (the harmonic mean of the two secants
// where they agree in sign, else 0; one-sided at the ends). Tangents at most twice the smaller
// secant keep each segment within its two end values (Fritsch & Carlson 1980): no overshoot.
// The expressions are kernels/slice_field_rules.h's, which the CUDA back-end's thick-slice field
// shares.
using kernels::HermiteWeights;
using kernels::monotoneTangent;
using kernels::roundHalfAway;

template <typename T> T storedFrom(float value) {
    if constexpr (std::is_floating_point_v<T>)
        return T(value);
    else
        return T(roundHalfAway(value)); // linear and monotone blends stay between the T values
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
    bool monotoneK; // else linear along k
    T* target;
    // Voxels from one source slice to the next: a plane, or factor planes where the source slices
    // lie in the target itself (refineBetweenSlices; split along k only).
    std::size_t sourceStride = std::size_t(sourceDims.x) * std::size_t(sourceDims.y);

    // The tangents at slices lower and lower + 1 of one gap, kept for the gap's other refined
    // slices (they share them: made once a gap, not once a refined slice).
    struct GapTangents {
        int gap = -1;
        std::vector<float> atLower, atUpper;
    };

    void tangentsOfGap(int lower, std::size_t planeSize, GapTangents& tangents) const {
        if (tangents.gap == lower)
            return;
        const T* y1 = source + planeSize * std::size_t(lower);
        const T* y2 = y1 + planeSize;
        const T* y0 = lower > 0 ? y1 - planeSize : y1;
        const T* y3 = lower + 2 < sourceDims.z ? y2 + planeSize : y2;
        const bool first = lower == 0;
        const bool last = lower + 2 >= sourceDims.z;
        tangents.atLower.resize(planeSize);
        tangents.atUpper.resize(planeSize);
        tangentsOf(planeSize, y0, y1, y2, y3, first, last, tangents.atLower.data(),
                   tangents.atUpper.data());
        tangents.gap = lower;
    }

    // Slices lower and lower + 1 on the Hermite curve at t, with their tangents from slices
    // lower - 1 and lower + 2 (one-sided at the ends: the end segment's own secant).
    // `out(v, value)` takes each pixel's value (into a plane to refine in-plane, or straight into
    // the slice).
    template <typename Out>
    void blendPlaneMonotone(const Blend& b, std::size_t planeSize, GapTangents& tangents,
                            Out&& out) const {
        tangentsOfGap(b.lower, planeSize, tangents);
        const T* y1 = source + planeSize * std::size_t(b.lower);
        const T* y2 = y1 + planeSize;
        const float* m1 = tangents.atLower.data();
        const float* m2 = tangents.atUpper.data();
        const HermiteWeights w(b.upperWeight);
        for (std::size_t v = 0; v < planeSize; ++v)
            out(v, kernels::hermiteBlend(w, float(y1[v]), m1[v], float(y2[v]), m2[v]));
    }

    template <typename Out> void blendPlane(int k, GapTangents& tangents, Out&& out) const {
        const std::size_t planeSize = std::size_t(sourceDims.x) * std::size_t(sourceDims.y);
        const Blend b = alongK[std::size_t(k)];
        if (monotoneK && b.upperWeight > 0.0f) {
            blendPlaneMonotone(b, planeSize, tangents, out);
            return;
        }
        const T* lower = source + planeSize * std::size_t(b.lower);
        const T* upper = b.upperWeight > 0.0f ? lower + planeSize : lower;
        for (std::size_t v = 0; v < planeSize; ++v)
            out(v, kernels::linearBlend(float(lower[v]), b.upperWeight, float(upper[v])));
    }

    // Voxels a run of refineGap takes at a time.
    static constexpr std::size_t kRun = 16;

    // Whether two runs of kRun voxels agree, four 64-bit words at a time.
    static bool sameRun(const T* a, const T* b) {
        constexpr std::size_t kWords = kRun * sizeof(T) / sizeof(std::uint64_t);
        std::uint64_t differ = 0;
        for (std::size_t n = 0; n < kWords; ++n) {
            std::uint64_t x, y;
            std::memcpy(&x, a + n * sizeof(std::uint64_t) / sizeof(T), sizeof x);
            std::memcpy(&y, b + n * sizeof(std::uint64_t) / sizeof(T), sizeof y);
            differ |= x ^ y;
        }
        return differ == 0;
    }

    // Refined slices [first, end) of one gap (slices lower and lower + 1), integer voxels, split
    // along k only, a run of kRun pixels at a time through all of them. A run where the two slices
    // agree is copied: a linear blend of two equal values is that value exactly, and a monotone
    // one is after rounding -- its tangents there are 0 (a secant of 0 makes Fritsch-Butland's
    // harmonic mean 0, and the one-sided end tangent is that secant) and its two value weights sum
    // to one within a few float ulps, far less than half a unit. In a thick-slice distance field
    // most pixels lie at the limit in both slices (on the demo 78 % of the runs). Elsewhere the
    // same arithmetic as blendPlane's, bit for bit.
    void refineGap(int lower, std::size_t first, std::size_t end) const {
        const std::size_t planeSize = std::size_t(sourceDims.x) * std::size_t(sourceDims.y);
        const T* y1 = source + sourceStride * std::size_t(lower);
        const T* y2 = y1 + sourceStride;
        const T* y0 = lower > 0 ? y1 - sourceStride : y1;
        const T* y3 = lower + 2 < sourceDims.z ? y2 + sourceStride : y2;
        const bool firstGap = lower == 0, lastGap = lower + 2 >= sourceDims.z;
        std::vector<HermiteWeights> weights;
        std::vector<T*> slices;
        for (std::size_t k = first; k < end; ++k) {
            weights.emplace_back(alongK[k].upperWeight);
            slices.push_back(target + planeSize * k);
        }
        const auto blend = [&](std::size_t run, std::size_t count, const float* m1,
                               const float* m2) {
            for (std::size_t n = 0; n < slices.size(); ++n)
                blendRun(count, y1 + run, y2 + run, m1, m2, weights[n],
                         alongK[first + n].upperWeight, slices[n] + run);
        };
        float m1[kRun], m2[kRun];
        std::size_t run = 0;
        for (; run + kRun <= planeSize; run += kRun) {
            if (sameRun(y1 + run, y2 + run)) {
                for (T* slice : slices)
                    std::memcpy(slice + run, y1 + run, kRun * sizeof(T));
                continue;
            }
            if (monotoneK) // a constant count: the inlined loops vectorise
                tangentsOf(kRun, y0 + run, y1 + run, y2 + run, y3 + run, firstGap, lastGap, m1, m2);
            blend(run, kRun, m1, m2);
        }
        const std::size_t rest = planeSize - run; // the plane's last pixels, fewer than a run
        if (monotoneK)
            tangentsOf(rest, y0 + run, y1 + run, y2 + run, y3 + run, firstGap, lastGap, m1, m2);
        blend(run, rest, m1, m2);
    }

    // The monotone tangents at slices 1 and 2 of `count` voxels, from slices 0 to 3 (`first`,
    // `last`: the stack's end gaps, one-sided there).
    static void tangentsOf(std::size_t count, const T* y0, const T* y1, const T* y2, const T* y3,
                           bool first, bool last, float* m1, float* m2) {
        for (std::size_t v = 0; v < count; ++v) {
            const float secant = float(y2[v]) - float(y1[v]);
            m1[v] = first ? secant : monotoneTangent(float(y1[v]) - float(y0[v]), secant);
            m2[v] = last ? secant : monotoneTangent(secant, float(y3[v]) - float(y2[v]));
        }
    }

    // `count` voxels between slices 1 and 2 at one refined slice: blendPlane's arithmetic.
    void blendRun(std::size_t count, const T* y1, const T* y2, const float* m1, const float* m2,
                  const HermiteWeights& w, float upperWeight, T* out) const {
        if (monotoneK)
            for (std::size_t v = 0; v < count; ++v)
                out[v] = storedFrom<T>(
                    kernels::hermiteBlend(w, float(y1[v]), m1[v], float(y2[v]), m2[v]));
        else
            for (std::size_t v = 0; v < count; ++v)
                out[v] =
                    storedFrom<T>(kernels::linearBlend(float(y1[v]), upperWeight, float(y2[v])));
    }

    // Refined slices [first, end) of integer voxels split along k only: originals copied, the
    // rest gap by gap (refineGap).
    void refineAlongSlicesOnly(std::size_t first, std::size_t end) const {
        const std::size_t planeSize = std::size_t(sourceDims.x) * std::size_t(sourceDims.y);
        for (std::size_t k = first; k < end;) {
            const Blend b = alongK[k];
            if (b.upperWeight == 0.0f) { // an original slice: copied, unless it is there
                T* slice = target + planeSize * k;
                const T* original = source + sourceStride * std::size_t(b.lower);
                if (slice != original)
                    std::memcpy(slice, original, planeSize * sizeof(T));
                ++k;
                continue;
            }
            std::size_t stop = k + 1;
            while (stop < end && alongK[stop].lower == b.lower && alongK[stop].upperWeight > 0.0f)
                ++stop;
            refineGap(b.lower, k, stop);
            k = stop;
        }
    }

    void refineRow(const std::vector<float>& plane, int j, std::vector<float>& row, T* out) const {
        const Blend b = alongJ[std::size_t(j)];
        const float* lower = plane.data() + std::size_t(sourceDims.x) * std::size_t(b.lower);
        const float* upper = b.upperWeight > 0.0f ? lower + sourceDims.x : lower;
        for (int i = 0; i < sourceDims.x; ++i)
            row[std::size_t(i)] = kernels::linearBlend(lower[i], b.upperWeight, upper[i]);
        for (int i = 0; i < dims.x; ++i) {
            const Blend c = alongI[std::size_t(i)];
            const float left = row[std::size_t(c.lower)];
            const float right = c.upperWeight > 0.0f ? row[std::size_t(c.lower) + 1] : left;
            out[i] = storedFrom<T>(kernels::linearBlend(left, c.upperWeight, right));
        }
    }

    // Refined slices [first, end): the scratch is made once for them (a fresh megabyte per
    // slice would cost its page faults anew).
    void refineSlices(std::size_t first, std::size_t end) const {
        if constexpr (std::is_integral_v<T>) { // where runs of equal voxels may be copied
            if (dims.x == sourceDims.x && dims.y == sourceDims.y) {
                refineAlongSlicesOnly(first, end);
                return;
            }
        }
        std::vector<float> plane(std::size_t(sourceDims.x) * std::size_t(sourceDims.y));
        std::vector<float> row(std::size_t(sourceDims.x));
        GapTangents tangents;
        const bool inPlaneAsIs = dims.x == sourceDims.x && dims.y == sourceDims.y;
        for (std::size_t k = first; k < end; ++k) {
            T* slice = target + std::size_t(dims.x) * std::size_t(dims.y) * k;
            if (inPlaneAsIs) { // split along k only: the plane is the slice (the same values)
                blendPlane(int(k), tangents, [slice](std::size_t v, float value) {
                    slice[v] = storedFrom<T>(value);
                });
                continue;
            }
            blendPlane(int(k), tangents,
                       [&plane](std::size_t v, float value) { plane[v] = value; });
            for (int j = 0; j < dims.y; ++j)
                refineRow(plane, j, row, slice + std::size_t(dims.x) * std::size_t(j));
        }
    }
};

} // namespace

glm::ivec3 oversampledDims(glm::ivec3 dims, glm::ivec3 factors) {
    return {oversampledCount(dims.x, factors.x), oversampledCount(dims.y, factors.y),
            oversampledCount(dims.z, factors.z)};
}

Volume oversampled(const Volume& volume, glm::ivec3 factors, unsigned threads,
                   SliceInterpolation alongSlices, const core::ImportLimits& limits) {
    if (factors.x < 1 || factors.y < 1 || factors.z < 1)
        throw core::Error("oversampling", "factors must be at least 1");
    const glm::ivec3 dims = oversampledDims(volume.dims(), factors);
    checkVolumeAllocation(dims, volume.voxelType(), limits, "oversampling",
                          "the oversampled volume");
    Volume result(dims, volume.voxelType(), volume.geometry().refined(factors, volume.dims().z));
    result.setValueMapping(volume.valueMapping());
    result.setDescription(volume.description());
    const std::vector<Blend> alongI = blendsAlong(volume.dims().x, factors.x);
    const std::vector<Blend> alongJ = blendsAlong(volume.dims().y, factors.y);
    const std::vector<Blend> alongK = blendsAlong(volume.dims().z, factors.z);
    const bool monotoneK = alongSlices == SliceInterpolation::MonotoneCubic && volume.dims().z > 2;
    dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        const SliceRefiner<T> refiner{
            volume.dataAs<T>(), volume.dims(),     dims, alongI, alongJ, alongK,
            monotoneK,          result.dataAs<T>()};
        // Runs of a few slices each: enough runs to balance the threads, few scratch planes.
        const std::size_t slices = std::size_t(dims.z);
        const std::size_t runs = 8 * std::size_t(core::workerCount());
        core::parallelForRanges(
            slices, (slices + runs - 1) / runs,
            [&](std::size_t begin, std::size_t end) { refiner.refineSlices(begin, end); }, threads);
    });
    return result;
}

void refineBetweenSlices(Volume& field, int factor, unsigned threads,
                         SliceInterpolation alongSlices) {
    const glm::ivec3 dims = field.dims();
    if (factor < 1 || (dims.z - 1) % factor != 0)
        throw core::Error("oversampling", "the field's slices are not the originals' every " +
                                              std::to_string(factor) + " slices");
    if (factor == 1 || dims.z < 2)
        return;
    const glm::ivec3 originalDims(dims.x, dims.y, (dims.z - 1) / factor + 1);
    const std::vector<Blend> alongI = blendsAlong(dims.x, 1);
    const std::vector<Blend> alongJ = blendsAlong(dims.y, 1);
    const std::vector<Blend> alongK = blendsAlong(originalDims.z, factor);
    const bool monotoneK = alongSlices == SliceInterpolation::MonotoneCubic && originalDims.z > 2;
    dispatchVoxelType(field.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        if constexpr (!std::is_integral_v<T>) {
            throw core::Error("oversampling", "refining in place takes integer voxels");
        } else {
            T* data = field.dataAs<T>();
            SliceRefiner<T> refiner{data,   originalDims, dims,      alongI,
                                    alongJ, alongK,       monotoneK, data};
            refiner.sourceStride = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(factor);
            // A gap a run: its refined slices read only the original slices, which no run writes.
            core::parallelFor(
                std::size_t(originalDims.z - 1),
                [&](std::size_t gap) {
                    refiner.refineGap(int(gap), gap * std::size_t(factor) + 1,
                                      (gap + 1) * std::size_t(factor));
                },
                threads);
        }
    });
}

} // namespace lw::volume
