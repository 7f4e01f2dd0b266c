#include "lw/render/gpu_memory_plan.h"

#include <algorithm>
#include <cstdint>

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
        slabs.push_back({int(std::int64_t(layers) * i / count),
                         int(std::int64_t(layers) * (i + 1) / count)});
    return slabs;
}

GpuResidency afterOutOfMemory(GpuResidency residency) {
    return residency == GpuResidency::WholeVolume ? GpuResidency::Slabs : GpuResidency::Cpu;
}

} // namespace lw::render
