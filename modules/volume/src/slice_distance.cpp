#include "lw/volume/slice_distance.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/slice_field_rules.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <string>
#include <type_traits>
#include <vector>

namespace lw::volume {
namespace {

using kernels::crossesIso;
using kernels::crossingOffset;
using kernels::nearTerm;
using kernels::squaredReachingLimit;
using kernels::stepTerm;

constexpr float kNoCrossing = std::numeric_limits<float>::infinity();

// A slice's values less the iso-value as the shared arithmetic has them, float(real - iso), and
// which pixels are inside (>= 0). For 8- and 16-bit voxels a table holds every stored value's
// (made once per field), and since the mapping is affine the inside values are one range of
// stored values: a pixel's sign is then two integer comparisons, with no arithmetic per pixel.
template <typename T> class AboveIso {
public:
    static constexpr bool kTabled = std::is_integral_v<T> && sizeof(T) <= 2;

    AboveIso(ValueMapping mapping, double iso) : m_mapping(mapping), m_iso(iso) {
        if constexpr (kTabled) {
            m_table.resize(std::size_t(1) << (8 * sizeof(T)));
            for (std::size_t n = 0; n < m_table.size(); ++n)
                m_table[n] = compute(T(long(n) + kLowest));
            findInsideRange();
        }
    }

    float operator()(T stored) const {
        if constexpr (kTabled)
            return m_table[std::size_t(long(stored) - kLowest)];
        else
            return compute(stored);
    }

    void insideOf(const T* slice, std::size_t count, std::uint8_t* inside) const {
        if constexpr (kTabled) {
            if (m_oneRange) {
                const int first = m_first, last = m_last;
                for (std::size_t p = 0; p < count; ++p)
                    inside[p] = std::uint8_t((int(slice[p]) >= first) & (int(slice[p]) <= last));
                return;
            }
        }
        for (std::size_t p = 0; p < count; ++p)
            inside[p] = (*this)(slice[p]) >= 0.0f;
    }

private:
    static constexpr long kLowest = long(std::numeric_limits<T>::lowest());

    float compute(T stored) const { return float(m_mapping.toReal(double(stored)) - m_iso); }

    // [m_first, m_last]: the stored values that are inside, if they are one range (an empty
    // range is first > last). Not one range only for a mapping that is not finite.
    void findInsideRange() {
        long first = 0, last = -1, runs = 0;
        bool previous = false;
        for (std::size_t n = 0; n < m_table.size(); ++n) {
            const bool inside = m_table[n] >= 0.0f;
            if (inside && !previous) {
                ++runs;
                first = long(n) + kLowest;
            }
            if (inside)
                last = long(n) + kLowest;
            previous = inside;
        }
        m_oneRange = runs <= 1;
        m_first = runs == 0 ? 1 : int(first);
        m_last = runs == 0 ? 0 : int(last);
    }

    ValueMapping m_mapping;
    double m_iso;
    std::vector<float> m_table; // kTabled: every stored value's, from the type's lowest
    bool m_oneRange = false;
    int m_first = 1;
    int m_last = 0;
};

// Half-open runs [begin, end) of pixels along a row.
struct Span {
    int begin;
    int end;
};

// Where a slice's contour crosses a row between pixels x and x + 1 (at `at`, in pixels along the
// row), or a column between rows y and y + 1 (at `at` along the column).
struct Crossing {
    int index; // x for a row crossing, y for a column crossing
    float at;
};

// The positions where adjacent bytes of `inside` differ, first[n] against second[n] for n in
// [0, count): eight at a time, since most pixels lie away from any contour.
template <typename Found>
void eachDifference(const std::uint8_t* first, const std::uint8_t* second, int count,
                    Found&& found) {
    int n = 0;
    for (; n + 8 <= count; n += 8) {
        std::uint64_t a, b;
        std::memcpy(&a, first + n, 8);
        std::memcpy(&b, second + n, 8);
        for (std::uint64_t differ = a ^ b; differ != 0; differ &= differ - 1)
            found(n + std::countr_zero(differ) / 8); // little-endian: byte order is bit order
    }
    for (; n < count; ++n)
        if (first[n] != second[n])
            found(n);
}

// One slice's squared distances (mm^2) to its crossings (kernels/slice_field_rules.h): per pixel
// the nearest row crossing along its row and the nearest column crossing along its column, then
// the minimum over the rows (columns) within the limit's reach of scaleJ (scaleI) * rows^2 plus
// those. Distances beyond the limit are not needed (they are stored as the limit), which is what
// keeps it fast: a slice of CT holds its contours in narrow bands (a skull's ring), so
//   - the crossings are found eight pixels at a time, and each is spread only over the pixels
//     within reach (+ 1) of it, where a scan would visit every pixel;
//   - a minimum takes only candidates from those pixels, where a full one would cost 2 * reach + 1
//     passes over every pixel;
//   - a row no candidate reaches is left at "beyond the limit" without a minimum.
// Every candidate within the limit is still taken, with the same arithmetic, so the result is the
// exact minimum, bit for bit what a scan of every pixel (or the GPU's window search) gives.
class SliceDistanceField {
public:
    SliceDistanceField(int width, int height, double spacingI, double spacingJ, double limitMm)
        : m_width(width), m_height(height), m_scaleI(float(spacingI * spacingI)),
          m_scaleJ(float(spacingJ * spacingJ)), m_reaching(squaredReachingLimit(limitMm)),
          m_reachI(kernels::sliceDistanceReach(limitMm, spacingI, width)),
          m_reachJ(kernels::sliceDistanceReach(limitMm, spacingJ, height)), m_inside(plane()),
          m_rowNear(plane()), m_columnNear(plane()), m_squared(std::size_t(width)),
          m_stepI(std::size_t(m_reachI) + 1), m_stepJ(std::size_t(m_reachJ) + 1),
          m_rowSpans(std::size_t(height)), m_rowCrossings(std::size_t(height)),
          m_columnTouched(std::size_t(height)),
          m_insideLimit(
              kernels::storedSliceDistance(kNoCrossing, true, limitMm, kSliceDistanceStepsPerMm)),
          m_outsideLimit(
              kernels::storedSliceDistance(kNoCrossing, false, limitMm, kSliceDistanceStepsPerMm)),
          m_limitMm(limitMm) {
        for (int n = 0; n <= m_reachI; ++n)
            m_stepI[std::size_t(n)] = stepTerm(m_scaleI, n);
        for (int n = 0; n <= m_reachJ; ++n)
            m_stepJ[std::size_t(n)] = stepTerm(m_scaleJ, n);
        for (int n = -m_reachI; n <= m_reachI; ++n)
            m_stepAcross.push_back(m_stepI[std::size_t(std::abs(n))]);
    }

