#pragma once

// The cap that closes an iso-surface where the volume's border cuts it (issue 7): where the
// first or last slice (or a side of the field of view) cuts through bone, marching cubes leaves
// the surface open, the shaded panel shows a cut face, and the silhouette methods, which only
// find contours of the surface, draw nothing there.
//
// The cap is marching cubes over the one layer of cells around the volume, as if the volume were
// padded with one voxel layer of a value far below the iso-value (the limit of the padding value
// going to minus infinity), in the volume's own geometry (tilt, uneven slice gaps):
//
//      pad   real  real            cell (-1, j, k) spans the pad voxel x = -1 and the real
//       o ---- # ---- # ...        voxels x = 0; its edges are
//       |      |      |             - pad -> real: the crossing sits on the real voxel (t -> 1:
//       o ---- # ---- # ...           the cap lies in the border plane, where the data ends),
//      x=-1   x=0    x=1              its normal is the face's outward normal (the padded
//                                     gradient is dominated by the pad step);
//                                   - real -> real, in the border plane: the vertex marching
//                                     cubes gives that edge, bit for bit (voxel_grid.h).
//
// The open surface is left as it is (its normals keep the in-volume gradient at the border; a
// literally padded volume would bend them towards the artificial pad value), so the closed
// surface is the open one plus this cap: the cap is appended, and the brick and slab schedules
// (L) draw it as one more piece. It depends only on the volume and the iso-value: renderers keep
// it per iso-value. The cap's border-plane vertices repeat open-surface vertices (same bits), not
// their indices.

#include "lw/kernels/triangle_mesh.h"
#include "lw/kernels/voxel_grid.h"
#include "lw/volume/volume.h"

#include <array>

namespace lw::kernels::cpu {

// The largest stored value on each face of the volume (x low, x high, y low, y high, z low,
// z high; NaN ignored, -infinity for a face of NaN only): which faces hold an inside voxel, at any
// iso-value, from one read of the border per volume. Reading the faces of a 512^3 volume takes
// 6-8 ms on the H200's host (the x faces a voxel a row), where the cap itself, when the border
// holds no inside voxel, is nothing.
struct BorderFaceMaxima {
    std::array<double, 6> value{};
};
BorderFaceMaxima borderFaceMaxima(const volume::Volume& volume);

// The cap at `storedIso` (stored units; inside = value >= iso, as marchingCubes). Empty when no
// voxel on the volume's border is inside. Vertices and triangles in a canonical order (padded
// cell order, then table order): the same volume and iso give the same bytes. `faces` (may be
// null: read here): the volume's borderFaceMaxima, for callers that keep them per volume.
TriangleMesh borderCap(const volume::Volume& volume, double storedIso,
                       GradientStencil stencil = GradientStencil::Central,
                       const BorderFaceMaxima* faces = nullptr);

// Appends `piece` to `mesh`, its indices shifted past mesh's vertices.
void appendMesh(TriangleMesh& mesh, const TriangleMesh& piece);

} // namespace lw::kernels::cpu
