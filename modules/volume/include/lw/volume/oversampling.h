#pragma once

// Finer samples of the same field. Marching cubes makes triangles as large as the cells: on a
// thick-slice or coarse series seen large, a triangle spans many pixels, and where the surface
// bends within one (the rim of a thin wall, a slab's terrace, the volume's cut border) the
// contour of the interpolated normals runs pixels away from the mesh's own outline. Splitting
// the cells (each axis's samples linearly interpolated, factor - 1 new ones per gap) leaves the
// trilinear field every method reads exactly as it was -- a trilinear function sampled on a
// finer grid interpolates back to itself -- so the surface does not change, only how finely
// its triangles follow it. Linear, not cubic: no value is invented (a cubic rings past a
// plateau next to a step, and at an iso-value just above the plateau that rings into specks of
// surface in the air).
//
//   factors (1, 1, 2), 3 slices -> 5:   slice  0 . 1 . 2        (. = new, the mean of its two
//                                       index  0 1 2 3 4        neighbours)

#include "lw/volume/volume.h"

#include <glm/glm.hpp>

namespace lw::volume {

// (n - 1) * factor + 1 samples per axis of n > 1; an axis of one sample stays one.
glm::ivec3 oversampledDims(glm::ivec3 dims, glm::ivec3 factors);

// `volume` sampled `factors` times as densely along (i, j, k), in its own voxel type (integer
// types rounded to the nearest value: the field then differs from the original by at most half
// a stored unit), with the geometry of VolumeGeometry::refined and the same value mapping and
// description. Factors of (1, 1, 1) give a clone. Throws core::Error for a factor below 1 or a
// result larger than core::ImportLimits allows a volume.
Volume oversampled(const Volume& volume, glm::ivec3 factors, unsigned threads = 0);

} // namespace lw::volume
