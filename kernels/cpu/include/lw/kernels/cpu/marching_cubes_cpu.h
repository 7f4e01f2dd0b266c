#pragma once

#include "lw/core/progress.h"
#include "lw/kernels/triangle_mesh.h"
#include "lw/kernels/voxel_grid.h"
#include "lw/volume/bricks.h"
#include "lw/volume/volume.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

namespace lw::kernels::cpu {

enum class McStatus {
    Ok,
    TooManyVertices, // more than 2^32 - 1 vertices: the index type cannot address them
    Cancelled,       // the cancel token was set: the output is empty
    OverByteLimit,   // the mesh would take more than McOutputBudget::maxBytes: nothing allocated
};

struct McResult {
    McStatus status = McStatus::Ok;
    std::size_t totalBricks = 0;
    std::size_t activeBricks = 0; // bricks whose min/max admit the iso-value
    std::size_t workUnits = 0;    // (brick, slab) items handed to the threads
    // The mesh's size, counted in the first pass before anything is allocated for it.
    std::uint64_t vertices = 0;
    std::uint64_t triangles = 0;
};

// Output buffers (the engine's one mesh type); reused across calls so repeated extraction
// (mode b) does not pay for fresh pages every frame.
using McOutput = TriangleMesh;

// What the output may take, decided once the first pass has counted the mesh and before its
// buffers are allocated. `spare*`: room reserved behind the mesh for what the caller appends
// (the border cap), so appending does not reallocate -- at a 4 GiB volume a reallocation holds
// the old and the new positions side by side, hundreds of MiB. maxBytes covers the spare too.
struct McOutputBudget {
    std::size_t maxBytes = std::numeric_limits<std::size_t>::max();
    std::size_t spareVertices = 0;
    std::size_t spareTriangles = 0;
};

// Marching cubes with per-vertex gradient normals over the active bricks of `grid`, on
// `threads` threads (0 = all cores). `storedIso` is in stored units; inside = value >= iso.
//
// The output is canonical and independent of the brick schedule and thread count: vertices
// are ordered by their global edge id (voxel index * 3 + axis), triangles by their cell index
// and then by table order. The one-brick grid (whole volume) and any chunked grid therefore
// give bit-identical meshes.
// `cancel` (optional) is polled between work units: a newer request in the GUI stops an
// extraction that is no longer wanted within one unit's time. `stencil`: the normals' gradient
// (voxel_grid.h). `budget`: a mesh whose meshBytes() (spare included) are more than maxBytes is
// not allocated (McStatus::OverByteLimit, with its counts in the result; the caller words the
// refusal).
McResult marchingCubes(const volume::Volume& volume, const volume::BrickGrid& grid,
                       double storedIso, McOutput& out, unsigned threads = 0,
                       const core::CancelToken* cancel = nullptr,
                       GradientStencil stencil = GradientStencil::Central,
                       const McOutputBudget& budget = {});

// The grid set-up (derivative spans, patient frame) that marchingCubes() uses for `volume`.
// Method 2 builds its vertices from the same one, which is what makes them bit-identical.
inline VoxelGridSetup voxelGridSetup(const volume::Volume& volume,
                                     GradientStencil stencil = GradientStencil::Central) {
    const volume::VolumeGeometry& g = volume.geometry();
    const int nz = volume.dims().z;
    std::vector<double> sliceOffsets(std::size_t(nz > 0 ? nz : 0));
    for (int k = 0; k < nz; ++k)
        sliceOffsets[std::size_t(k)] = g.sliceOffset(double(k));
    return VoxelGridSetup(volume.dims(), g.origin(), g.axisI(), g.axisJ(), g.stackAxis(),
                          g.spacingI(), g.spacingJ(), std::move(sliceOffsets), stencil);
}

using kernels::voxelInsideThreshold;

// Marching cubes of one brick at a time, for method 3's L variant (the paper's chunked method 3
// exists for devices whose memory cannot hold the whole mesh). The surface of one brick's cells:
// the same triangles (same corner order, hence the same winding) with bit-identical vertex
// positions and normals as marchingCubes() gives for those cells -- both take the grid set-up,
// gradient and edge vertex from voxel_grid.h / marching_cubes.h -- so per-pixel maxima drawn
// from it equal those of the whole mesh. Only the numbering differs: indices are brick-local,
// and a vertex on a face shared with a neighbour brick is computed by both.
struct BrickSurface : TriangleMesh {
    // Scratch over the brick's corner voxels, reused from brick to brick.
    std::vector<std::uint8_t> inside;
    std::vector<std::uint8_t> rowState; // per voxel row: 0 all outside, 1 all inside, 2 mixed
    std::vector<std::uint32_t> edgeIds[3];
};

class BrickSurfaceExtractor {
public:
    // `storedIso` in stored units; inside = value >= iso (as marchingCubes). The volume must
    // outlive the extractor. Cheap to construct (per-slice tables only).
    BrickSurfaceExtractor(const volume::Volume& volume, double storedIso,
                          GradientStencil stencil = GradientStencil::Central);
    // Replaces `out`'s geometry with the surface of `brick`'s cells (single-threaded: callers
    // run several bricks side by side).
    void extract(const volume::Brick& brick, BrickSurface& out) const;

private:
    template <typename T> void extractTyped(const volume::Brick& brick, BrickSurface& out) const;

    const volume::Volume& m_volume;
    double m_iso;
    float m_isoF;
    VoxelGridSetup m_voxelGrid;
};

} // namespace lw::kernels::cpu
