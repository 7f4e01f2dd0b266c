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

#include "lw/kernels/cell_slab.h"
#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/volume_view.h"
#include "lw/kernels/voxel_grid.h"

#include <cstddef>
#include <cstdint>
#include <functional>
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
    // The same with voxels that are in this device's memory already (`deviceVolume.voxels`, the
    // layout of a VolumeView): copied device to device, so the source may change afterwards. A
    // renderer of a copy made on the device (the thick-slice field) saves the upload over the bus.
    CudaStatus setDeviceVolume(const VolumeView& deviceVolume, const VoxelGridSetup& setup);
    // The same with the voxels left in host memory: the volume is page-locked and mapped into
    // the device's address space, and the kernels read it over the bus (the device holds only
    // the tables and the per-frame buffers). For a volume over the device memory budget where
    // every kernel needs the whole volume at once (method 2's rays). `hostVolume` must outlive
    // the calls; release() or another set*Volume unmaps it.
    CudaStatus setMappedVolume(const VolumeView& hostVolume, const VoxelGridSetup& setup);
    double uploadMs() const;         // the copy of the voxels to the device, CUDA events
    std::size_t deviceBytes() const; // device memory held now

    // The normals' gradient of the next extractions (voxel_grid.h); set*Volume takes the
    // setup's. No upload: the stencil is a field of the spans every kernel gets.
    void setGradientStencil(GradientStencil stencil);
    // Extracts the surface at `storedIso` (stored units; inside = value >= iso).
    CudaStatus extract(double storedIso);
    DeviceMeshView mesh() const;
    const McCudaTimes& times() const;
    std::size_t activeVoxelCount() const;

    // The streamed (L) variant: the volume stays in host memory and goes to the device one slab
    // at a time. A slab (cell_slab.h) is cell layers along z, cropped to the cell rows along y
    // that can hold the surface; its box (corner voxels plus the one-voxel gradient apron, whole
    // x rows) is one contiguous run per slice in the host volume, so it goes up with one
    // asynchronous 2D copy from page-locked memory (the volume is registered with the driver, or,
    // where that fails, staged through a pinned buffer). Two slots: slab k + 1 uploads on its own
    // stream while slab k is extracted. Each slab's mesh has the same triangles and bit-identical
    // vertices as the whole mesh's triangles of those cells (only the numbering is slab-local),
    // so per-pixel maxima drawn from the slabs equal those of the whole mesh.
    //
    // setStreamedVolume keeps `hostVolume` (it must outlive the calls) and uploads only the grid
    // tables; extractSlabs calls onSlab(k, mesh) once per slab with triangles (k: its index in
    // `slabs`), the mesh valid during the call; a failed status from onSlab stops the walk and is
    // returned.
    CudaStatus setStreamedVolume(const VolumeView& hostVolume, const VoxelGridSetup& setup);
    using SlabCallback = std::function<CudaStatus(std::size_t slab, const DeviceMeshView& mesh)>;
    CudaStatus extractSlabs(double storedIso, const std::vector<CellSlab>& slabs,
                            const SlabCallback& onSlab);
    // Frees every device buffer (after running out of memory, before trying another way); the
    // next frame needs setVolume or setStreamedVolume again.
    void release();
    // Device memory held at the most since setVolume / setStreamedVolume (bytes).
    std::size_t peakDeviceBytes() const;

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
