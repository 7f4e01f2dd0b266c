#pragma once

#include "lw/volume/volume.h"

#include <glm/glm.hpp>
#include <vector>

namespace lw::volume {

// A brick is a box of marching-cubes cells. Cell (i,j,k) spans voxels i..i+1, j..j+1, k..k+1,
// so a brick of cells [cellBegin, cellEnd) reads voxels [cellBegin, cellEnd] (the +1 apron that
// marching cubes needs) and, for central-difference gradients at those voxels, one more voxel on
// every side: [cellBegin - 1, cellEnd + 1], clamped to the volume.
//
//      gradient apron   cells of the brick     gradient apron
//   |  cellBegin-1  | cellBegin ... cellEnd-1 | cellEnd | cellEnd+1 |
//                   ^------- corners read by marching cubes -------^
//
// minValue/maxValue cover the corner voxels only: a brick can hold part of the surface of
// `iso` (inside = value >= iso) only when minValue < iso <= maxValue.
struct Brick {
    glm::ivec3 cellBegin{0};
    glm::ivec3 cellEnd{0};
    float minValue = 0.0f; // stored units
    float maxValue = 0.0f;

    glm::ivec3 cellCount() const { return cellEnd - cellBegin; }
    bool mayContainSurface(double storedIso) const {
        return double(minValue) < storedIso && storedIso <= double(maxValue);
    }
    // Voxel box [begin, end) that marching cubes with central-difference gradients reads.
    glm::ivec3 readBegin() const { return glm::max(cellBegin - 1, glm::ivec3(0)); }
    glm::ivec3 readEnd(glm::ivec3 dims) const { return glm::min(cellEnd + 2, dims); }
};

class BrickGrid {
public:
    BrickGrid() = default;
    // Cuts the cell grid (dims - 1) into bricks of at most `brickCells` cells per axis and
    // computes each brick's min/max in parallel. brickCells >= the cell grid gives one brick:
    // the whole-volume case is the one-brick schedule.
    static BrickGrid build(const Volume& volume, glm::ivec3 brickCells);
    // What an extraction over bricks of `brickCells` takes: build()'s grid, except where one
    // brick covers the volume (the whole-volume schedule). That brick's min/max could only skip
    // an extraction with no surface at all, which the extraction's own first pass finds empty;
    // the scan reads every voxel, and a volume made anew per iso-value (the thick-slice field)
    // would pay it at every iso-value -- 43 MB on the demo, 4-10 ms on one thread. So the one
    // brick is not scanned: its bounds are -inf and +inf, and it may always hold the surface.
    static BrickGrid forExtraction(const Volume& volume, glm::ivec3 brickCells);

    const std::vector<Brick>& bricks() const { return m_bricks; }
    glm::ivec3 brickCells() const { return m_brickCells; }
    glm::ivec3 gridSize() const { return m_gridSize; }
    // Bricks that may hold part of the surface at `storedIso`.
    std::vector<int> activeBricks(double storedIso) const;

private:
    // The bricks of `brickCells` over a volume of `dims`, their min/max not yet set.
    static BrickGrid partition(glm::ivec3 dims, glm::ivec3 brickCells);
    // Each brick's min/max over its corner voxels, in parallel.
    void scanBounds(const Volume& volume);

    std::vector<Brick> m_bricks;
    glm::ivec3 m_brickCells{0};
    glm::ivec3 m_gridSize{0};
};

} // namespace lw::volume
