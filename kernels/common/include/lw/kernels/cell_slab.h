#pragma once

// One slab of the streamed (L) marching cubes: the cells a slab covers, and so the voxels that
// go to the device for it. Cells are numbered like voxels (cell (i, j, k) spans voxels i..i+1,
// j..j+1, k..k+1); a slab is every cell along x of the rows and layers below:
//
//      z (layers)          layers [layers.x, layers.y) along z,
//      ^  +-----------+    rows   [rows.x,   rows.y)   along y within them,
//      |  |  rows     |    every cell along x.
//      |  +-----------+    Rows outside hold no part of the surface (their corners' min/max
//      +-------------> y   exclude the iso-value), so leaving them out changes no triangle.
//
// Uploaded box: the corner voxels plus the one-voxel gradient apron, clamped to the volume:
// z [layers.x - 1, layers.y + 2), y [rows.x - 1, rows.y + 2), x whole rows (so each slice's part
// of the box is one contiguous run of host memory).

#include <glm/glm.hpp>

namespace lw::kernels {

struct CellSlab {
    glm::ivec2 layers{0}; // cell layers [first, end) along z
    glm::ivec2 rows{0};   // cell rows [first, end) along y
};

} // namespace lw::kernels
