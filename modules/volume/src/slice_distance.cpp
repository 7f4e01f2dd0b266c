#include "lw/volume/slice_distance.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/slice_field_rules.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace lw::volume {
namespace {

using kernels::crossesIso;
using kernels::crossingOffset;
using kernels::nearTerm;
using kernels::stepTerm;

constexpr float kNoCrossing = std::numeric_limits<float>::infinity();

// One slice's squared distances (mm^2) to its crossings, made separably
// (kernels/slice_field_rules.h): the row crossings' nearest along each row, then the minimum over
// the rows within reach; the column crossings the same way with the axes swapped. Distances
// beyond the limit are not needed (they are stored as the limit), so each minimum looks only as
// many pixels away as the limit reaches -- which is what keeps it linear in the slice's size.
class SliceDistanceField {
public:
    SliceDistanceField(int width, int height, double spacingI, double spacingJ, double limitMm)
        : m_width(width), m_height(height), m_scaleI(float(spacingI * spacingI)),
          m_scaleJ(float(spacingJ * spacingJ)),
          m_reachI(kernels::sliceDistanceReach(limitMm, spacingI, width)),
          m_reachJ(kernels::sliceDistanceReach(limitMm, spacingJ, height)), m_rowNear(plane()),
          m_columnNear(plane()), m_squared(plane()), m_stepI(std::size_t(m_reachI) + 1),
          m_stepJ(std::size_t(m_reachJ) + 1), m_rowHasCrossing(std::size_t(height)) {
        for (int n = 0; n <= m_reachI; ++n)
            m_stepI[std::size_t(n)] = stepTerm(m_scaleI, n);
        for (int n = 0; n <= m_reachJ; ++n)
            m_stepJ[std::size_t(n)] = stepTerm(m_scaleJ, n);
    }

    // `above` holds the slice's values less the iso-value; afterwards squared(p) is pixel p's
    // squared distance to the nearest crossing, or more than the limit's square.
    void compute(const std::vector<float>& above) {
        nearestAlongRows(above);
        nearestAlongColumns(above);
        for (int y = 0; y < m_height; ++y)
            minimumOverRows(y);
        for (int y = 0; y < m_height; ++y)
            minimumOverColumns(y);
    }

    float squared(std::size_t p) const { return m_squared[p]; }

private:
    std::size_t plane() const { return std::size_t(m_width) * std::size_t(m_height); }
    std::size_t at(int x, int y) const {
        return std::size_t(y) * std::size_t(m_width) + std::size_t(x);
    }

    // Per pixel, scaleI * (pixels along its row to the row's nearest crossing)^2: the crossings
    // lie in order along the row, so the nearest is the last one before the pixel or the first
    // one after it.
    void nearestAlongRows(const std::vector<float>& above) {
        for (int y = 0; y < m_height; ++y) {
            const float* values = above.data() + at(0, y);
            float* near = m_rowNear.data() + at(0, y);
            float before = -kNoCrossing;
            bool any = false;
            for (int x = 0; x < m_width; ++x) {
                near[x] = float(x) - before;
                if (x + 1 < m_width && crossesIso(values[x], values[x + 1])) {
                    before = float(x) + crossingOffset(values[x], values[x + 1]);
                    any = true;
                }
            }
            float after = kNoCrossing;
            for (int x = m_width - 1; x >= 0; --x) {
                if (x + 1 < m_width && crossesIso(values[x], values[x + 1]))
                    after = float(x) + crossingOffset(values[x], values[x + 1]);
                near[x] = nearTerm(m_scaleI, std::min(near[x], after - float(x)));
            }
            m_rowHasCrossing[std::size_t(y)] = any;
        }
    }

    // The same along the columns, a row at a time (the rows are contiguous): scaleJ * (pixels to
    // the column's nearest crossing)^2.
    void nearestAlongColumns(const std::vector<float>& above) {
        std::vector<float> crossing(std::size_t(m_width), -kNoCrossing);
        for (int y = 0; y < m_height; ++y) {
            float* near = m_columnNear.data() + at(0, y);
            for (int x = 0; x < m_width; ++x)
                near[x] = float(y) - crossing[std::size_t(x)];
            if (y + 1 < m_height)
                recordColumnCrossings(above, y, crossing);
        }
        std::fill(crossing.begin(), crossing.end(), kNoCrossing);
        for (int y = m_height - 1; y >= 0; --y) {
            if (y + 1 < m_height)
                recordColumnCrossings(above, y, crossing);
            float* near = m_columnNear.data() + at(0, y);
            for (int x = 0; x < m_width; ++x)
                near[x] =
                    nearTerm(m_scaleJ, std::min(near[x], crossing[std::size_t(x)] - float(y)));
        }
    }