    // The stored distances of slice `values` (stored voxels; `above` says their values less the
    // iso-value) into `out`, a row at a time: its squared distances (mm^2) to the row crossings
    // within reach, then to the column crossings, then stored (kernels/slice_field_rules.h).
    template <typename T>
    void compute(const T* values, const AboveIso<T>& above, std::int16_t* out) {
        above.insideOf(values, plane(), m_inside.data());
        const auto valueAbove = [&](std::size_t p) { return above(values[p]); };
        findRowCrossings(valueAbove);
        nearestAlongRows();
        nearestAlongColumns(valueAbove);
        for (int y = 0; y < m_height; ++y) {
            const bool reachedByRows = minimumOverRows(y);
            const bool reachedByColumns = minimumOverColumns(y);
            storeRow(y, reachedByRows || reachedByColumns, out + at(0, y));
        }
    }

private:
    std::size_t plane() const { return std::size_t(m_width) * std::size_t(m_height); }
    std::size_t at(int x, int y) const {
        return std::size_t(y) * std::size_t(m_width) + std::size_t(x);
    }

    // The pixels a crossing between index and index + 1 can be nearer than the limit to, along
    // its axis: reach pixels cover the limit, one more is margin against rounding.
    static Span spreadOf(int index, int reach, int length) {
        return {std::max(0, index - reach - 1), std::min(length, index + reach + 2)};
    }

