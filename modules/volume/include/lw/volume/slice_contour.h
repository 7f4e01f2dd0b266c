#pragma once

// The iso contour on a slice (marching squares on the resampled image): where the slice plane
// cuts the iso-surface that marching cubes draws from the same trilinear field, to within the
// interpolation's difference (under half the finest voxel spacing).

#include "lw/volume/slice_plane.h"

#include <glm/glm.hpp>

#include <vector>

namespace lw::volume {

// One piece of the contour, in image coordinates (pixel centres at integers).
struct ContourSegment {
    glm::dvec2 a{0.0};
    glm::dvec2 b{0.0};
};

// Marching squares over `image` at `iso` (real units): a crossing on every cell edge whose ends
// lie on either side (inside: value >= iso), placed by linear interpolation; a saddle cell is
// resolved by the mean of its four corners. Cells with a corner outside the volume (NaN) have
// no contour.
std::vector<ContourSegment> isoContour(const SliceImage& image, double iso);

} // namespace lw::volume
