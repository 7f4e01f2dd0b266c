#pragma once

// Method 2's voxel ray stepping and visibility rule, host+device: the CPU back-end
// (kernels/cpu/voxel_ray.h, raycast_silhouette_cpu.cpp) and the CUDA one call these same
// functions, so a silhouette point is visible on one exactly when it is on the other.
//
// Grid coordinates u = (i, j, s): i and j are the fractional voxel indices and s the distance
// along the stack axis from slice 0 (mm). With M = [spacingI * axisI | spacingJ * axisJ |
// stackAxis]
//   patient = origin + M u
// holds for every geometry VolumeGeometry describes, tilted (sheared) and unevenly spaced stacks
// included, because the slice offset is the only non-linear part of index -> patient and s is
// that offset itself. A straight ray in patient space is therefore a straight ray in u, and the
// cell walls are at integer i, integer j and s = offset(k): the walk needs no per-slab inverse.

#include "lw/kernels/host_device.h"
#include "lw/kernels/voxel_grid.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

namespace lw::kernels {

// Where the walk crossed a cell wall.
struct CellExit {
    glm::ivec3 cell{0};    // the cell being left: it spans voxels cell .. cell + 1
    int axis = 0;          // 0, 1, 2: the wall is perpendicular to i, j or s
    int wall = 0;          // voxel plane of the wall along `axis` (cell[axis] or cell[axis] + 1)
    double t = 0.0;        // ray parameter of the exit point
    glm::dvec3 point{0.0}; // grid coordinates of the exit point
};

// The grid as the walk sees it: plain values and one pointer (host or device memory).
struct RayGridView {
    glm::ivec3 dims{0};
    glm::dvec3 origin{0.0};
    glm::dmat3 toGrid{1.0};
    const double* offsets = nullptr; // per slice, increasing (s of wall k); at least one entry
    int offsetCount = 1;
    // (offsetCount - 1) / (last offset - first): the slab a coordinate falls in on an evenly
    // spaced stack, as a first guess that cellOf checks against the offsets (0: no guess).
    double slabGuessScale = 0.0;

    LW_HOST_DEVICE glm::ivec3 cellCount() const {
        return glm::ivec3(dims.x > 1 ? dims.x - 1 : 0, dims.y > 1 ? dims.y - 1 : 0,
                          dims.z > 1 ? dims.z - 1 : 0);
    }
    LW_HOST_DEVICE glm::dvec3 toGridPoint(glm::dvec3 patient) const {
        return toGrid * (patient - origin);
    }
    LW_HOST_DEVICE glm::dvec3 directionToGrid(glm::dvec3 patientDirection) const {
        return toGrid * patientDirection;
    }
    // Fractional slice index of grid coordinate s inside slab k (k .. k+1).
    LW_HOST_DEVICE double sliceFraction(double s, int k) const {
        const double gap = offsets[k + 1] - offsets[k];
        return gap > 0.0 ? (s - offsets[k]) / gap : 0.0;
    }
    LW_HOST_DEVICE double wall(int axis, int c) const { return axis < 2 ? double(c) : offsets[c]; }

    // The cell holding grid point u, or false when u lies outside the cell grid. Points on a
    // wall go to the cell on the side `direction` points to, so a walk starting on a wall
    // begins in the cell it enters.
    LW_HOST_DEVICE bool cellOf(glm::dvec3 u, glm::dvec3 direction, glm::ivec3& cell) const {
        const glm::ivec3 cells = cellCount();
        if (cells.x < 1 || cells.y < 1 || cells.z < 1)
            return false;
        for (int a = 0; a < 2; ++a) {
            double f = floor(u[a]);
            if (f == u[a] && direction[a] < 0.0)
                f -= 1.0;
            if (!(u[a] >= 0.0 && u[a] <= double(cells[a])) || f < 0.0 || f >= double(cells[a]))
                return false;
            cell[a] = int(f);
        }
        if (!(u.z >= offsets[0] && u.z <= offsets[offsetCount - 1]))
            return false;
        const int k = slabOf(u.z, direction.z < 0.0);
        if (k < 0 || k >= cells.z)
            return false;
        cell.z = k;
        return true;
    }

