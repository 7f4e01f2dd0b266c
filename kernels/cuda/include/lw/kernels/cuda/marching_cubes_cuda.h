#pragma once

// Marching cubes with gradient normals on the GPU: the same triangles as the CPU reference
// (lw/kernels/cpu/marching_cubes_cpu.h) in the same canonical order -- vertices by global edge id
// (voxel index * 3 + axis), triangles by cell and then table order -- with bit-identical
// positions and normals (shared expressions from kernels/common, no FMA contraction).
//
// Pipeline per extraction (one stream):
//   bricks     active = min < iso <= max per 16^3-cell brick (min/max computed at upload)
//   classify   per 256-voxel tile: count the voxels with a crossing edge or a cut cell
//              (threads of inactive bricks read nothing), CUB DeviceScan over the tile counts,
//              then the same tile again writes the active voxels in order (CUB BlockScan ranks)
//   count      vertices (crossing edges) and triangles (table) per active voxel, CUB DeviceScan
//   generate   vertices with gradient normals; triangles, each corner's vertex found by a binary
//              search for its owning voxel in the ordered active list
// Output stays in device buffers (method 3 draws from there); download() copies it to the host.
// Public header: no CUDA types.

#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/volume_view.h"
#include "lw/kernels/voxel_grid.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace lw::kernels::cuda {

// A mesh in device memory, valid until the next extract() or setVolume().
struct DeviceMeshView {
    const glm::vec3* positions = nullptr; // patient mm
    const glm::vec3* normals = nullptr;   // unit, outward
    const std::uint32_t* indices = nullptr;
    std::size_t vertexCount = 0;
    std::size_t triangleCount = 0;
    // A border voxel is inside: the surface may be open there, so back faces are not culled.
    bool touchesBorder = false;
};

// Stage times of the last extraction, from CUDA events (ms).
struct McCudaTimes {
    double bricksMs = 0, classifyMs = 0, countMs = 0, generateMs = 0;
    double totalMs() const { return bricksMs + classifyMs + countMs + generateMs; }
};

class MarchingCubesCuda {
public:
    MarchingCubesCuda();
    ~MarchingCubesCuda();
    MarchingCubesCuda(const MarchingCubesCuda&) = delete;
    MarchingCubesCuda& operator=(const MarchingCubesCuda&) = delete;

    // Uploads the voxels (host memory) and the grid tables of `setup`, and computes the brick
    // min/max on the device. The host volume is not referenced afterwards.
    CudaStatus setVolume(const VolumeView& hostVolume, const VoxelGridSetup& setup);
    double uploadMs() const;     // host -> device copy of the voxels, CUDA events
    std::size_t deviceBytes() const; // device memory held now

    // Extracts the surface at `storedIso` (stored units; inside = value >= iso).
    CudaStatus extract(double storedIso);
    DeviceMeshView mesh() const;
    const McCudaTimes& times() const;
    std::size_t activeVoxelCount() const;

    // Only the classification: the ordered list of active voxels (a crossing edge or a cut cell),
    // without generating the mesh; what method 2 starts from.
    CudaStatus classify(double storedIso);

    CudaStatus download(std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals,
                        std::vector<std::uint32_t>& indices) const;

    // The back-end's other kernels (kernels/cuda/src) reach the state through this.
    struct Impl;
    Impl& implementation() { return *m_impl; }

private:
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::kernels::cuda
