#pragma once

#include "lw/kernels/voxel_grid.h"
#include "lw/volume/bricks.h"
#include "lw/volume/volume.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <utility>
#include <vector>

namespace lw::kernels::cpu {

enum class McStatus {
    Ok,
    TooManyVertices, // more than 2^32 - 1 vertices: the index type cannot address them
};

struct McResult {
    McStatus status = McStatus::Ok;
    std::size_t totalBricks = 0;
    std::size_t activeBricks = 0; // bricks whose min/max admit the iso-value
    std::size_t workUnits = 0;    // (brick, slab) items handed to the threads
};

// Output buffers; reused across calls so repeated extraction (mode b) does not pay for fresh
// pages every frame.
struct McOutput {
    std::vector<glm::vec3> positions; // patient mm
    std::vector<glm::vec3> normals;   // unit, outward (from value >= iso towards value < iso)
    std::vector<std::uint32_t> indices;
};

// Marching cubes with per-vertex gradient normals over the active bricks of `grid`, on
// `threads` threads (0 = all cores). `storedIso` is in stored units; inside = value >= iso.
//
// The output is canonical and independent of the brick schedule and thread count: vertices
// are ordered by their global edge id (voxel index * 3 + axis), triangles by their cell index
// and then by table order. The one-brick grid (whole volume) and any chunked grid therefore
// give bit-identical meshes.
McResult marchingCubes(const volume::Volume& volume, const volume::BrickGrid& grid,
                       double storedIso, McOutput& out, unsigned threads = 0);

// The grid set-up (derivative spans, patient frame) that marchingCubes() uses for `volume`.
// Method 2 builds its vertices from the same one, which is what makes them bit-identical.
inline VoxelGridSetup voxelGridSetup(const volume::Volume& volume) {
    const volume::VolumeGeometry& g = volume.geometry();
    const int nz = volume.dims().z;
    std::vector<double> sliceOffsets(std::size_t(nz > 0 ? nz : 0));
    for (int k = 0; k < nz; ++k)
        sliceOffsets[std::size_t(k)] = g.sliceOffset(double(k));
    return VoxelGridSetup(volume.dims(), g.origin(), g.axisI(), g.axisJ(), g.stackAxis(),
                          g.spacingI(), g.spacingJ(), std::move(sliceOffsets));
}

} // namespace lw::kernels::cpu