    // The last wall at or below s (strictly below when walking down), -1 for none: the upper
    // (lower) bound of s in the offsets, less one. The walk asks at every macro cell; on an evenly
    // spaced stack the guess from slabGuessScale or a neighbour of it is that wall, which the
    // offsets confirm (the answer is unique, so it is the search's bit for bit); otherwise, or
    // when the guess misses, a binary search.
    LW_HOST_DEVICE int slabOf(double s, bool down) const {
        auto atOrBelow = [&](int m) { return down ? offsets[m] < s : offsets[m] <= s; };
        if (slabGuessScale > 0.0) {
            const double guess = (s - offsets[0]) * slabGuessScale;
            if (guess > -1.0 && guess < double(offsetCount)) {
                const int g = int(guess);
                for (int m = g > 0 ? g - 1 : 0; m <= g + 1 && m < offsetCount; ++m)
                    if (atOrBelow(m) && (m + 1 == offsetCount || !atOrBelow(m + 1)))
                        return m;
            }
        }
        int lo = 0, hi = offsetCount;
        while (lo < hi) {
            const int mid = lo + (hi - lo) / 2;
            if (atOrBelow(mid))
                lo = mid + 1;
            else
                hi = mid;
        }
        return lo - 1;
    }

    // Where the ray u(t) = start + t * direction, t in [tMin, tMax], enters the box of the cell
    // grid when it starts outside it: `t` and the axis of the border wall it enters through.
    // False when it does not enter (or starts inside: no wall to enter through).
    LW_HOST_DEVICE bool entry(glm::dvec3 start, glm::dvec3 direction, double tMin, double tMax,
                              double& t, int& axis) const {
        const glm::ivec3 cells = cellCount();
        const glm::dvec3 lo(0.0, 0.0, offsets[0]);
        const glm::dvec3 hi(double(cells.x), double(cells.y), offsets[offsetCount - 1]);
        double enter = tMin, leave = tMax;
        axis = -1;
        for (int a = 0; a < 3; ++a) {
            if (direction[a] == 0.0) {
                if (start[a] < lo[a] || start[a] > hi[a])
                    return false;
                continue;
            }
            double t0 = (lo[a] - start[a]) / direction[a], t1 = (hi[a] - start[a]) / direction[a];
            if (t0 > t1) {
                const double swap = t0;
                t0 = t1;
                t1 = swap;
            }
            if (t0 > enter) {
                enter = t0;
                axis = a;
            }
            leave = t1 < leave ? t1 : leave;
        }
        t = enter;
        return axis >= 0 && enter <= leave;
    }

