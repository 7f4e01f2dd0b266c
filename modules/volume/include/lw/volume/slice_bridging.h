#pragma once

// Thin walls sliding between thick slices, after the shape-based field is refined
// (volume/slice_distance.h, volume/oversampling.h).
//
// Where a thin wall -- the top of a skull -- runs shallow to thick slices, its cuts in two
// neighbouring slices lie side by side in plane. The shape-based field interpolates each point's
// two distances, and between the cuts both are negative: the wall pinches to a waist or breaks
// into one lip per slice, which the silhouette draws as slits and ridge lines, slice after slice.
// This pass slides each cut straight to the other's place instead, where both are walls at most
// `widthMm` wide whose contours face along the same line, and raises the slices between to the
// slid wall (never lowers them); walls up to half as wide again get a share of that raise, less
// the wider they are, so that the pass fades out instead of stopping at one width.
// kernels/thin_shell_bridge.h holds the geometry, shared with the CUDA back-end so that both make
// the same field bit for bit. The slices themselves do not change, nor does anything wider than
// 1.5 `widthMm` or farther than the field's limit.

#include "lw/volume/volume.h"

namespace lw::volume {

// `field`: an int16 shape-based field whose every factor-th slice holds a slice's distances
// (1/kSliceDistanceStepsPerMm mm, limited to +-limitMm) and whose slices between are refined.
// Does nothing for a factor below 2, a widthMm of 0 or a field under 3 x 3 pixels. Throws
// core::Error for a field that is not int16 or whose slice count is not (n - 1) * factor + 1.
void bridgeThinWalls(Volume& field, int factor, double limitMm, double widthMm,
                     unsigned threads = 0);

} // namespace lw::volume
