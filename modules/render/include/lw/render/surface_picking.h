#pragma once

// Picking: a pixel of a rendered panel -> the point on the iso-surface under it, in patient
// coordinates (LPS, mm). The mesh lies in patient space (marching cubes maps every vertex through
// VolumeGeometry::indexToPatient), so a tilted or unevenly spaced series is picked where the
// scanner put it, with nothing resampled.

#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"

#include <glm/glm.hpp>
#include <optional>
#include <vector>

namespace lw::render {

// From a depth buffer as the panels keep it (top row first, GL window depth in [0, 1], 1 where
// no surface is; shadeSurfaceCpu's `depth` or a GL read-back flipped to top-first) rendered with
// `camera`. `pixel` is in continuous pixel coordinates of that viewport (ProjectedPoint::pixel);
// the depth of the pixel containing it is unprojected through its centre. Nothing when the
// pixel is outside the viewport, shows no surface, or the buffer does not match the camera.
std::optional<glm::dvec3> pickFromDepthBuffer(const std::vector<float>& depth, const Camera& camera,
                                              glm::dvec2 pixel);

// The nearest intersection in front of the eye of the ray through `pixel` with the mesh's
// triangles (Moeller-Trumbore, both facings): exact on the mesh, independent of any depth
// buffer's precision. Linear in the triangle count (about 10 ms per million triangles).
std::optional<glm::dvec3> pickMeshSurface(const Mesh& mesh, const Camera& camera, glm::dvec2 pixel);

} // namespace lw::render
