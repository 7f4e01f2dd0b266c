#pragma once

// The triangles of a surface that a view's contour may cross: those whose vertices' d =
// N . (eye - P) are not all beyond a small margin on one side (kernels' mayHoldContour), a
// superset of the triangles Burns' rule crosses. The vector lines (visible_polylines.h) chained
// from them are the same as from the whole surface: the same crossed triangles in the same order,
// their edges welded by position as before. The CUDA back-ends select them on the device, so an
// export downloads a few in a hundred of the surface's triangles (ContourTrianglesCuda).
//
// The part is a Mesh of unshared corners: vertex 3 i + k is corner k of its i-th triangle.

#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"

#include <glm/glm.hpp>

namespace lw::render {

// Appends the triangles of `mesh` that may hold the contour seen from `viewer` (the eye, w = 1,
// or the unit vector toward the viewer, w = 0: Camera::viewerHomogeneous) to `part`, in order,
// as unshared corners (positions and normals; numberCorners gives the indices).
void appendContourTriangles(const Mesh& mesh, glm::vec4 viewer, Mesh& part);
// part.indices = 0, 1, ..., its vertex count - 1.
void numberCorners(Mesh& part);
// The whole selection on the host: what the CUDA back-end downloads for the same surface.
Mesh contourTriangles(const Mesh& mesh, const Camera& camera);

} // namespace lw::render
