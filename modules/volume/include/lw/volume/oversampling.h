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
//
// Along the slice axis alone the refined slices may instead follow a monotone cubic
// (SliceInterpolation::MonotoneCubic): the cubic Hermite curve through the slices with
// Fritsch-Butland tangents. It passes through every slice, is continuously differentiable
// across them -- so a surface slanted across thick slices has no crease at each slice, whose
// normals would turn there and draw a line -- and never leaves the range of the two slices it
// lies between (no overshoot: the ringing that rules out Catmull-Rom). The thick-slice field of
// volume/slice_distance.h is refined this way. A field linear along k stays exactly linear.

#include "lw/volume/volume.h"

#include <glm/glm.hpp>

namespace lw::volume {

// How refined samples along the slice axis (k) come from the slices.
enum class SliceInterpolation {
    Linear,        // the trilinear field, sampled finer (unchanged)
    MonotoneCubic, // smooth across the slices (see above); i and j stay linear
};

// (n - 1) * factor + 1 samples per axis of n > 1; an axis of one sample stays one.
glm::ivec3 oversampledDims(glm::ivec3 dims, glm::ivec3 factors);

// `volume` sampled `factors` times as densely along (i, j, k), in its own voxel type (integer
// types rounded to the nearest value: the field then differs from the original by at most half
// a stored unit), with the geometry of VolumeGeometry::refined and the same value mapping and
// description. Factors of (1, 1, 1) give a clone (Linear). Throws core::Error for a factor below 1
// or, before allocating, a result larger than `limits` allows a volume.
Volume oversampled(const Volume& volume, glm::ivec3 factors, unsigned threads = 0,
                   SliceInterpolation alongSlices = SliceInterpolation::Linear,
                   const core::ImportLimits& limits = {});

// Fills the slices of `field` between every factor-th one in place: those hold a volume's slices
// (slice k of it in slice k * factor), and afterwards `field` is what
// oversampled(that volume, {1, 1, factor}, threads, alongSlices) would be, bit for bit, with no
// second volume written or read. Integer voxel types only. Throws core::Error for a field whose
// slice count is not (n - 1) * factor + 1, or for float voxels.
void refineBetweenSlices(Volume& field, int factor, unsigned threads = 0,
                         SliceInterpolation alongSlices = SliceInterpolation::Linear);

} // namespace lw::volume
