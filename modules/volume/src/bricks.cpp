#include "lw/volume/bricks.h"

#include "lw/core/parallel.h"

#include <algorithm>
#include <limits>

namespace lw::volume {

BrickGrid BrickGrid::partition(glm::ivec3 dims, glm::ivec3 brickCells) {
    BrickGrid grid;
    const glm::ivec3 cells = glm::max(dims - 1, glm::ivec3(0));
    if (cells.x == 0 || cells.y == 0 || cells.z == 0)
        return grid;
    grid.m_brickCells = glm::clamp(brickCells, glm::ivec3(1), cells);
    grid.m_gridSize = (cells + grid.m_brickCells - 1) / grid.m_brickCells;
    for (int bz = 0; bz < grid.m_gridSize.z; ++bz)
        for (int by = 0; by < grid.m_gridSize.y; ++by)
            for (int bx = 0; bx < grid.m_gridSize.x; ++bx) {
                Brick brick;
                brick.cellBegin = glm::ivec3(bx, by, bz) * grid.m_brickCells;
                brick.cellEnd = glm::min(brick.cellBegin + grid.m_brickCells, cells);
                grid.m_bricks.push_back(brick);
            }
    return grid;
}

BrickGrid BrickGrid::forExtraction(const Volume& volume, glm::ivec3 brickCells) {
    BrickGrid grid = partition(volume.dims(), brickCells);
    if (grid.m_bricks.size() != 1) {
        grid.scanBounds(volume);
        return grid;
    }
    grid.m_bricks[0].minValue = -std::numeric_limits<float>::infinity();
    grid.m_bricks[0].maxValue = std::numeric_limits<float>::infinity();
    return grid;
}

BrickGrid BrickGrid::build(const Volume& volume, glm::ivec3 brickCells) {
    BrickGrid grid = partition(volume.dims(), brickCells);
    grid.scanBounds(volume);
    return grid;
}

void BrickGrid::scanBounds(const Volume& volume) {
    dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        const T* voxels = volume.dataAs<T>();
        core::parallelFor(m_bricks.size(), [&](std::size_t b) {
            Brick& brick = m_bricks[b];
            T lo = voxels[volume.index(brick.cellBegin.x, brick.cellBegin.y, brick.cellBegin.z)];
            T hi = lo;
            // Corner voxels of the brick's cells: [cellBegin, cellEnd] inclusive.
            for (int z = brick.cellBegin.z; z <= brick.cellEnd.z; ++z)
                for (int y = brick.cellBegin.y; y <= brick.cellEnd.y; ++y) {
                    const T* row = voxels + volume.index(0, y, z);
                    for (int x = brick.cellBegin.x; x <= brick.cellEnd.x; ++x) {
                        lo = std::min(lo, row[x]);
                        hi = std::max(hi, row[x]);
                    }
                }
            brick.minValue = float(lo);
            brick.maxValue = float(hi);
        });
    });
}

std::vector<int> BrickGrid::activeBricks(double storedIso) const {
    std::vector<int> active;
    for (std::size_t i = 0; i < m_bricks.size(); ++i)
        if (m_bricks[i].mayContainSurface(storedIso))
            active.push_back(int(i));
    return active;
}

} // namespace lw::volume