    template <typename ValueAbove> void findRowCrossings(const ValueAbove& valueAbove) {
        for (int y = 0; y < m_height; ++y) {
            std::vector<Crossing>& crossings = m_rowCrossings[std::size_t(y)];
            crossings.clear();
            const std::uint8_t* inside = m_inside.data() + at(0, y);
            eachDifference(inside, inside + 1, m_width - 1, [&](int x) {
                const float a = valueAbove(at(x, y)), b = valueAbove(at(x + 1, y));
                crossings.push_back({x, float(x) + crossingOffset(a, b)});
            });
        }
    }

    // Per pixel within reach of a row crossing, scaleI * (pixels along its row to the nearest)^2:
    // from each crossing, float(x) - at for one before the pixel, at - float(x) for one at or
    // after it -- the subtractions of a scan that keeps the last crossing before the pixel and the
    // first after it (nearTerm is monotone, so the minimum of the terms is the term of the
    // minimum). The row's spans say where they are; elsewhere the row is not read.
    void nearestAlongRows() {
        for (int y = 0; y < m_height; ++y) {
            std::vector<Span>& spans = m_rowSpans[std::size_t(y)];
            spans.clear();
            float* near = m_rowNear.data() + at(0, y);
            for (const Crossing& crossing : m_rowCrossings[std::size_t(y)]) {
                const Span spread = spreadOf(crossing.index, m_reachI, m_width);
                if (!spans.empty() && spread.begin <= spans.back().end) {
                    std::fill(near + spans.back().end, near + spread.end, kNoCrossing);
                    spans.back().end = std::max(spans.back().end, spread.end);
                } else {
                    std::fill(near + spread.begin, near + spread.end, kNoCrossing);
                    spans.push_back(spread);
                }
                for (int x = spread.begin; x < spread.end; ++x) {
                    const float along =
                        crossing.index < x ? float(x) - crossing.at : crossing.at - float(x);
                    near[x] = std::min(near[x], nearTerm(m_scaleI, along));
                }
            }
        }
    }

    // The same for the column crossings, spread up and down their column into m_columnNear
    // (beyond the limit elsewhere).
    template <typename ValueAbove> void nearestAlongColumns(const ValueAbove& valueAbove) {
        std::fill(m_columnNear.begin(), m_columnNear.end(), kNoCrossing);
        std::fill(m_columnTouched.begin(), m_columnTouched.end(), char(0));
        for (int y = 0; y + 1 < m_height; ++y) {
            const std::uint8_t* upper = m_inside.data() + at(0, y);
            eachDifference(upper, upper + m_width, m_width, [&](int x) {
                const float at = float(y) + crossingOffset(valueAbove(this->at(x, y)),
                                                           valueAbove(this->at(x, y + 1)));
                const Span spread = spreadOf(y, m_reachJ, m_height);
                for (int row = spread.begin; row < spread.end; ++row) {
                    const float along = y < row ? float(row) - at : at - float(row);
                    float& near = m_columnNear[this->at(x, row)];
                    near = std::min(near, nearTerm(m_scaleJ, along));
                    m_columnTouched[std::size_t(row)] = 1;
                }
            });
        }
    }

    // Row y's squared distances to the row crossings into m_squared: the minimum over the rows
    // within reach, each over its spans. Whether any span was there.
    bool minimumOverRows(int y) {
        float* out = m_squared.data();
        std::fill(out, out + m_width, kNoCrossing);
        bool reached = false;
        const int first = std::max(0, y - m_reachJ);
        const int last = std::min(m_height - 1, y + m_reachJ);
        for (int r = first; r <= last; ++r) {
            const float step = m_stepJ[std::size_t(std::abs(r - y))];
            const float* near = m_rowNear.data() + at(0, r);
            for (const Span& span : m_rowSpans[std::size_t(r)]) {
                reached = true;
                for (int x = span.begin; x < span.end; ++x)
                    out[x] = std::min(out[x], near[x] + step);
            }
        }
        return reached;
    }

