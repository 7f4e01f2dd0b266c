#pragma once

// The chunked (L) variant's set-up on the CPU, shared by methods 1 and 3: the volume's brick grid
// (per-brick min/max, one scan of the volume), kept while the brick size stays; the bricks whose
// value range holds the iso-value; and the extractor that turns one brick into its surface piece.
// What a method does with each piece is its own: method 1 uploads and draws it with GL, method 3
// rasterises it on a worker thread.

#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/volume/bricks.h"
#include "lw/volume/volume.h"

#include <cstddef>
#include <vector>

namespace lw::render {

// One frame's pieces, in the grid's order.
struct CpuBrickPass {
    const volume::BrickGrid& grid;
    std::vector<int> active; // indices into grid.bricks()
    kernels::cpu::BrickSurfaceExtractor extractor;

    std::size_t size() const { return active.size(); }
    const volume::Brick& brick(std::size_t i) const {
        return grid.bricks()[std::size_t(active[i])];
    }
};

class CpuBrickSchedule {
public:
    // Forgets the grid, e.g. for a new volume: even one of the same size has other brick ranges.
    void reset() {
        m_grid = volume::BrickGrid{};
        m_brickCells = 0;
    }

    // The pieces of a frame with bricks of `brickCells` cells at `storedIso` (stored units).
    // `rebuildGrid` scans the volume again even for the same brick size (mode b: everything is
    // made anew every frame). The volume must outlive the pass.
    CpuBrickPass pass(const volume::Volume& volume, int brickCells, double storedIso,
                      kernels::GradientStencil stencil, bool rebuildGrid) {
        if (rebuildGrid || m_brickCells != brickCells) {
            m_brickCells = 0; // no half-built grid is taken for a good one if build() throws
            m_grid = volume::BrickGrid::forExtraction(volume, glm::ivec3(brickCells));
            m_brickCells = brickCells;
        }
        return {m_grid, m_grid.activeBricks(storedIso),
                kernels::cpu::BrickSurfaceExtractor(volume, storedIso, stencil)};
    }

private:
    volume::BrickGrid m_grid;
    int m_brickCells = 0; // 0: no grid
};

} // namespace lw::render
