#include "lw/volume/slice_distance.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace lw::volume {
namespace {

constexpr float kNoSeed = std::numeric_limits<float>::infinity();

// One slice's nearest contour points: per pixel the vector (in pixels) from it to the nearest
// point where the grey values cross the iso-value, and that vector's squared length in mm^2.
class SliceDistanceField {
public:
    SliceDistanceField(int width, int height, double spacingI, double spacingJ)
        : m_width(width), m_height(height), m_scaleI(float(spacingI * spacingI)),
          m_scaleJ(float(spacingJ * spacingJ)),
          m_nearest(std::size_t(width) * std::size_t(height), Nearest{0.0f, 0.0f, kNoSeed}) {}

    // The crossings along rows and columns, where linear interpolation puts the contour: both
    // pixels of a crossing pair get the vector to it.
    void seed(const std::vector<float>& above) {
        for (int y = 0; y < m_height; ++y)
            for (int x = 0; x < m_width; ++x) {
                const std::size_t p = at(x, y);
                if (x + 1 < m_width)
                    seedPair(above, p, p + 1, 1.0f, 0.0f);
                if (y + 1 < m_height)
                    seedPair(above, p, p + std::size_t(m_width), 0.0f, 1.0f);
            }
    }

    // Danielsson's sequential passes: each pixel takes the nearest point its neighbours carry,
    // first down the slice (left, up-left, up, up-right; then right), then up it (right,
    // down-right, down, down-left; then left).
    void propagate() {
        for (int y = 0; y < m_height; ++y)
            sweepRow(y, -1);
        for (int y = m_height - 1; y >= 0; --y)
            sweepRow(y, +1);
    }

    // Forget every contour point, for the next slice.
    void reset() { std::fill(m_nearest.begin(), m_nearest.end(), Nearest{0.0f, 0.0f, kNoSeed}); }

    // mm to the contour, or infinity where the slice has none.
    float distance(std::size_t p) const { return std::sqrt(m_nearest[p].squared); }

private:
    struct Nearest {
        float dx, dy;  // pixels to the nearest contour point
        float squared; // its distance squared, mm^2
    };

    std::size_t at(int x, int y) const {
        return std::size_t(y) * std::size_t(m_width) + std::size_t(x);
    }

    void offer(Nearest& here, float vx, float vy) const {
        const float squared = m_scaleI * vx * vx + m_scaleJ * vy * vy;
        if (squared < here.squared)
            here = {vx, vy, squared};
    }

    // `above` holds value - iso; p and q are neighbours, q = p + (stepX, stepY).
    void seedPair(const std::vector<float>& above, std::size_t p, std::size_t q, float stepX,
                  float stepY) {
        const float a = above[p];
        const float b = above[q];
        if ((a >= 0.0f) == (b >= 0.0f))
            return;
        const float t = a / (a - b); // in [0, 1]: where the straight line from a to b is zero
        offer(m_nearest[p], t * stepX, t * stepY);
        offer(m_nearest[q], (t - 1.0f) * stepX, (t - 1.0f) * stepY);
    }

    void from(Nearest& here, const Nearest& neighbour, float offsetX, float offsetY) const {
        if (neighbour.squared != kNoSeed)
            offer(here, neighbour.dx + offsetX, neighbour.dy + offsetY);
    }

    // One row of a pass: `dy` -1 takes from the row above (the pass down), +1 from the row below.
    void sweepRow(int y, int dy) {
        Nearest* row = m_nearest.data() + at(0, y);
        const int other = y + dy;
        const Nearest* near =
            other >= 0 && other < m_height ? m_nearest.data() + at(0, other) : nullptr;
        const float oy = float(dy);
        const int last = m_width - 1;
        for (int x = 0; x <= last; ++x) {
            Nearest& here = row[dy < 0 ? x : last - x];
            const int nx = dy < 0 ? x : last - x;
            const int back = dy < 0 ? -1 : 1; // the neighbour this sweep has done already
            if (nx + back >= 0 && nx + back <= last)
                from(here, row[nx + back], float(back), 0.0f);
            if (near) {
                from(here, near[nx], 0.0f, oy);
                if (nx > 0)
                    from(here, near[nx - 1], -1.0f, oy);
                if (nx < last)
                    from(here, near[nx + 1], 1.0f, oy);
            }
        }
        for (int x = 0; x < last; ++x) { // back the other way: the side not yet taken
            const int nx = dy < 0 ? last - 1 - x : x + 1;
            const int ahead = dy < 0 ? 1 : -1;
            from(row[nx], row[nx + ahead], float(ahead), 0.0f);
        }
    }

    int m_width;
    int m_height;
    float m_scaleI;
    float m_scaleJ;
    std::vector<Nearest> m_nearest;
};

std::int16_t storedDistance(float mm, bool inside, double limitMm) {
    const double limited = std::min(double(mm), limitMm);
    return std::int16_t(std::lround((inside ? limited : -limited) * kSliceDistanceStepsPerMm));
}

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
                                     volume.geometry().spacingJ());
            for (std::size_t k = begin; k < end; ++k) {
                aboveIso(volume, int(k), iso, above);
                field.reset();
                field.seed(above);
                field.propagate();
                std::int16_t* out = target + plane * k;
                for (std::size_t p = 0; p < plane; ++p)
                    out[p] = storedDistance(field.distance(p), above[p] >= 0.0f, limitMm);
            }
        },
        threads);
    return result;
}

} // namespace lw::volume