    // ... and then the column crossings': each pixel of the row nearer than the limit to one
    // (few: a contour crosses few columns where it runs along them) spreads its term plus
    // scaleI * n^2 over the pixels n <= reach columns away -- the minimum over the columns within
    // reach, taken from the side of the candidates. Whether there was one.
    bool minimumOverColumns(int y) {
        if (!m_columnTouched[std::size_t(y)])
            return false;
        float* out = m_squared.data();
        const float* near = m_columnNear.data() + at(0, y);
        const float* across = m_stepAcross.data() + m_reachI; // across[n] for |n| <= reach
        bool reached = false;
        const auto spread = [&](int x) {
            reached = true;
            const float term = near[x];
            const int first = std::max(0, x - m_reachI);
            const int end = std::min(m_width, x + m_reachI + 1);
            for (int to = first; to < end; ++to)
                out[to] = std::min(out[to], term + across[to - x]);
        };
        int block = 0;
        for (; block + kStoreBlock <= m_width; block += kStoreBlock)
            if (anyNearer<kStoreBlock>(near + block))
                for (int x = block; x < block + kStoreBlock; ++x)
                    if (near[x] < m_reaching)
                        spread(x);
        for (; block < m_width; ++block)
            if (near[block] < m_reaching)
                spread(block);
        return reached;
    }

    // Row y's stored distances from m_squared: the limit first, signed by the side each pixel is
    // on, then the pixels nearer than it, looked for a block at a time (a row no candidate
    // reached has none).
    void storeRow(int y, bool reached, std::int16_t* target) const {
        const std::uint8_t* inside = m_inside.data() + at(0, y);
        for (int x = 0; x < m_width; ++x)
            target[x] = inside[x] != 0 ? m_insideLimit : m_outsideLimit;
        if (!reached)
            return;
        const float* squared = m_squared.data();
        int block = 0;
        for (; block + kStoreBlock <= m_width; block += kStoreBlock)
            if (anyNearer<kStoreBlock>(squared + block))
                storeNearer<kStoreBlock>(squared + block, inside + block, target + block);
        for (; block < m_width; ++block)
            storeNearer<1>(squared + block, inside + block, target + block);
    }

    // Pixels storeRow looks at together: most lie beyond the limit, and a block with none nearer
    // is left at the limit after one comparison of each.
    static constexpr int kStoreBlock = 8;

    template <int Count> bool anyNearer(const float* squared) const {
        bool nearer = false;
        for (int x = 0; x < Count; ++x)
            nearer |= squared[x] < m_reaching;
        return nearer;
    }

    template <int Count>
    void storeNearer(const float* squared, const std::uint8_t* inside, std::int16_t* target) const {
        for (int x = 0; x < Count; ++x)
            if (squared[x] < m_reaching)
                target[x] = kernels::storedSliceDistance(squared[x], inside[x] != 0, m_limitMm,
                                                         kSliceDistanceStepsPerMm);
    }

    int m_width;
    int m_height;
    float m_scaleI;
    float m_scaleJ;
    float m_reaching;                   // squared distances from here on are stored as the limit
    int m_reachI;                       // pixels along i (columns) that the limit reaches
    int m_reachJ;                       // pixels along j (rows)
    std::vector<std::uint8_t> m_inside; // 1 where the value is at least the iso-value
    std::vector<float> m_rowNear;    // scaleI * (pixels to the row's nearest crossing)^2, in spans
    std::vector<float> m_columnNear; // scaleJ * (pixels to the column's nearest crossing)^2
    std::vector<float> m_squared;    // one row's squared distances
    std::vector<float> m_stepI;      // scaleI * n^2
    std::vector<float> m_stepJ;
    std::vector<float> m_stepAcross;                   // scaleI * n^2 for n in [-reachI, reachI]
    std::vector<std::vector<Span>> m_rowSpans;         // per row, where m_rowNear is written
    std::vector<std::vector<Crossing>> m_rowCrossings; // per row, in order along it
    std::vector<char> m_columnTouched; // per row, whether a column crossing reaches it
    std::int16_t m_insideLimit;        // the limit as stored, inside and outside
    std::int16_t m_outsideLimit;
    double m_limitMm;
};

// Scratch fields for the threads of one call, each used by one thread at a time.
class FieldPool {
public:
    explicit FieldPool(std::function<std::unique_ptr<SliceDistanceField>()> make)
        : m_make(std::move(make)) {}

