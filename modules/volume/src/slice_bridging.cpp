#include "lw/volume/slice_bridging.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/thin_shell_bridge.h"
#include "lw/volume/slice_distance.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace lw::volume {
namespace {

// Rows of one gap an item of the parallel loop takes (its candidate mask is made once an item).
constexpr int kRowsPerItem = 16;
// int16 voxels in a 64-byte cache line.
constexpr int kVoxelsPerCacheLine = 32;

// thinShellCandidate over a row of pixels into a mask (vector code: the test has no branch).
void markCandidates(const std::int16_t* lower, const std::int16_t* upper, int count, int limitSteps,
                    std::uint8_t* candidate) {
    for (int x = 0; x < count; ++x)
        candidate[x] = std::uint8_t(kernels::thinShellCandidate(lower[x], upper[x], limitSteps));
}

// One row of one gap: the slices between raised to the wall slid from one cut to the other where
// an inner pixel lies between two thin cuts (never lowered). The candidates are found eight at a
// time from the mask.
void bridgeRow(const kernels::ThinShellSlices& slices, std::int16_t* between, std::size_t plane,
               int factor, int y, std::vector<std::uint8_t>& candidate) {
    const std::size_t row = std::size_t(y) * std::size_t(slices.width);
    const int inner = slices.width - 2;
    markCandidates(slices.lower + row + 1, slices.upper + row + 1, inner, int(slices.limitSteps),
                   candidate.data());
    // The candidates' first reads of the slices between (their voxels, compared before any
    // raise) waited on memory: the row of each is asked for ahead, a cache line at a time.
    for (int step = 1; step < factor; ++step)
        for (int x = 0; x < slices.width; x += kVoxelsPerCacheLine)
            __builtin_prefetch(between + plane * std::size_t(step - 1) + row + std::size_t(x), 1);
    const auto bridge = [&](int n) {
        const int x = n + 1;
        kernels::bridgeThinShellCandidate(slices, between, plane, factor, x, y,
                                          float(slices.lower[row + std::size_t(x)]),
                                          float(slices.upper[row + std::size_t(x)]));
    };
    int n = 0;
    for (; n + 8 <= inner; n += 8) {
        std::uint64_t word;
        std::memcpy(&word, candidate.data() + n, 8);
        for (; word != 0; word &= word - 1)
            bridge(n + std::countr_zero(word) / 8); // little-endian: byte order is bit order
    }
    for (; n < inner; ++n)
        if (candidate[std::size_t(n)] != 0)
            bridge(n);
}

} // namespace

void bridgeThinWalls(Volume& field, int factor, double limitMm, double widthMm, unsigned threads) {
    const glm::ivec3 dims = field.dims();
    if (field.voxelType() != VoxelType::Int16)
        throw core::Error("thick slices", "bridging thin walls takes an int16 field");
    if (factor < 1 || (dims.z - 1) % factor != 0)
        throw core::Error("thick slices", "the field's slices are not the originals' every " +
                                              std::to_string(factor) + " slices");
    if (factor < 2 || !(widthMm > 0.0) || dims.x < 3 || dims.y < 3)
        return;
    const kernels::ThinShellSlices s = kernels::thinShellSlices(
        dims.x, dims.y, field.geometry().spacingI(), field.geometry().spacingJ(),
        kSliceDistanceStepsPerMm, limitMm, widthMm);
    std::int16_t* voxels = field.dataAs<std::int16_t>();
    const std::size_t plane = std::size_t(dims.x) * std::size_t(dims.y);
    const int gaps = (dims.z - 1) / factor;
    const int rows = dims.y - 2;
    const int itemsPerGap = (rows + kRowsPerItem - 1) / kRowsPerItem;
    // An item is a band of rows of a gap: it reads the gap's two slices, which no item writes,
    // and writes only its own rows of the slices between (the CUDA kernel's work per pixel).
    core::parallelFor(
        std::size_t(gaps) * std::size_t(itemsPerGap),
        [&](std::size_t item) {
            const int gap = int(item / std::size_t(itemsPerGap));
            const int first = 1 + int(item % std::size_t(itemsPerGap)) * kRowsPerItem;
            const int end = first + kRowsPerItem < dims.y - 1 ? first + kRowsPerItem : dims.y - 1;
            kernels::ThinShellSlices slices = s;
            slices.lower = voxels + plane * std::size_t(gap) * std::size_t(factor);
            slices.upper = slices.lower + plane * std::size_t(factor);
            std::int16_t* between = voxels + plane * (std::size_t(gap) * std::size_t(factor) + 1);
            std::vector<std::uint8_t> candidate(std::size_t(dims.x));
            for (int y = first; y < end; ++y)
                bridgeRow(slices, between, plane, factor, y, candidate);
        },
        threads);
}

} // namespace lw::volume
