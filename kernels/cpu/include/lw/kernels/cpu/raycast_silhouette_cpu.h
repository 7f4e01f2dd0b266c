#pragma once

#include "lw/core/progress.h"

// Method 2 of the paper on the CPU: silhouette segments straight from the active cells (no mesh
// kept) and the ray-cast visibility test through the voxel grid.

#include "lw/kernels/cpu/voxel_ray.h"
#include "lw/kernels/silhouette_segment.h"
#include "lw/kernels/voxel_grid.h"
#include "lw/volume/bricks.h"
#include "lw/volume/volume.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace lw::kernels::cpu {

// Where the silhouette is seen from: the eye (perspective) or the unit vector toward the viewer
// (orthographic), the same convention as silhouetteDistance().
struct SilhouetteView {
    glm::dvec3 eyeOrDirection{0.0, -1.0, 0.0};
    bool orthographic = false;
    double pixelSpan = 0.0; // rayPixelSpan() of the camera; 0: no neighbour ray
};

class RayCastSilhouetteCpu {
public:
    RayCastSilhouetteCpu();
    ~RayCastSilhouetteCpu();
    RayCastSilhouetteCpu(const RayCastSilhouetteCpu&) = delete;
    RayCastSilhouetteCpu& operator=(const RayCastSilhouetteCpu&) = delete;

    // The view-independent part (what mode a caches): the cells with mixed corners of the
    // bricks of `grid` whose min/max admit `storedIso`, in brick order. Inside = value >= iso,
    // as in marchingCubes(). `volume` must outlive this object or the next prepare().
    // withNormalCones (for mode a, where the cells serve many views) also keeps, per cell, a cone
    // around its vertex normals and its centre (32 bytes) so that a view skips the cells that
    // cannot hold a silhouette; the cull is conservative, the segments are the same with or without
    // it. Also builds an occupancy grid of 8^3-cell macro cells that lets the visibility rays jump
    // over empty space.
    // `cancel` (optional) is polled between cell layers; false = cancelled, nothing prepared.
    // `stencil`: the normals' gradient, as marchingCubes() was given it.
    bool prepare(const volume::Volume& volume, const volume::BrickGrid& grid, double storedIso,
                 bool withNormalCones = true, unsigned threads = 0,
                 const core::CancelToken* cancel = nullptr,
                 GradientStencil stencil = GradientStencil::Central);
    bool isPrepared() const;
    std::size_t activeCellCount() const;
    std::size_t activeBrickCount() const;

    // The Burns segment of every marching-cubes triangle of the active cells that holds one, in
    // patient mm, cell by cell in brick order. The triangles, vertices and normals are those of
    // marchingCubes() bit for bit (same shared expressions, same evaluation order), so the
    // segments equal the ones computed from its mesh. Returns the number of triangles visited.
    std::size_t extractSegments(const SilhouetteView& view, unsigned threads = 0);
    // The segments of the last extractSegments() in work chunks (never straddling a brick), in
    // brick then cell order. Kept in place rather than concatenated: on a 512 x 512 x 1024 CT a
    // copy would cost as much memory as the segments themselves.
    std::size_t segmentChunkCount() const;
    const std::vector<SegmentEndpoints>& segmentChunk(std::size_t chunk) const;
    std::size_t segmentCount() const;
    // Cells the last extractSegments() built (those the normal-cone cull could not skip; every
    // active cell without cones).
    std::size_t builtCellCount() const;
    // Convenience (tests, tools): extractSegments() and the segments in one flat list.
    std::size_t extractSegments(const SilhouetteView& view, std::vector<SegmentEndpoints>& out,
                                unsigned threads = 0);

    // The paper's visibility test for a point on the surface: a ray from the point toward the
    // viewer, walked cell by cell (VoxelRayGrid); occluded when the bilinearly interpolated value
    // on a wall the ray leaves a cell through is inside (>= iso).
    //
    // Self-occlusion rule: the ray starts 1e-4 cell off the point toward the viewer, and walls
    // are not tested until the ray has left the cell it starts in and travelled at least
    // selfSkipCells() cell widths (measured in grid units); from there any inside wall
    // occludes. A silhouette point lies on a chord of the interpolated surface
    // and its ray runs tangent to it; near the start the ray stays within a hair of the
    // trilinear surface, where round-off and the difference between the linear mesh and the
    // trilinear field would hide it. A point whose ray is blocked near it is still visible when
    // the ray from one pixel beside it, outward across the view, passes (the neighbour ray,
    // voxel_ray_walk.h; only with view.pixelSpan set). Rays leaving the grid, or reaching the
    // eye, are visible; one starting outside the grid is walked from where it enters it.
    bool isVisible(glm::dvec3 patientPoint, const SilhouetteView& view) const;
    static double selfSkipCells();

    const VoxelRayGrid& rayGrid() const;

    // The per-voxel-type engine; public only so the implementation file can derive from it.
    struct Impl;

private:
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::kernels::cpu