    void recordColumnCrossings(const std::vector<float>& above, int y,
                               std::vector<float>& crossing) const {
        const float* upper = above.data() + at(0, y);
        const float* lower = upper + m_width;
        for (int x = 0; x < m_width; ++x)
            if (crossesIso(upper[x], lower[x]))
                crossing[std::size_t(x)] = float(y) + crossingOffset(upper[x], lower[x]);
    }

    // Row y's squared distances to the row crossings: the minimum over the rows within reach.
    void minimumOverRows(int y) {
        float* out = m_squared.data() + at(0, y);
        std::fill(out, out + m_width, kNoCrossing);
        const int first = std::max(0, y - m_reachJ);
        const int last = std::min(m_height - 1, y + m_reachJ);
        for (int r = first; r <= last; ++r) {
            if (!m_rowHasCrossing[std::size_t(r)])
                continue;
            const float step = m_stepJ[std::size_t(std::abs(r - y))];
            const float* near = m_rowNear.data() + at(0, r);
            for (int x = 0; x < m_width; ++x)
                out[x] = std::min(out[x], near[x] + step);
        }
    }

    // ... and then the column crossings': the minimum over the columns within reach.
    void minimumOverColumns(int y) {
        float* out = m_squared.data() + at(0, y);
        const float* near = m_columnNear.data() + at(0, y);
        for (int n = -m_reachI; n <= m_reachI; ++n) {
            const float step = m_stepI[std::size_t(std::abs(n))];
            const int first = std::max(0, -n);
            const int end = std::min(m_width, m_width - n);
            for (int x = first; x < end; ++x)
                out[x] = std::min(out[x], near[x + n] + step);
        }
    }

    int m_width;
    int m_height;
    float m_scaleI;
    float m_scaleJ;
    int m_reachI;                    // pixels along i (columns) that the limit reaches
    int m_reachJ;                    // pixels along j (rows)
    std::vector<float> m_rowNear;    // scaleI * (pixels to the row's nearest crossing)^2
    std::vector<float> m_columnNear; // scaleJ * (pixels to the column's nearest crossing)^2
    std::vector<float> m_squared;
    std::vector<float> m_stepI; // scaleI * n^2
    std::vector<float> m_stepJ;
    std::vector<char> m_rowHasCrossing;
};

// Slice k's real values less the iso-value, as float, into `above` (a plane's size).
void aboveIso(const Volume& volume, int k, double iso, std::vector<float>& above) {
    const glm::ivec3 dims = volume.dims();
    const std::size_t plane = std::size_t(dims.x) * std::size_t(dims.y);
    const ValueMapping mapping = volume.valueMapping();
    dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        const T* slice = volume.dataAs<T>() + plane * std::size_t(k);
        for (std::size_t v = 0; v < plane; ++v)
            above[v] = float(mapping.toReal(double(slice[v])) - iso);
    });
}

} // namespace

Volume signedSliceDistance(const Volume& volume, double iso, double limitMm, unsigned threads,
                           const core::ImportLimits& limits) {
    if (!(limitMm > 0.0) || limitMm * kSliceDistanceStepsPerMm > 32767.0)
        throw core::Error("shape-based interpolation",
                          "the distance limit must lie in (0, " +
                              std::to_string(int(32767.0 / kSliceDistanceStepsPerMm)) + "] mm");
    const glm::ivec3 dims = volume.dims();
    checkVolumeAllocation(dims, VoxelType::Int16, limits, "shape-based interpolation",
                          "the signed-distance copy");
    Volume result(dims, VoxelType::Int16, volume.geometry());
    result.setValueMapping({1.0 / kSliceDistanceStepsPerMm, iso});
    result.setDescription(volume.description());
    const std::size_t plane = std::size_t(dims.x) * std::size_t(dims.y);
    std::int16_t* target = result.dataAs<std::int16_t>();
    // Runs of slices, each with its own scratch (made once per run, not per slice).
    const std::size_t slices = std::size_t(dims.z);
    const std::size_t runs = 4 * std::size_t(core::workerCount());
    core::parallelForRanges(
        slices, (slices + runs - 1) / runs,
        [&](std::size_t begin, std::size_t end) {
            std::vector<float> above(plane);
            SliceDistanceField field(dims.x, dims.y, volume.geometry().spacingI(),
                                     volume.geometry().spacingJ(), limitMm);
            for (std::size_t k = begin; k < end; ++k) {
                aboveIso(volume, int(k), iso, above);
                field.compute(above);
                std::int16_t* out = target + plane * k;
                for (std::size_t p = 0; p < plane; ++p)
                    out[p] = kernels::storedSliceDistance(field.squared(p), above[p] >= 0.0f,
                                                          limitMm, kSliceDistanceStepsPerMm);
            }
        },
        threads);
    return result;
}

} // namespace lw::volume
