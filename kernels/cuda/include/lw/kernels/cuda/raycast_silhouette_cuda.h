#pragma once

// Method 2 on the GPU: silhouette segments straight from the active cells (no mesh kept) and the
// ray-cast visibility test through the voxel grid, as one kernel over the cells.
//   prepare   the ordered active cells (MarchingCubesCuda::classify: bricks with min/max skip,
//             CUB scans) and the macro-cell occupancy for empty-space skipping (view-independent:
//             what mode a keeps)
//   render    per active cell: the marching-cubes vertices and normals of its crossing edges
//             (kernels/common, bit for bit the CPU's), Burns' segment of each triangle, and for
//             each segment the visibility rays of kernels/common's RayVisibility (both endpoints,
//             one ray per point where segments share one, or every pixel step along it), then
//             the DDA of rasterizeLine into a byte mask
//   prune     short strokes cleared from the mask on the device (stroke_pruning.h)
// The CPU back-end (kernels/cpu/raycast_silhouette_cpu.h) calls the same rules, so the images
// agree. Public header: no CUDA types.

#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/pixel_camera.h"
#include "lw/kernels/silhouette_segment.h"
#include "lw/kernels/voxel_ray_walk.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace lw::kernels::cuda {

struct RayCastCudaSettings {
    bool visibility = true;
    bool alongSegment = false; // test every pixel step of a segment, not only its endpoints
    // Strokes of fewer pixels (joined across gaps of strokeGapPixels) cleared on the device before
    // the mask is copied to the host (stroke_pruning.h); 0 or 1: none.
    int minStrokePixels = 0;
    int strokeGapPixels = 0;
};

struct RayCastCudaFrame {
    std::size_t triangles = 0; // triangles of the active cells (visited)
    std::size_t segments = 0;  // silhouette segments found (before visibility)
    double prepareMs = 0.0;    // CUDA events; 0 when the cache was reused
    double renderMs = 0.0;
};

// The walk's grid on the host side (kernels/cpu's VoxelRayGrid supplies it).
struct RayGridSetup {
    RayGridView view;            // offsets point to host memory here
    std::vector<double> offsets; // increasing slice offsets (the view's table)
    glm::dvec3 cellScale{1.0};
    double neighbourReach = RayVisibilityRule::kNeighbourReachCells; // neighbourReachCells()
};

class RayCastSilhouetteCuda {
public:
    RayCastSilhouetteCuda();
    ~RayCastSilhouetteCuda();
    RayCastSilhouetteCuda(const RayCastSilhouetteCuda&) = delete;
    RayCastSilhouetteCuda& operator=(const RayCastSilhouetteCuda&) = delete;

    // `mapped`: the voxels stay in host memory, read over the bus (MarchingCubesCuda::
    // setMappedVolume): the chunked (L) variant, for a volume over the device memory budget.
    // `deviceVoxels` (or null): the same voxels in this device's memory already; a volume kept
    // on the device (neither mapped nor slabbed) is copied from there device to device
    // (MarchingCubesCuda::setDeviceVolume) instead of uploaded from the host.
    CudaStatus setVolume(const VolumeView& hostVolume, const VoxelGridSetup& setup,
                         const RayGridSetup& rayGrid, bool mapped = false,
                         const void* deviceVoxels = nullptr);
    std::size_t deviceBytes() const; // device memory held now
    double uploadMs() const;
    // Whether the kernels read the volume from host memory (mapped or slabbed): page-locked with
    // the driver until release() or the next setVolume, which must come before that memory goes.
    bool readsHostMemory() const;
    // The normals' gradient from the next prepare() on (MarchingCubesCuda::setGradientStencil).
    void setGradientStencil(GradientStencil stencil);
    // Whether prepare() keeps the active cells' mesh on the device for the views' segments (the
    // default; without room for it, or when off, each view builds them from the voxels). Both
    // give the same segments; off exists for the test that says so.
    void setKeepCellMesh(bool keep);
    // Volumes of 2^32 voxels or more are extracted in slabs of cell layers (whole-volume marching
    // cubes indexes voxels with 32 bits) and their rays read the volume from host memory; `layers`
    // > 0 makes every volume go that way with slabs of that many layers (from the next
    // setVolume), so that tests can compare it with the whole volume at small sizes.
    void setSlabLayers(int layers);
    CudaStatus prepare(double storedIso, RayCastCudaFrame& frame);
    // `extraSegments` (host memory, may be null): segments found elsewhere (the border cap's),
    // tested and drawn after the cells' own with the same rule.
    CudaStatus render(const PixelCamera& camera, glm::dvec3 eyeOrDirection, bool orthographic,
                      const RayCastCudaSettings& settings, std::uint8_t* hostMask,
                      RayCastCudaFrame& frame, const SegmentEndpoints* extraSegments = nullptr,
                      std::size_t extraCount = 0);

    void release(); // frees every device buffer (after running out of memory)

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::kernels::cuda