    std::unique_ptr<SliceDistanceField> take() {
        {
            const std::lock_guard lock(m_mutex);
            if (!m_free.empty()) {
                std::unique_ptr<SliceDistanceField> field = std::move(m_free.back());
                m_free.pop_back();
                return field;
            }
        }
        return m_make();
    }

    void giveBack(std::unique_ptr<SliceDistanceField> field) {
        const std::lock_guard lock(m_mutex);
        m_free.push_back(std::move(field));
    }

private:
    std::function<std::unique_ptr<SliceDistanceField>()> m_make;
    std::mutex m_mutex;
    std::vector<std::unique_ptr<SliceDistanceField>> m_free;
};

} // namespace

namespace {

void checkLimit(double limitMm) {
    if (!(limitMm > 0.0) || limitMm * kSliceDistanceStepsPerMm > 32767.0)
        throw core::Error("shape-based interpolation",
                          "the distance limit must lie in (0, " +
                              std::to_string(int(32767.0 / kSliceDistanceStepsPerMm)) + "] mm");
}

// Slice k of the distances into target + k * sliceStride.
void writeDistances(const Volume& volume, double iso, double limitMm, std::int16_t* target,
                    std::size_t sliceStride, unsigned threads) {
    const glm::ivec3 dims = volume.dims();
    dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        const AboveIso<T> above(volume.valueMapping(), iso);
        const T* source = volume.dataAs<T>();
        const std::size_t plane = std::size_t(dims.x) * std::size_t(dims.y);
        // Each run takes a scratch field from the pool and puts it back, so that there are as
        // many as threads at once, not as many as slices: a field's first touch of its planes
        // costs page faults. One slice a run, since slices differ in cost (a skull's cap against
        // its base).
        FieldPool pool([&] {
            return std::make_unique<SliceDistanceField>(dims.x, dims.y,
                                                        volume.geometry().spacingI(),
                                                        volume.geometry().spacingJ(), limitMm);
        });
        core::parallelFor(
            std::size_t(dims.z),
            [&](std::size_t k) {
                std::unique_ptr<SliceDistanceField> field = pool.take();
                field->compute(source + plane * k, above, target + sliceStride * k);
                pool.giveBack(std::move(field));
            },
            threads);
    });
}

} // namespace

Volume signedSliceDistance(const Volume& volume, double iso, double limitMm, unsigned threads,
                           const core::ImportLimits& limits) {
    checkLimit(limitMm);
    const glm::ivec3 dims = volume.dims();
    checkVolumeAllocation(dims, VoxelType::Int16, limits, "shape-based interpolation",
                          "the signed-distance copy");
    Volume result(dims, VoxelType::Int16, volume.geometry());
    result.setValueMapping({1.0 / kSliceDistanceStepsPerMm, iso});
    result.setDescription(volume.description());
    writeDistances(volume, iso, limitMm, result.dataAs<std::int16_t>(),
                   std::size_t(dims.x) * std::size_t(dims.y), threads);
    return result;
}

void writeSignedSliceDistance(const Volume& volume, double iso, double limitMm, int sliceStep,
                              Volume& field, unsigned threads) {
    checkLimit(limitMm);
    const glm::ivec3 dims = volume.dims();
    if (sliceStep < 1 || field.voxelType() != VoxelType::Int16 ||
        field.dims() != glm::ivec3(dims.x, dims.y, (dims.z - 1) * sliceStep + 1))
        throw core::Error("shape-based interpolation",
                          "the field to write is not of this volume's size and slice step");
    writeDistances(volume, iso, limitMm, field.dataAs<std::int16_t>(),
                   std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(sliceStep), threads);
}

} // namespace lw::volume
