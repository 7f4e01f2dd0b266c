#include "lw/kernels/cpu/marching_cubes_cpu.h"

#include "lw/core/parallel.h"
#include "lw/kernels/marching_cubes.h"

#include <algorithm>
#include <cmath>
#include <limits>

// Two passes over (brick, slab) work units, like flying edges: pass 1 classifies rows and
// counts vertices per row segment and triangles per cell-row segment; an exclusive prefix sum
// over (z, y, brick column) turns the counts into output offsets; pass 2 walks the same rows
// again, gives every crossing edge its id (segment offset + rank in the segment), writes the
// vertices it owns and the triangles of its cells. Because segments are ordered (z, y, x) and
// each brick column covers a contiguous x range, the offsets equal those of the one-brick
// schedule: chunked and whole outputs are the same bytes.
//
// Ownership: voxel (x, y, z) and its three +axis edges belong to the brick whose cell range
// holds it; the voxels on the upper faces of the volume belong to the last brick. Edges a
// brick's cells use on its upper faces belong to the neighbour, whose ids the brick computes
// itself from the neighbour's segment offset (ranks restart at 0 there).

namespace lw::kernels::cpu {
namespace {

// Classification summary of one voxel row over a brick's voxel x range [cb.x, ce.x]:
// the row is constant (== left) on [cb.x, xl] and constant (== right) on [xr, ce.x].
struct RowInfo {
    int xl = 0;               // first x whose +x edge crosses; ce.x when none
    int xr = 0;               // last such x + 1; cb.x when none
    std::uint32_t xCross = 0; // crossing +x edges with x in [cb.x, ce.x)
    std::uint8_t left = 0;
    std::uint8_t right = 0;
};

// The cells of one cell row (y, z) that cut the surface: [begin, end) in Unit::cellX/cellCase.
struct CellRow {
    int y = 0, z = 0;
    std::uint32_t begin = 0, end = 0;
};

struct Unit {
    int brick = 0;
    int z0 = 0, z1 = 0;       // cell layers [z0, z1)
    int rowY1 = 0, rowZ1 = 0; // rows y in [cb.y, rowY1], z in [z0, rowZ1]
    std::vector<RowInfo> rows;
    // Pass 1 keeps the cases of the cutting cells so pass 2 neither re-classifies nor scans
    // the empty cells between them.
    std::vector<CellRow> cellRows;
    std::vector<int> cellX;
    std::vector<std::uint8_t> cellCase;
};

template <typename T> class Extractor {
public:
    Extractor(const volume::Volume& volume, const volume::BrickGrid& grid, double iso,
              McOutput& out, GradientStencil stencil)
        : m_volume(volume), m_grid(grid), m_voxels(volume.dataAs<T>()), m_iso(iso),
          m_isoF(insideThreshold(iso)), m_out(out), m_dims(makeGridDims(volume.dims())),
          m_threshold(voxelInsideThreshold<T>(iso)),
          m_voxelGrid(voxelGridSetup(volume, stencil)), m_gradient{m_voxels, m_voxelGrid.spans()} {
        m_gx = grid.gridSize().x;
        m_brickCells = grid.brickCells();
    }

    McResult run(unsigned threads, const core::CancelToken* cancel, const McOutputBudget& budget) {
        McResult result;
        // Units not started once the token is set are skipped; the phase ends and reports it.
        const auto cancelled = [cancel] { return cancel && cancel->isCancelled(); };
        const auto stop = [&] {
            clearOutput();
            result.status = McStatus::Cancelled;
            return result;
        };
        result.totalBricks = m_grid.bricks().size();
        if (m_dims.cx < 1 || m_dims.cy < 1 || m_dims.cz < 1 || result.totalBricks == 0) {
            clearOutput();
            return result;
        }
        const std::vector<int> active = m_grid.activeBricks(m_iso);
        result.activeBricks = active.size();
        if (active.empty()) {
            clearOutput();
            return result;
        }
        makeUnits(active, threads == 0 ? core::workerCount() : threads);
        result.workUnits = m_units.size();

        m_vertexOffset.assign(std::size_t(m_dims.nz) * std::size_t(m_dims.ny) * std::size_t(m_gx),
                              0u);
        m_triangleOffset.assign(std::size_t(m_dims.cz) * std::size_t(m_dims.cy) * std::size_t(m_gx),
                                0u);
        core::parallelFor(
            m_units.size(),
            [&](std::size_t u) {
                if (!cancelled())
                    countUnit(m_units[u]);
            },
            threads);
        if (cancelled())
            return stop();

        const std::uint64_t vertices = exclusiveScan(m_vertexOffset);
        const std::uint64_t triangles = exclusiveScan(m_triangleOffset);
        result.vertices = vertices;
        result.triangles = triangles;
        if (vertices > std::numeric_limits<std::uint32_t>::max() ||
            triangles > std::numeric_limits<std::uint32_t>::max() / 3)
            result.status = McStatus::TooManyVertices;
        else if (meshBytes(vertices + budget.spareVertices, triangles + budget.spareTriangles) >
                 budget.maxBytes)
            result.status = McStatus::OverByteLimit;
        if (result.status != McStatus::Ok) {
            clearOutput();
            return result;
        }
        // resize() keeps existing elements: a reused buffer of the right size is not rewritten.
        m_out.positions.reserve(std::size_t(vertices) + budget.spareVertices);
        m_out.normals.reserve(std::size_t(vertices) + budget.spareVertices);
        m_out.indices.reserve((std::size_t(triangles) + budget.spareTriangles) * 3);
        m_out.positions.resize(std::size_t(vertices));
        m_out.normals.resize(std::size_t(vertices));
        m_out.indices.resize(std::size_t(triangles) * 3);
        core::parallelFor(
            m_units.size(),
            [&](std::size_t u) {
                if (!cancelled())
                    emitUnit(m_units[u]);
            },
            threads);
        if (cancelled())
            return stop();
        return result;
    }

private:
    void clearOutput() {
        m_out.positions.clear();
        m_out.normals.clear();
        m_out.indices.clear();
    }

    static std::uint64_t exclusiveScan(std::vector<std::uint32_t>& values) {
        std::uint64_t sum = 0;
        for (auto& v : values) {
            const std::uint64_t count = v;
            v = std::uint32_t(sum); // checked by the caller against the 32-bit limit
            sum += count;
        }
        return sum;
    }

    void makeUnits(const std::vector<int>& active, unsigned threads) {
        // Enough units for dynamic load balance (a few per thread) but slabs thick enough that
        // the repeated apron layer stays a small overhead.
        const std::size_t wanted = std::size_t(threads) * 8;
        const int perBrick =
            int(std::max<std::size_t>(1, (wanted + active.size() - 1) / active.size()));
        m_units.clear();
        for (int b : active) {
            const auto& brick = m_grid.bricks()[std::size_t(b)];
            const int depth = brick.cellEnd.z - brick.cellBegin.z;
            const int slabs = std::clamp(perBrick, 1, std::max(1, depth / 8));
            for (int s = 0; s < slabs; ++s) {
                Unit unit;
                unit.brick = b;
                unit.z0 = brick.cellBegin.z + int(std::int64_t(depth) * s / slabs);
                unit.z1 = brick.cellBegin.z + int(std::int64_t(depth) * (s + 1) / slabs);
                if (unit.z1 > unit.z0)
                    m_units.push_back(std::move(unit));
            }
        }
    }

    bool inside(std::size_t index) const { return m_voxels[index] >= m_threshold; }
    std::size_t voxelIndex(int x, int y, int z) const {
        return std::size_t(x) + m_dims.sy * std::size_t(y) + m_dims.sz * std::size_t(z);
    }

    const RowInfo& row(const Unit& unit, int y, int z) const {
        const auto& brick = m_grid.bricks()[std::size_t(unit.brick)];
        const int width = unit.rowY1 - brick.cellBegin.y + 1;
        return unit.rows[std::size_t(z - unit.z0) * std::size_t(width) +
                         std::size_t(y - brick.cellBegin.y)];
    }

    // Voxel range [lo, hi) within [begin, end) outside which rows a and b agree everywhere.
    static void differingRange(const RowInfo& a, const RowInfo& b, int begin, int end, int& lo,
                               int& hi) {
        lo = a.left == b.left ? std::max(begin, std::min(a.xl, b.xl)) : begin;
        hi = a.right == b.right ? std::min(end, std::max(a.xr, b.xr) + 1) : end;
    }

    // Counts one unit's vertices and triangles (the first pass): its voxel rows classified,
    // then per row the crossing edges it owns and per cell row the triangles.
    void countUnit(Unit& unit) {
        const auto& brick = m_grid.bricks()[std::size_t(unit.brick)];
        unit.rowY1 = std::min(brick.cellEnd.y + 1, m_dims.ny - 1);
        unit.rowZ1 = std::min(unit.z1 + 1, m_dims.nz - 1);
        classifyRows(unit);
        countVertices(unit);
        countCells(unit);
    }

    // Per voxel row of the unit (and the rows one past it): where its x-crossings lie.
    void classifyRows(Unit& unit) {
        const auto& brick = m_grid.bricks()[std::size_t(unit.brick)];
        const glm::ivec3 cb = brick.cellBegin, ce = brick.cellEnd;
        const int width = unit.rowY1 - cb.y + 1;
        unit.rows.resize(std::size_t(width) * std::size_t(unit.rowZ1 - unit.z0 + 1));
        for (int z = unit.z0; z <= unit.rowZ1; ++z)
            for (int y = cb.y; y <= unit.rowY1; ++y) {
                const T* p = m_voxels + voxelIndex(0, y, z);
                const T thr = m_threshold;
                RowInfo info;
                info.xl = ce.x;
                info.xr = cb.x;
                info.left = p[cb.x] >= thr;
                info.right = p[ce.x] >= thr;
                // Branch-free count first (the compiler vectorises it); most rows of a CT have
                // no crossing at all and end here.
                std::uint32_t crossings = 0;
                for (int x = cb.x; x < ce.x; ++x)
                    crossings += std::uint32_t((p[x] >= thr) != (p[x + 1] >= thr));
                if (crossings > 0) {
                    int first = cb.x;
                    while ((p[first] >= thr) == (p[first + 1] >= thr))
                        ++first;
                    int last = ce.x - 1;
                    while ((p[last] >= thr) == (p[last + 1] >= thr))
                        --last;
                    info.xl = first;
                    info.xr = last + 1;
                }
                info.xCross = crossings;
                unit.rows[std::size_t(z - unit.z0) * std::size_t(width) + std::size_t(y - cb.y)] =
                    info;
            }
    }

    // The crossing edges each voxel row owns (x, y and z edges leaving its voxels).
    void countVertices(const Unit& unit) {
        const auto& brick = m_grid.bricks()[std::size_t(unit.brick)];
        const glm::ivec3 cb = brick.cellBegin, ce = brick.cellEnd;
        const int bx = cb.x / m_brickCells.x;
        const int ownXEnd = ce.x == m_dims.cx ? m_dims.nx : ce.x;
        const int ownYEnd = ce.y == m_dims.cy ? m_dims.ny : ce.y;
        const int ownZEnd = unit.z1 == m_dims.cz ? m_dims.nz : unit.z1;
        for (int z = unit.z0; z < ownZEnd; ++z)
            for (int y = cb.y; y < ownYEnd; ++y) {
                const RowInfo& r = row(unit, y, z);
                std::uint32_t n = r.xCross;
                const std::size_t base = voxelIndex(0, y, z);
                int lo, hi;
                if (y + 1 < m_dims.ny) {
                    differingRange(r, row(unit, y + 1, z), cb.x, ownXEnd, lo, hi);
                    for (int x = lo; x < hi; ++x)
                        n += inside(base + std::size_t(x)) !=
                             inside(base + m_dims.sy + std::size_t(x));
                }
                if (z + 1 < m_dims.nz) {
                    differingRange(r, row(unit, y, z + 1), cb.x, ownXEnd, lo, hi);
                    for (int x = lo; x < hi; ++x)
                        n += inside(base + std::size_t(x)) !=
                             inside(base + m_dims.sz + std::size_t(x));
                }
                m_vertexOffset[(std::size_t(z) * std::size_t(m_dims.ny) + std::size_t(y)) *
                                   std::size_t(m_gx) +
                               std::size_t(bx)] = n;
            }
    }

    // The unit's active cells (listed for the second pass) and each cell row's triangles.
    void countCells(Unit& unit) {
        const auto& brick = m_grid.bricks()[std::size_t(unit.brick)];
        const glm::ivec3 cb = brick.cellBegin, ce = brick.cellEnd;
        const int bx = cb.x / m_brickCells.x;
        for (int z = unit.z0; z < unit.z1; ++z)
            for (int y = cb.y; y < ce.y; ++y) {
                int lo, hi;
                if (!cellRange(unit, cb, ce, y, z, lo, hi))
                    continue;
                std::uint32_t n = 0;
                const std::size_t base = voxelIndex(0, y, z);
                CellRow cellRow{y, z, std::uint32_t(unit.cellX.size()), 0};
                int column = columnBits(base + std::size_t(lo));
                for (int x = lo; x < hi; ++x) {
                    const int next = columnBits(base + std::size_t(x) + 1);
                    const int cubeCase = mcCaseFromColumns(column, next);
                    column = next;
                    if (cubeCase == 0 || cubeCase == 255)
                        continue;
                    n += kMcTriangleCount.count[cubeCase];
                    unit.cellX.push_back(x);
                    unit.cellCase.push_back(std::uint8_t(cubeCase));
                }
                cellRow.end = std::uint32_t(unit.cellX.size());
                if (cellRow.end > cellRow.begin)
                    unit.cellRows.push_back(cellRow);
                m_triangleOffset[(std::size_t(z) * std::size_t(m_dims.cy) + std::size_t(y)) *
                                     std::size_t(m_gx) +
                                 std::size_t(bx)] = n;
            }
    }

    // Inside bits of voxels (x,y,z), (x,y+1,z), (x,y,z+1), (x,y+1,z+1).
    int columnBits(std::size_t index) const {
        return mcColumnBits([this](std::size_t i) { return inside(i); }, index, m_dims.sy,
                            m_dims.sz);
    }

    // Cells [lo, hi) of cell row (y, z) that can have mixed corners; false when none.
    bool cellRange(const Unit& unit, glm::ivec3 cb, glm::ivec3 ce, int y, int z, int& lo,
                   int& hi) const {
        const RowInfo* r[4] = {&row(unit, y, z), &row(unit, y + 1, z), &row(unit, y, z + 1),
                               &row(unit, y + 1, z + 1)};
        bool sameLeft = true, sameRight = true;
        int minL = r[0]->xl, maxR = r[0]->xr;
        for (int i = 1; i < 4; ++i) {
            sameLeft = sameLeft && r[i]->left == r[0]->left;
            sameRight = sameRight && r[i]->right == r[0]->right;
            minL = std::min(minL, r[i]->xl);
            maxR = std::max(maxR, r[i]->xr);
        }
        lo = sameLeft ? minL : cb.x;
        hi = sameRight ? maxR : ce.x;
        return lo < hi;
    }

    // Pass 2 ------------------------------------------------------------------------------

    struct LayerIds {
        std::vector<std::uint32_t> axis[3];
        void resize(std::size_t n) {
            for (auto& a : axis)
                if (a.size() < n)
                    a.resize(n);
        }
    };

    void emitUnit(const Unit& unit) {
        const auto& brick = m_grid.bricks()[std::size_t(unit.brick)];
        const glm::ivec3 cb = brick.cellBegin, ce = brick.cellEnd;
        const int width = ce.x - cb.x + 1;
        const std::size_t layerSize = std::size_t(width) * std::size_t(ce.y - cb.y + 1);
        // Per thread, grown as needed: no allocation per voxel and hardly any per unit.
        thread_local LayerIds layers[2];
        layers[0].resize(layerSize);
        layers[1].resize(layerSize);
        LayerIds* below = &layers[0];
        LayerIds* above = &layers[1];
        layerIds(unit, cb, ce, unit.z0, *below);
        std::size_t cursor = 0;
        for (int z = unit.z0; z < unit.z1; ++z) {
            layerIds(unit, cb, ce, z + 1, *above);
            emitTriangles(unit, cb, ce, z, cursor, *below, *above);
            std::swap(below, above);
        }
    }

    // Voxels [lo, hi) of voxel row (y, z) that may start a crossing edge: the row's own mixed
    // range widened by where it differs from the row above it in y and in z; false when none.
    bool edgeRange(const Unit& unit, glm::ivec3 cb, glm::ivec3 ce, int y, int z, int& lo,
                   int& hi) const {
        const RowInfo& r = row(unit, y, z);
        lo = r.xl;
        hi = r.xr;
        const auto widen = [&](const RowInfo& other) {
            int l2, h2;
            differingRange(r, other, cb.x, ce.x + 1, l2, h2);
            if (l2 < h2) {
                lo = std::min(lo, l2);
                hi = std::max(hi, h2);
            }
        };
        if (y + 1 < m_dims.ny)
            widen(row(unit, y + 1, z));
        if (z + 1 < m_dims.nz)
            widen(row(unit, y, z + 1));
        return lo < hi;
    }

    void layerIds(const Unit& unit, glm::ivec3 cb, glm::ivec3 ce, int z, LayerIds& ids) {
        const int bx = cb.x / m_brickCells.x;
        const int width = ce.x - cb.x + 1;
        const bool nextSegment =
            ce.x < m_dims.cx; // voxel ce.x starts the next brick column's segment
        const int ownXEnd = ce.x == m_dims.cx ? m_dims.nx : ce.x;
        const int ownYEnd = ce.y == m_dims.cy ? m_dims.ny : ce.y;
        const int ownZEnd = unit.z1 == m_dims.cz ? m_dims.nz : unit.z1;
        const bool ownLayer = z < ownZEnd;
        const bool hasZ = z + 1 < m_dims.nz;
        for (int y = cb.y; y <= ce.y; ++y) {
            const bool hasY = y + 1 < m_dims.ny;
            int lo, hi;
            if (!edgeRange(unit, cb, ce, y, z, lo, hi))
                continue;
            const std::size_t segment =
                (std::size_t(z) * std::size_t(m_dims.ny) + std::size_t(y)) * std::size_t(m_gx) +
                std::size_t(bx);
            std::uint32_t id = m_vertexOffset[segment];
            const bool ownRow = ownLayer && y < ownYEnd;
            const std::size_t base = voxelIndex(0, y, z);
            std::uint32_t* idsX =
                ids.axis[0].data() + std::size_t(y - cb.y) * std::size_t(width) - std::size_t(cb.x);
            std::uint32_t* idsY =
                ids.axis[1].data() + std::size_t(y - cb.y) * std::size_t(width) - std::size_t(cb.x);
            std::uint32_t* idsZ =
                ids.axis[2].data() + std::size_t(y - cb.y) * std::size_t(width) - std::size_t(cb.x);
            // The three edges leaving voxel x share its gradient, and the +x edge's far end is
            // the next voxel: compute each gradient once per row walk.
            McVec3 gradientHere{}, gradientNext{};
            int nextX = -1;
            for (int x = lo; x < hi; ++x) {
                if (x == ce.x && nextSegment)
                    id = m_vertexOffset[segment + 1];
                const std::size_t index = base + std::size_t(x);
                const bool a = inside(index);
                const bool own = ownRow && x < ownXEnd;
                bool haveHere = nextX == x;
                if (haveHere)
                    gradientHere = gradientNext;
                auto here = [&]() -> const McVec3& {
                    if (!haveHere) {
                        gradientHere = gradient(x, y, z);
                        haveHere = true;
                    }
                    return gradientHere;
                };
                if (x + 1 < m_dims.nx && a != inside(index + 1)) {
                    if (x < ce.x)
                        idsX[x] = id;
                    if (own) {
                        gradientNext = gradient(x + 1, y, z);
                        nextX = x + 1;
                        writeVertex(x, y, z, 0, id, here(), gradientNext);
                    }
                    ++id;
                }
                if (hasY && a != inside(index + m_dims.sy)) {
                    idsY[x] = id;
                    if (own)
                        writeVertex(x, y, z, 1, id, here(), gradient(x, y + 1, z));
                    ++id;
                }
                if (hasZ && a != inside(index + m_dims.sz)) {
                    idsZ[x] = id;
                    if (own)
                        writeVertex(x, y, z, 2, id, here(), gradient(x, y, z + 1));
                    ++id;
                }
            }
        }
    }

    void emitTriangles(const Unit& unit, glm::ivec3 cb, glm::ivec3 ce, int z, std::size_t& cursor,
                       const LayerIds& below, const LayerIds& above) {
        const int bx = cb.x / m_brickCells.x;
        const int width = ce.x - cb.x + 1;
        std::uint32_t* indices = m_out.indices.data();
        for (; cursor < unit.cellRows.size() && unit.cellRows[cursor].z == z; ++cursor) {
            const CellRow& cellRow = unit.cellRows[cursor];
            const int y = cellRow.y;
            std::size_t t =
                m_triangleOffset[(std::size_t(z) * std::size_t(m_dims.cy) + std::size_t(y)) *
                                     std::size_t(m_gx) +
                                 std::size_t(bx)];
            const std::size_t rowOffset = std::size_t(y - cb.y) * std::size_t(width);
            for (std::uint32_t c = cellRow.begin; c < cellRow.end; ++c) {
                const int cubeCase = unit.cellCase[c];
                const std::int8_t* edges = kMcTriTable[cubeCase];
                const std::size_t cell = rowOffset + std::size_t(unit.cellX[c] - cb.x);
                for (int e = 0; edges[e] >= 0; ++e) {
                    const std::int8_t* owner = kMcEdgeOwner[edges[e]];
                    const LayerIds& layer = owner[2] ? above : below;
                    indices[t * 3 + std::size_t(e)] =
                        layer.axis[owner[3]][cell + std::size_t(owner[1]) * std::size_t(width) +
                                             std::size_t(owner[0])];
                }
                t += kMcTriangleCount.count[cubeCase];
            }
        }
    }

    McVec3 gradient(int x, int y, int z) const { return m_gradient.gradient(x, y, z); }

    // ga/gb: gradients at the edge's lower and upper voxel.
    void writeVertex(int x, int y, int z, int axis, std::uint32_t id, const McVec3& ga,
                     const McVec3& gb) {
        const McVertex v =
            m_gradient.edgeVertex(m_voxelGrid.frame(), x, y, z, axis, ga, gb, m_iso, m_isoF);
        m_out.positions[id] = glm::vec3(v.position.x, v.position.y, v.position.z);
        m_out.normals[id] = glm::vec3(v.normal.x, v.normal.y, v.normal.z);
    }

    const volume::Volume& m_volume;
    const volume::BrickGrid& m_grid;
    const T* m_voxels;
    double m_iso;
    float m_isoF;
    McOutput& m_out;
    GridDims m_dims;
    T m_threshold{};
    int m_gx = 1;
    glm::ivec3 m_brickCells{1};
    VoxelGridSetup m_voxelGrid; // declared after m_voxels: m_gradient points into both
    VoxelGradientSampler<T> m_gradient;
    std::vector<Unit> m_units;
    std::vector<std::uint32_t> m_vertexOffset;   // per (z, y, brick column): count, then offset
    std::vector<std::uint32_t> m_triangleOffset; // per cell (z, y, brick column)
};

} // namespace

McResult marchingCubes(const volume::Volume& volume, const volume::BrickGrid& grid,
                       double storedIso, McOutput& out, unsigned threads,
                       const core::CancelToken* cancel, GradientStencil stencil,
                       const McOutputBudget& budget) {
    return volume::dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        Extractor<T> extractor(volume, grid, storedIso, out, stencil);
        return extractor.run(threads, cancel, budget);
    });
}

} // namespace lw::kernels::cpu
