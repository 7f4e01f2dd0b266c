#pragma once

// A 3D DDA through the cells of a volume's grid, in the grid's own coordinates, for the ray-cast
// visibility test of method 2.
//
// Grid coordinates u = (i, j, s): i and j are the fractional voxel indices and s the distance
// along the stack axis from slice 0 (mm). With M = [spacingI * axisI | spacingJ * axisJ |
// stackAxis]
//   patient = origin + M u
// holds for every geometry VolumeGeometry describes, tilted (sheared) and unevenly spaced stacks
// included, because the slice offset is the only non-linear part of index -> patient and s is
// that offset itself. A straight ray in patient space is therefore a straight ray in u, and the
// cell walls are at integer i, integer j and s = offset(k): the walk needs no per-slab inverse.

#include "lw/volume/volume.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <limits>
#include <vector>

namespace lw::kernels::cpu {

// Where the walk crossed a cell wall.
struct CellExit {
    glm::ivec3 cell{0};    // the cell being left: it spans voxels cell .. cell + 1
    int axis = 0;          // 0, 1, 2: the wall is perpendicular to i, j or s
    int wall = 0;          // voxel plane of the wall along `axis` (cell[axis] or cell[axis] + 1)
    double t = 0.0;        // ray parameter of the exit point
    glm::dvec3 point{0.0}; // grid coordinates of the exit point
};

class VoxelRayGrid {
public:
    VoxelRayGrid() = default;
    explicit VoxelRayGrid(const volume::Volume& volume) {
        const auto& g = volume.geometry();
        m_dims = volume.dims();
        m_origin = g.origin();
        m_offsets.resize(std::size_t(std::max(m_dims.z, 1)));
        for (int k = 0; k < m_dims.z; ++k)
            m_offsets[std::size_t(k)] = g.sliceOffset(double(k));
        glm::dvec3 stack = g.stackAxis();
        // Slices stored against the stack direction: flip s so the walls increase with k.
        if (m_dims.z > 1 && m_offsets.back() < m_offsets.front()) {
            stack = -stack;
            for (double& o : m_offsets)
                o = -o;
        }
        const glm::dmat3 frame(g.spacingI() * g.axisI(), g.spacingJ() * g.axisJ(), stack);
        m_toGrid = glm::inverse(frame);
        m_toPatient = frame;
    }

    glm::ivec3 dims() const { return m_dims; }
    glm::ivec3 cellCount() const { return glm::max(m_dims - 1, glm::ivec3(0)); }
    glm::dvec3 toGrid(glm::dvec3 patient) const { return m_toGrid * (patient - m_origin); }
    glm::dvec3 directionToGrid(glm::dvec3 patientDirection) const {
        return m_toGrid * patientDirection;
    }
    glm::dvec3 toPatient(glm::dvec3 grid) const { return m_origin + m_toPatient * grid; }
    double offset(int k) const { return m_offsets[std::size_t(k)]; }
    // Fractional slice index of grid coordinate s inside slab k (k .. k+1).
    double sliceFraction(double s, int k) const {
        const double gap = m_offsets[std::size_t(k) + 1] - m_offsets[std::size_t(k)];
        return gap > 0.0 ? (s - m_offsets[std::size_t(k)]) / gap : 0.0;
    }

    // The cell holding grid point u, or false when u lies outside the cell grid. Points on a
    // wall go to the cell on the side `direction` points to, so a walk starting on a wall
    // begins in the cell it enters.
    bool cellOf(glm::dvec3 u, glm::dvec3 direction, glm::ivec3& cell) const {
        const glm::ivec3 cells = cellCount();
        if (cells.x < 1 || cells.y < 1 || cells.z < 1)
            return false;
        for (int a = 0; a < 2; ++a) {
            double f = std::floor(u[a]);
            if (f == u[a] && direction[a] < 0.0)
                f -= 1.0;
            if (!(u[a] >= 0.0 && u[a] <= double(cells[a])) || f < 0.0 || f >= double(cells[a]))
                return false;
            cell[a] = int(f);
        }
        if (!(u.z >= m_offsets.front() && u.z <= m_offsets.back()))
            return false;
        // First wall strictly above s (or at s when walking down).
        const auto it = direction.z < 0.0
                            ? std::lower_bound(m_offsets.begin(), m_offsets.end(), u.z)
                            : std::upper_bound(m_offsets.begin(), m_offsets.end(), u.z);
        const int k = int(it - m_offsets.begin()) - 1;
        if (k < 0 || k >= cells.z)
            return false;
        cell.z = k;
        return true;
    }

    // Walks the cells along u(t) = start + t * direction for t in [0, tMax], calling
    // onExit(const CellExit&) at every wall the ray leaves a cell through, in order; onExit
    // returns false to stop the walk. Returns false when stopped that way, true when the ray
    // left the grid or reached tMax. Simultaneous walls (edges, corners) are reported one
    // after the other with the same t. No allocation.
    template <typename OnExit>
    bool walk(glm::dvec3 start, glm::dvec3 direction, double tMax, OnExit&& onExit) const {
        glm::ivec3 cell;
        if (!cellOf(start, direction, cell))
            return true;
        const glm::ivec3 cells = cellCount();
        constexpr double kInf = std::numeric_limits<double>::infinity();
        int step[3];
        double next[3]; // t of the next wall per axis
        double inv[3];
        for (int a = 0; a < 3; ++a) {
            step[a] = direction[a] > 0.0 ? 1 : (direction[a] < 0.0 ? -1 : 0);
            inv[a] = step[a] != 0 ? 1.0 / direction[a] : 0.0;
        }
        auto wall = [&](int a, int c) { return a < 2 ? double(c) : m_offsets[std::size_t(c)]; };
        for (int a = 0; a < 3; ++a)
            next[a] = step[a] == 0 ? kInf
                                   : (wall(a, cell[a] + (step[a] > 0 ? 1 : 0)) - start[a]) * inv[a];
        for (;;) {
            int axis = 0;
            if (next[1] < next[axis])
                axis = 1;
            if (next[2] < next[axis])
                axis = 2;
            const double t = next[axis];
            if (t > tMax || t == kInf)
                return true;
            CellExit exit;
            exit.cell = cell;
            exit.axis = axis;
            exit.t = t;
            exit.wall = cell[axis] + (step[axis] > 0 ? 1 : 0);
            exit.point = start + t * direction;
            // Exact wall coordinate, so interpolation on the wall sees no round-off across it.
            exit.point[axis] = wall(axis, exit.wall);
            if (!onExit(exit))
                return false;
            cell[axis] += step[axis];
            if (cell[axis] < 0 || cell[axis] >= cells[axis])
                return true;
            next[axis] =
                (wall(axis, cell[axis] + (step[axis] > 0 ? 1 : 0)) - start[axis]) * inv[axis];
        }
    }

private:
    glm::ivec3 m_dims{0};
    glm::dvec3 m_origin{0.0};
    glm::dmat3 m_toGrid{1.0};
    glm::dmat3 m_toPatient{1.0};
    std::vector<double> m_offsets{0.0};
};

} // namespace lw::kernels::cpu
