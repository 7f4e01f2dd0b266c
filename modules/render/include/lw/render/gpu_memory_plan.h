#pragma once

// How the CUDA back-end fits a frame into a device memory budget: whether the whole volume can be
// resident (S) or streams in slabs (L), how thick the slabs are, and what to try when the device
// runs out of memory. Plain arithmetic, so it is tested on machines without a GPU.

#include "lw/kernels/cell_slab.h"
#include "lw/volume/volume.h"

#include <cstddef>
#include <glm/glm.hpp>
#include <string_view>
#include <vector>

namespace lw::render {

enum class GpuResidency { WholeVolume, Slabs, Cpu };
std::string_view residencyName(GpuResidency residency);

// What a resident whole volume needs besides its voxels, as a multiple of the voxel bytes: the
// classification, the mesh and the method's buffers. An estimate from the buffer sizes on the
// 512^3 CT phantom at 300.5 HU (tiles, active voxels, mesh: about 0.6 times the voxels), with
// room for much denser surfaces (noise); frames report what they really held
// (SilhouetteFrame::deviceBytes), and running out anyway falls back (afterOutOfMemory).
inline constexpr double kWholeVolumeOverhead = 3.0;
// Per slab: two slab boxes in flight, the classification and the slab's mesh.
inline constexpr double kSlabOverhead = 6.0;
// The default budget keeps this much of the free memory for everyone else (display, other
// programs): the larger of 512 MiB and 10 % of the free memory.
std::size_t defaultGpuBudget(std::size_t freeBytes);

// WholeVolume when the caller did not ask for chunks and the volume with its overhead fits in
// `budget` (after `reservedBytes`, e.g. the image buffers); Slabs otherwise.
GpuResidency chooseResidency(glm::ivec3 dims, std::size_t voxelBytes, std::size_t budget,
                             std::size_t reservedBytes, bool chunkedRequested);

// Cell layers [first, end) of each slab: as thick as `budget` allows, at least one layer, the
// cell grid (dims.z - 1 layers) covered in order without gaps. Empty for fewer than 2 slices.
// maxLayers > 0 caps the thickness.
std::vector<glm::ivec2> planSlabs(glm::ivec3 dims, std::size_t voxelBytes, std::size_t budget,
                                  std::size_t reservedBytes, int maxLayers = 0);

// The value range of every voxel row (all x of one y and z), computed once per volume: which cell
// rows of a slab can hold the surface, so that a streamed slab uploads only those (on a CT at a
// bone iso-value much of each slice is air and soft tissue).
class VoxelRowRanges {
public:
    VoxelRowRanges() = default;
    explicit VoxelRowRanges(const volume::Volume& volume); // all cores
    glm::ivec3 dims() const { return m_dims; }
    // Cell row j of cell layer k (corners: voxel rows j, j + 1 of slices k, k + 1) can hold the
    // surface at `storedIso` (inside = value >= iso): min < iso <= max over its corners, the rule
    // of volume::Brick::mayContainSurface.
    bool cellRowMayHoldSurface(int j, int k, double storedIso) const;

private:
    glm::ivec3 m_dims{0};
    std::vector<float> m_min, m_max; // per voxel row, index z * dims.y + y
};

// The slabs of `layerRanges` (planSlabs) cropped to the cell rows that can hold the surface at
// `storedIso`; slabs with none are left out. The crop never adds voxels, so a slab still fits the
// budget it was planned for.
std::vector<kernels::CellSlab> cropSlabsToSurface(const std::vector<glm::ivec2>& layerRanges,
                                                  const VoxelRowRanges& rows, double storedIso);

// Where a frame goes when the device ran out of memory: the whole volume falls back to slabs,
// slabs to the CPU (which is final).
GpuResidency afterOutOfMemory(GpuResidency residency);

} // namespace lw::render
