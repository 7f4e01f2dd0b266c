#pragma once

// First and second derivatives of the voxel field at the vertices of its iso-surface, in patient
// coordinates (mm): what the radial curvature of suggestive contours needs (radial_curvature.h).
// They do not depend on the view, so a mesh gets them once and every frame reuses them.
//
// A vertex of marching cubes lies on a grid edge; its position is mapped back to continuous
// index coordinates through the volume's geometry (the oblique frame, uneven slice offsets) and
// the gradient and Hessian of the grid points around it are interpolated trilinearly there (on
// an edge, that is linear between its two ends, as marching cubes interpolates the gradient).
// Grid points use the voxel gradient of voxel_grid.h and its derivative (frameHessian), so the
// normal direction agrees with the mesh's normals. The cap that closes the surface where the
// volume's border cuts it (its triangles lie in a border plane) is the flat cut face: gradient
// along its normal, Hessian 0.

#include "lw/kernels/radial_curvature.h"
#include "lw/kernels/triangle_mesh.h"
#include "lw/kernels/voxel_grid.h"
#include "lw/volume/volume.h"

#include <glm/glm.hpp>
#include <vector>

namespace lw::render {

struct SurfaceDerivatives {
    std::vector<glm::vec3> gradient;    // per vertex; points inside (toward larger values)
    std::vector<kernels::Sym3> hessian; // per vertex
};

// Per vertex of `mesh` (extracted from `volume`), in the volume's stored units per mm (a
// positive value slope scales both alike, so the curvature does not see it). `stencil`: the
// gradient the mesh's normals were made with; the Hessian is its derivative.
SurfaceDerivatives
surfaceDerivatives(const volume::Volume& volume, const kernels::TriangleMesh& mesh,
                   unsigned threads = 0,
                   kernels::GradientStencil stencil = kernels::GradientStencil::Central);

} // namespace lw::render