    // Walks the cells along u(t) = start + t * direction for t in [0, tMax], calling
    // onExit(const CellExit&) at every wall the ray leaves a cell through, in order; onExit
    // returns false to stop the walk. Returns false when stopped that way, true when the ray
    // left the grid or reached tMax. Simultaneous walls (edges, corners) are reported one
    // after the other with the same t. No allocation.
    template <typename OnExit>
    LW_HOST_DEVICE bool walk(glm::dvec3 start, glm::dvec3 direction, double tMax,
                             OnExit&& onExit) const {
        glm::ivec3 cell;
        if (!cellOf(start, direction, cell))
            return true;
        return walkFrom(cell, start, direction, tMax, onExit);
    }
    // walk() from `cell`, which is cellOf(start, direction) (a caller that has it already).
    template <typename OnExit>
    LW_HOST_DEVICE bool walkFrom(glm::ivec3 cell, glm::dvec3 start, glm::dvec3 direction,
                                 double tMax, OnExit&& onExit) const {
        const glm::ivec3 cells = cellCount();
        const double kInf = HUGE_VAL;
        int step[3];
        double next[3]; // t of the next wall per axis
        double inv[3];
        for (int a = 0; a < 3; ++a) {
            step[a] = direction[a] > 0.0 ? 1 : (direction[a] < 0.0 ? -1 : 0);
            inv[a] = step[a] != 0 ? 1.0 / direction[a] : 0.0;
        }
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
};

// The paper's visibility test for a point on the surface, with empty-space skipping: a ray from
// the point toward the viewer, walked cell by cell; occluded when the bilinearly interpolated
// value on a wall the ray leaves a cell through is inside (>= iso).
//
// Self-occlusion rule: the ray starts kStartOffsetCells off the point toward the viewer, and
// walls are not tested until the ray has left the cell it starts in and travelled at least
// kSelfSkipCells cell widths (measured in grid units); from there any inside wall occludes. A
// silhouette point lies on a chord of the interpolated surface and its ray runs tangent to it;
// near the start the ray stays within a hair of the trilinear surface, where round-off and the
// difference between the linear mesh and the trilinear field would hide it. (A grazing zone of
// two cells, where a wall had to be inside by a tenth of its corners' spread to occlude, was
// there before the neighbour ray; with the neighbour ray it only drew terrace rims that method 3
// hides, and the analytic sweep is the same without it: kernels/common/README.md, "Method 2's
// ray walk".) Rays leaving the grid, or reaching the eye, are visible; a ray
// that starts outside it (a neighbour ray shifted past the border) is walked from where it enters
// it, and entering through an inside border wall crosses the cap that closes the surface there.
//
// The neighbour ray: a point whose own ray is occluded within the reach (neighbourReachCells) is
// still visible when the ray from kNeighbourPixels pixel beside it, on the outward side of the
// surface across the view, reaches the eye; that ray starts off the surface and is tested from its
// start, with no self-occlusion zone. It is method 3's rule (a line pixel is visible when a pixel
// of its 3 x 3 neighbourhood sees the surface at or behind it) and the contour score's 1 px
// tolerance, applied where the occluder is the point's own surface. Thick slices need it: slabs
// of several mm leave the surface terraced, and there the silhouette (where the interpolated
// gradient is normal to the view) does not lie where the surface is edge-on, so at the outline
// the point's own ray runs inside the surface for mm (demo CT, 0.49 x 0.49 x 5.6 mm: 2-8 mm,
// shallow or deep), past any self-occlusion zone, while the ray a pixel outside passes. (Since the
// slab edges' own differences set the normals' slab component, mcThickSlabEdge, the contour lies
// on the mesh's outline, but the terraces stay: without the neighbour ray method 2's outline on
// 2.4-5.6 mm series still falls to 0.80-0.92 of the shaded panel's.) An occluder further away
// is another surface. The terraces are as deep as a slab is thick against the pixels, so the
// reach is that ratio in cells, at least one and at most kNeighbourReachCells: eight cells on
// the 5.6 mm demo, one on an isotropic grid, where a block within a few cells is a real occluder
// and the second walk is cost for nothing (the benchmark phantom: 79 % of the points asked
// within eight cells, 2.6 % of them turned visible). Between the two it is a trade of outline
// against rays: dicom2stl's 4 mm CT (reach 3.2) at reach 8 draws its worst view's outline 0.993
// instead of 0.983, with the same agreement with method 3, for a visibility stage some 15 %
// slower. An oversampled volume (volume/oversampling.h) holds its original grid's field, so its
// terraces are as deep as the original slabs: the caller passes the ratio of those
// (kernels/cpu VoxelRayGrid::neighbourReach); with the finer slabs' own ratio dicom2stl's 4 mm CT
// split in two drew its outline at 24 of 32 views. A grid coarse in plane (VTK's quarter head,
// 3.2 mm pixels on 1.5 mm slices) is terraced in plane: the reach is then its pixel against its
// slab -- in general the coarsest original cell against the finest cell.
//
// Empty-space skipping: macro cells of kMacroCells^3 cells that hold no inside voxel cannot
// occlude (a bilinear wall value is a convex combination of its corners); the walk crosses them
// in one jump.
struct RayVisibilityRule {
    static constexpr double kStartOffsetCells = 1e-4;
    // Half of what the rule had before the neighbour ray: with it, real CT loses no outline and
    // the demo's worst agreement with method 3 improves; the analytic sweep is unchanged
    // (kernels/common/README.md, "Method 2's ray walk").
    static constexpr double kSelfSkipCells = 0.5;
    static constexpr int kMacroCells = 8;
    // Coarse blocks of kCoarseMacros^3 macro cells (32^3 cells): a ray through empty space
    // (air around the head, the brain at a bone iso-value) jumps a block at a time.
    static constexpr int kCoarseMacros = 4;
    static constexpr int kCoarseCells = kMacroCells * kCoarseMacros;
    static constexpr double kNeighbourPixels = 1.0;
    static constexpr double kNeighbourReachCells = 8.0;
};

// The neighbour ray's reach (cells) on a grid whose slabs are `slabOverPixel` times as thick as
// its pixels are wide (see RayVisibilityRule).
LW_HOST_DEVICE inline double neighbourReachCells(double slabOverPixel) {
    const double most = RayVisibilityRule::kNeighbourReachCells;
    return slabOverPixel > most ? most : (slabOverPixel > 1.0 ? slabOverPixel : 1.0);
}

// One pixel's width in mm at unit distance from the eye (perspective) or anywhere
// (orthographic), from the camera's half height (tan of the half angle, or mm) and its height
// in pixels: RayVisibility::pixelSpan, computed alike by every back-end.
LW_HOST_DEVICE inline double rayPixelSpan(double halfHeight, int height) {
    return height > 0 ? 2.0 * halfHeight / double(height) : 0.0;
}

// Index of `p` in a grid of `dims`, x fastest (the macro and coarse occupancy grids).
LW_HOST_DEVICE inline std::size_t occupancyIndex(glm::ivec3 p, glm::ivec3 dims) {
    return std::size_t(p.x) +
           std::size_t(dims.x) * (std::size_t(p.y) + std::size_t(dims.y) * std::size_t(p.z));
}

// The coarse occupancy grid's size, and whether coarse block `coarse` holds an occupied macro
// cell: built from the macro grid by every back-end alike.
LW_HOST_DEVICE inline glm::ivec3 coarseDimsOf(glm::ivec3 macroDims) {
    const int n = RayVisibilityRule::kCoarseMacros;
    return (macroDims + n - 1) / n;
}
LW_HOST_DEVICE inline std::uint8_t coarseOccupancy(const std::uint8_t* macroOccupied,
                                                   glm::ivec3 macroDims, glm::ivec3 coarse) {
    const int n = RayVisibilityRule::kCoarseMacros;
    const glm::ivec3 first = coarse * n;
    const glm::ivec3 last = glm::min(first + n, macroDims);
    for (int z = first.z; z < last.z; ++z)
        for (int y = first.y; y < last.y; ++y)
            for (int x = first.x; x < last.x; ++x)
                if (macroOccupied[occupancyIndex({x, y, z}, macroDims)])
                    return 1;
    return 0;
}

template <typename T> struct RayVisibility {
    const T* voxels = nullptr;
    GridDims dims;
    RayGridView grid;
    const std::uint8_t* macroOccupied = nullptr; // per macro cell: holds a voxel >= iso
    glm::ivec3 macroDims{0};
    const std::uint8_t* coarseOccupied = nullptr; // per coarse block (null: no coarse jumps)
    glm::ivec3 coarseDims{0};
    glm::dvec3 cellScale{1.0}; // cell widths in grid units (i, j, s)
    double iso = 0.0;
    double pixelSpan = 0.0; // rayPixelSpan(); 0: no neighbour ray
    double neighbourReach = RayVisibilityRule::kNeighbourReachCells; // neighbourReachCells()

    using Rule = RayVisibilityRule;

    LW_HOST_DEVICE std::size_t voxelIndex(int x, int y, int z) const {
        return std::size_t(x) + dims.sy * std::size_t(y) + dims.sz * std::size_t(z);
    }
    LW_HOST_DEVICE std::size_t macroIndex(glm::ivec3 cell) const {
        return occupancyIndex(cell / Rule::kMacroCells, macroDims);
    }
    // Grid coordinate of the wall of `block` (blocks of `cells`^3 cells: macro cells or coarse
    // blocks) that a ray going along du leaves through on `axis`.
    LW_HOST_DEVICE double blockWall(glm::ivec3 block, glm::dvec3 du, int axis, int cells) const {
        const int cellsOnAxis = axis == 0 ? dims.cx : (axis == 1 ? dims.cy : dims.cz);
        const int end = (block[axis] + 1) * cells;
        const int c =
            du[axis] > 0.0 ? (end < cellsOnAxis ? end : cellsOnAxis) : block[axis] * cells;
        return grid.wall(axis, c);
    }
    // Ray parameter (from `from`) where the ray leaves `block`, and through which axis.
    LW_HOST_DEVICE double blockExit(glm::ivec3 block, glm::dvec3 from, glm::dvec3 du, int cells,
                                    int& axis) const {
        double best = 1e308;
        bool any = false;
        for (int a = 0; a < 3; ++a) {
            if (du[a] == 0.0)
                continue;
            const double t = (blockWall(block, du, a, cells) - from[a]) / du[a];
            if (!any || t < best) {
                best = t;
                axis = a;
                any = true;
            }
        }
        if (!any)
            return HUGE_VAL;
        return best > 0.0 ? best : 0.0;
    }
    // The empty block the walk may jump from `cell`: the coarse block when it is empty, else the
    // macro cell when that is; `cells` 0 when the macro cell is occupied (walk cell by cell).
    // A jump of length 0 would not progress: then the next smaller block is tried.
    LW_HOST_DEVICE double emptyBlockExit(glm::ivec3 cell, glm::dvec3 from, glm::dvec3 du,
                                         glm::ivec3& block, int& cells, int& axis) const {
        cells = 0;
        if (macroOccupied[macroIndex(cell)])
            return 0.0;
        if (coarseOccupied) {
            const glm::ivec3 coarse = cell / Rule::kCoarseCells;
            if (!coarseOccupied[occupancyIndex(coarse, coarseDims)]) {
                const double t = blockExit(coarse, from, du, Rule::kCoarseCells, axis);
                if (t > 0.0) {
                    block = coarse;
                    cells = Rule::kCoarseCells;
                    return t;
                }
            }
        }
        block = cell / Rule::kMacroCells;
        const double t = blockExit(block, from, du, Rule::kMacroCells, axis);
        cells = t > 0.0 ? Rule::kMacroCells : 0;
        return t;
    }

    // Bilinear value on the wall the ray leaves through (stored units).
    LW_HOST_DEVICE double wallValue(const CellExit& exit) const {
        const int a = exit.axis, b = (a + 1) % 3, c = (a + 2) % 3;
        auto fraction = [&](int axis) {
            const double f = axis == 2 ? grid.sliceFraction(exit.point.z, exit.cell.z)
                                       : exit.point[axis] - double(exit.cell[axis]);
            return f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
        };
        const double fb = fraction(b), fc = fraction(c);
        glm::ivec3 v = exit.cell;
        v[a] = exit.wall;
        const std::size_t stride[3] = {1, dims.sy, dims.sz};
        const std::size_t i00 = voxelIndex(v.x, v.y, v.z);
        const std::size_t sb = stride[b], sc = stride[c];
        const double v00 = double(float(voxels[i00])), v10 = double(float(voxels[i00 + sb])),
                     v01 = double(float(voxels[i00 + sc])),
                     v11 = double(float(voxels[i00 + sb + sc]));
        return (1.0 - fc) * ((1.0 - fb) * v00 + fb * v10) + fc * ((1.0 - fb) * v01 + fb * v11);
    }

    LW_HOST_DEVICE bool occludes(const CellExit& exit) const { return wallValue(exit) >= iso; }

    // Unit vector across the view (normal to `toward`) pointing out of the surface at `point`:
    // the gradient of the trilinear field in the cell holding it, negated and projected. Zero
    // where the point lies outside the grid or the gradient runs along the view.
    LW_HOST_DEVICE glm::dvec3 outwardAcrossView(glm::dvec3 point, glm::dvec3 toward) const {
        const glm::dvec3 u = grid.toGridPoint(point);
        glm::ivec3 cell;
        if (!grid.cellOf(u, toward, cell))
            return glm::dvec3(0.0);
        const double fx = u.x - double(cell.x), fy = u.y - double(cell.y);
        const double fz = grid.sliceFraction(u.z, cell.z);
        const double gap = grid.offsets[cell.z + 1] - grid.offsets[cell.z];
        double c[8]; // corner k at cell + (k & 1, k >> 1 & 1, k >> 2 & 1)
        for (int k = 0; k < 8; ++k)
            c[k] = double(float(voxels[voxelIndex(cell.x + (k & 1), cell.y + (k >> 1 & 1),
                                                  cell.z + (k >> 2 & 1))]));
        auto mix = [](double a, double b, double f) { return a + f * (b - a); };
        const double dx =
            mix(mix(c[1] - c[0], c[3] - c[2], fy), mix(c[5] - c[4], c[7] - c[6], fy), fz);
        const double dy =
            mix(mix(c[2] - c[0], c[3] - c[1], fx), mix(c[6] - c[4], c[7] - c[5], fx), fz);
        const double dw =
            mix(mix(c[4] - c[0], c[5] - c[1], fx), mix(c[6] - c[2], c[7] - c[3], fx), fy);
        const glm::dvec3 gridGradient(dx, dy, gap > 0.0 ? dw / gap : 0.0);
        // u = toGrid (p - origin), so the patient gradient is toGrid^T times the grid one.
        glm::dvec3 out = -(glm::transpose(grid.toGrid) * gridGradient);
        const double towardLength = glm::length(toward);
        if (!(towardLength > 0.0))
            return glm::dvec3(0.0);
        const glm::dvec3 view = toward / towardLength;
        out -= glm::dot(out, view) * view;
        const double length = glm::length(out);
        return length > 0.0 ? out / length : glm::dvec3(0.0);
    }

    // `eyeOrDirection`: the eye (perspective) or the unit vector toward the viewer (orthographic).
    // The point's own ray with the self-occlusion rule, then the neighbour ray (see
    // RayVisibilityRule).
    LW_HOST_DEVICE bool visible(glm::dvec3 point, glm::dvec3 eyeOrDirection,
                                bool orthographic) const {
        const OwnRay own = ownRay(point, eyeOrDirection, orthographic);
        return own == OwnRay::Visible ||
               (own == OwnRay::AskNeighbour && neighbourRay(point, eyeOrDirection, orthographic));
    }

    // visible() in two steps, for a back-end that runs the neighbour rays apart (CUDA: in warps of
    // their own, not as a second walk that idles the rest of the point rays' warp).
    enum class OwnRay : unsigned char { Hidden = 0, Visible = 1, AskNeighbour = 2 };
    LW_HOST_DEVICE OwnRay ownRay(glm::dvec3 point, glm::dvec3 eyeOrDirection,
                                 bool orthographic) const {
        double blockedCells = 0.0;
        if (rayReachesEye(point, eyeOrDirection, orthographic, true, &blockedCells))
            return OwnRay::Visible;
        return asksNeighbour(blockedCells) ? OwnRay::AskNeighbour : OwnRay::Hidden;
    }
    LW_HOST_DEVICE bool neighbourRay(glm::dvec3 point, glm::dvec3 eyeOrDirection,
                                     bool orthographic) const {
        glm::dvec3 start;
        return neighbourRayStart(point, eyeOrDirection, orthographic, start) &&
               rayReachesEye(start, eyeOrDirection, orthographic, false);
    }
    // Where the neighbour ray of `point` starts; false when there is none (hidden).
    LW_HOST_DEVICE bool neighbourRayStart(glm::dvec3 point, glm::dvec3 eyeOrDirection,
                                          bool orthographic, glm::dvec3& start) const {
        const glm::dvec3 toward = orthographic ? eyeOrDirection : eyeOrDirection - point;
        const glm::dvec3 out = outwardAcrossView(point, toward);
        if (out == glm::dvec3(0.0))
            return false;
        const double width = pixelSpan * (orthographic ? 1.0 : glm::length(toward));
        start = point + Rule::kNeighbourPixels * width * out;
        return true;
    }
    // Whether a point whose own ray was blocked `blockedCells` away asks the neighbour ray.
    LW_HOST_DEVICE bool asksNeighbour(double blockedCells) const {
        return pixelSpan > 0.0 && !(blockedCells > neighbourReach);
    }

    // A ray that starts outside the grid: a neighbour ray shifted past the border, beside the cap
    // that closes the surface in the border plane. It is walked from where it enters the grid;
    // entering through a border wall whose value is inside crosses the cap. `from`, `tFrom` and
    // `cell` receive the entry (`tFrom` is where the ray may start counting on input).
    static constexpr int kEnteredGrid = 0, kMissesGrid = 1, kBlockedOnEntry = 2;
    LW_HOST_DEVICE int enterGrid(glm::dvec3 u0, glm::dvec3 du, double tMax, glm::dvec3& from,
                                 double& tFrom, glm::ivec3& cell) const {
        double tEnter = 0.0;
        int axis = 0;
        if (!grid.entry(u0, du, tFrom, tMax, tEnter, axis))
            return kMissesGrid;
        const glm::ivec3 cells = grid.cellCount();
        CellExit wall;
        wall.axis = axis;
        wall.wall = du[axis] > 0.0 ? 0 : cells[axis];
        wall.point = u0 + tEnter * du;
        wall.point[axis] = grid.wall(axis, wall.wall);
        if (!grid.cellOf(wall.point, du, cell))
            return kMissesGrid;
        wall.cell = cell;
        from = wall.point;
        tFrom = tEnter;
        return occludes(wall) ? kBlockedOnEntry : kEnteredGrid;
    }

    // One ray's walk between two of its steps (see beginRay / advanceRay): everything the walk
    // carries from one macro cell to the next. A back-end may interleave many rays' steps (CUDA:
    // a lane takes a new ray when its own ends, so short rays do not idle while a long one
    // walks); each ray's result is that of walking it in one go, bit for bit.
    struct RayWalk {
        glm::dvec3 du{0.0};   // direction in grid coordinates
        glm::dvec3 from{0.0}; // where the next step starts, always exactly on a wall entered
        double tFrom = 0.0;
        double tMax = 0.0;
        double tSkip = 0.0; // walls before it do not occlude (self-occlusion rule)
        double cellsPerT = 0.0;
        glm::ivec3 startCell{0};
        bool onSurface = false;
    };
    enum class RayStep : unsigned char { Walking = 0, ReachesEye = 1, Blocked = 2 };

    // The walk of one ray. `onSurface`: the ray starts on the surface, so the self-occlusion rule
    // applies; otherwise every wall counts from the start. `blockedCells` receives how far from
    // the point (in cells) a blocked ray was blocked.
    LW_HOST_DEVICE bool rayReachesEye(glm::dvec3 point, glm::dvec3 eyeOrDirection,
                                      bool orthographic, bool onSurface,
                                      double* blockedCells = nullptr) const {
        RayWalk ray;
        RayStep step = beginRay(point, eyeOrDirection, orthographic, onSurface, ray, blockedCells);
        while (step == RayStep::Walking)
            step = advanceRay(ray, blockedCells);
        return step == RayStep::ReachesEye;
    }

    // The ray's set-up, and its entry into the grid when it starts outside it: Walking when
    // advanceRay has to go on.
    LW_HOST_DEVICE RayStep beginRay(glm::dvec3 point, glm::dvec3 eyeOrDirection, bool orthographic,
                                    bool onSurface, RayWalk& ray, double* blockedCells) const {
        const glm::dvec3 toward = orthographic ? eyeOrDirection : eyeOrDirection - point;
        ray.tMax = orthographic ? HUGE_VAL : 1.0;
        ray.onSurface = onSurface;
        const glm::dvec3 u0 = grid.toGridPoint(point);
        ray.du = grid.directionToGrid(toward);
        ray.cellsPerT = glm::length(ray.du / cellScale);
        if (!(ray.cellsPerT > 0.0))
            return RayStep::ReachesEye;
        const double tStart = Rule::kStartOffsetCells / ray.cellsPerT;
        if (tStart >= ray.tMax)
            return RayStep::ReachesEye;
        ray.tSkip = onSurface ? Rule::kSelfSkipCells / ray.cellsPerT : 0.0;
        // The walk restarts at every macro cell boundary: an empty macro cell is crossed in one
        // jump, an occupied one cell by cell. `from` always lies exactly on the wall entered.
        ray.from = u0 + tStart * ray.du;
        ray.tFrom = tStart;
        if (!grid.cellOf(ray.from, ray.du, ray.startCell)) {
            const int entered = enterGrid(u0, ray.du, ray.tMax, ray.from, ray.tFrom, ray.startCell);
            if (entered == kMissesGrid)
                return RayStep::ReachesEye;
            if (entered == kBlockedOnEntry && ray.tFrom >= ray.tSkip) {
                if (blockedCells)
                    *blockedCells = ray.tFrom * ray.cellsPerT;
                return RayStep::Blocked;
            }
        }
        return RayStep::Walking;
    }

    // One step of the walk: an empty block crossed in one jump, or an occupied macro cell walked
    // cell by cell.
    LW_HOST_DEVICE RayStep advanceRay(RayWalk& ray, double* blockedCells) const {
        glm::ivec3 cell;
        if (!grid.cellOf(ray.from, ray.du, cell))
            return RayStep::ReachesEye;
        const glm::ivec3 macro = cell / Rule::kMacroCells;
        int axis = 0, blockCells = 0;
        glm::ivec3 block;
        const double tExit = emptyBlockExit(cell, ray.from, ray.du, block, blockCells, axis);
        if (blockCells > 0) {
            if (ray.tFrom + tExit >= ray.tMax)
                return RayStep::ReachesEye;
            glm::dvec3 next = ray.from + tExit * ray.du;
            next[axis] = blockWall(block, ray.du, axis, blockCells);
            ray.from = next;
            ray.tFrom += tExit;
            return RayStep::Walking;
        }
        bool occluded = false, moved = false;
        CellExit last;
        grid.walkFrom(cell, ray.from, ray.du, ray.tMax - ray.tFrom, [&](const CellExit& exit) {
            const double t = ray.tFrom + exit.t;
            if ((!ray.onSurface || exit.cell != ray.startCell) && t >= ray.tSkip &&
                occludes(exit)) {
                occluded = true;
                if (blockedCells)
                    *blockedCells = t * ray.cellsPerT;
                return false;
            }
            glm::ivec3 next = exit.cell;
            next[exit.axis] += exit.wall > exit.cell[exit.axis] ? 1 : -1;
            if (next / Rule::kMacroCells != macro) {
                last = exit;
                moved = true;
                return false;
            }
            return true;
        });
        if (occluded)
            return RayStep::Blocked;
        if (!moved)
            return RayStep::ReachesEye;
        ray.from = last.point;
        ray.tFrom += last.t;
        return RayStep::Walking;
    }
};

} // namespace lw::kernels
