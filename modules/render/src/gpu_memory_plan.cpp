#include "lw/render/gpu_memory_plan.h"

#include "lw/core/parallel.h"

#include <algorithm>
#include <cstdint>
#include <limits>

namespace lw::render {

std::string_view residencyName(GpuResidency residency) {
    switch (residency) {
    case GpuResidency::WholeVolume:
        return "whole volume on the GPU";
    case GpuResidency::Slabs:
        return "slabs streamed to the GPU";
    case GpuResidency::Cpu:
        return "CPU";
    }
    return "?";
}

std::size_t defaultGpuBudget(std::size_t freeBytes) {
    const std::size_t margin = std::max<std::size_t>(std::size_t(512) << 20, freeBytes / 10);
    return freeBytes > margin ? freeBytes - margin : 0;
}

GpuResidency chooseResidency(glm::ivec3 dims, std::size_t voxelBytes, std::size_t budget,
                             std::size_t reservedBytes, bool chunkedRequested) {
    if (chunkedRequested)
        return GpuResidency::Slabs;
    const double volumeBytes =
        double(dims.x) * double(dims.y) * double(dims.z) * double(voxelBytes);
    const double needed = volumeBytes * (1.0 + kWholeVolumeOverhead) + double(reservedBytes);
    return needed <= double(budget) ? GpuResidency::WholeVolume : GpuResidency::Slabs;
}

std::vector<glm::ivec2> planSlabs(glm::ivec3 dims, std::size_t voxelBytes, std::size_t budget,
                                  std::size_t reservedBytes, int maxLayers) {
    std::vector<glm::ivec2> slabs;
    const int layers = dims.z - 1;
    if (layers < 1 || dims.x < 1 || dims.y < 1)
        return slabs;
    const double sliceBytes = double(dims.x) * double(dims.y) * double(voxelBytes);
    const double available = budget > reservedBytes ? double(budget - reservedBytes) : 0.0;
    // A slab of t layers holds t + 3 slices (corner voxels and the gradient apron).
    const double fit = available / (kSlabOverhead * sliceBytes) - 3.0;
    int thickness = std::clamp(int(std::min(fit, double(layers))), 1, layers);
    if (maxLayers > 0)
        thickness = std::min(thickness, maxLayers);
    const int count = (layers + thickness - 1) / thickness;
    // Even slabs: the last one is not a sliver.
    for (int i = 0; i < count; ++i)
        slabs.push_back(
            {int(std::int64_t(layers) * i / count), int(std::int64_t(layers) * (i + 1) / count)});
    return slabs;
}

namespace {

// Min and max over x of every voxel row (index z * dims.y + y), in parallel over the rows.
template <typename T>
void voxelRowRanges(const T* voxels, glm::ivec3 dims, std::vector<float>& lo,
                    std::vector<float>& hi) {
    const std::size_t rows = std::size_t(dims.y) * std::size_t(dims.z);
    lo.resize(rows);
    hi.resize(rows);
    core::parallelFor(rows, [&](std::size_t r) {
        const T* row = voxels + r * std::size_t(dims.x);
        float rowLo = float(row[0]), rowHi = rowLo;
        for (int x = 1; x < dims.x; ++x) {
            rowLo = std::min(rowLo, float(row[x]));
            rowHi = std::max(rowHi, float(row[x]));
        }
        lo[r] = rowLo;
        hi[r] = rowHi;
    });
}

} // namespace

VoxelRowRanges::VoxelRowRanges(const volume::Volume& volume) : m_dims(volume.dims()) {
    if (m_dims.x < 2 || m_dims.y < 2 || m_dims.z < 2)
        return;
    std::vector<float> rowLo, rowHi;
    volume::dispatchVoxelType(volume.voxelType(), [&](auto zero) {
        voxelRowRanges(volume.dataAs<decltype(zero)>(), m_dims, rowLo, rowHi);
    });
    // A cell row's corners are the voxel rows (j, k), (j + 1, k), (j, k + 1), (j + 1, k + 1).
    const int cellRows = m_dims.y - 1, cellLayers = m_dims.z - 1;
    m_min.resize(std::size_t(cellRows) * std::size_t(cellLayers));
    m_max.resize(m_min.size());
    for (int k = 0; k < cellLayers; ++k)
        for (int j = 0; j < cellRows; ++j) {
            const std::size_t r = std::size_t(k) * std::size_t(m_dims.y) + std::size_t(j);
            const std::size_t up = r + std::size_t(m_dims.y);
            const std::size_t cell = std::size_t(k) * std::size_t(cellRows) + std::size_t(j);
            m_min[cell] = std::min({rowLo[r], rowLo[r + 1], rowLo[up], rowLo[up + 1]});
            m_max[cell] = std::max({rowHi[r], rowHi[r + 1], rowHi[up], rowHi[up + 1]});
        }
}

bool VoxelRowRanges::cellRowMayHoldSurface(int j, int k, double storedIso) const {
    const std::size_t cell = std::size_t(k) * std::size_t(m_dims.y - 1) + std::size_t(j);
    return double(m_min[cell]) < storedIso && storedIso <= double(m_max[cell]);
}

std::vector<kernels::CellSlab> cropSlabsToSurface(const std::vector<glm::ivec2>& layerRanges,
                                                  const VoxelRowRanges& rows, double storedIso) {
    std::vector<kernels::CellSlab> slabs;
    const int cellRows = rows.dims().y - 1;
    for (const glm::ivec2& layers : layerRanges) {
        // Per layer the first and the last row that can hold the surface, each searched from its
        // end of the layer: on a CT most layers stop after a few rows.
        int first = cellRows, end = 0;
        for (int k = layers.x; k < layers.y; ++k) {
            int j = 0;
            while (j < first && !rows.cellRowMayHoldSurface(j, k, storedIso))
                ++j;
            if (j == cellRows)
                continue; // no surface in this layer
            first = std::min(first, j);
            int last = cellRows - 1;
            while (last + 1 > end && !rows.cellRowMayHoldSurface(last, k, storedIso))
                --last;
            end = std::max(end, last + 1);
        }
        if (first < end)
            slabs.push_back(kernels::CellSlab{layers, glm::ivec2(first, end)});
    }
    return slabs;
}

GpuResidency afterOutOfMemory(GpuResidency residency) {
    return residency == GpuResidency::WholeVolume ? GpuResidency::Slabs : GpuResidency::Cpu;
}

} // namespace lw::render
