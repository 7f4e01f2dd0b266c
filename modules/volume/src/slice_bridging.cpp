#include "lw/volume/slice_bridging.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/thin_shell_bridge.h"
#include "lw/volume/slice_distance.h"

#include <cstdint>
#include <string>

namespace lw::volume {
namespace {

// One row of one gap: the inner pixels' cuts, and the slices between raised to the wall slid
// from one cut to the other (never lowered).
void bridgeRow(const kernels::ThinShellSlices& slices, std::int16_t* between, std::size_t plane,
               int factor, int y) {
    const std::size_t row = std::size_t(y) * std::size_t(slices.width);
    for (int x = 1; x + 1 < slices.width; ++x) {
        kernels::ThinShellCuts cuts{};
        if (kernels::thinShellCuts(slices, x, y, cuts))
            kernels::raiseToSlidWall(between, plane, row + std::size_t(x), factor, slices, cuts);
    }
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
    // An item is a row of a gap: it reads the gap's two slices, which no item writes, and writes
    // only its own row of the slices between (the CUDA kernel's work per pixel, a row at a time).
    core::parallelFor(
        std::size_t(gaps) * std::size_t(rows),
        [&](std::size_t item) {
            const int gap = int(item / std::size_t(rows));
            const int y = 1 + int(item % std::size_t(rows));
            kernels::ThinShellSlices slices = s;
            slices.lower = voxels + plane * std::size_t(gap) * std::size_t(factor);
            slices.upper = slices.lower + plane * std::size_t(factor);
            bridgeRow(slices, voxels + plane * (std::size_t(gap) * std::size_t(factor) + 1), plane,
                      factor, y);
        },
        threads);
}

} // namespace lw::volume
