#include "lw/kernels/cpu/marching_cubes_cpu.h"

#include "lw/kernels/marching_cubes.h"
#include "lw/volume/parallel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

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

// Spread a column of four inside bits (y,z), (y+1,z), (y,z+1), (y+1,z+1) onto the corner bits
// of the cell's lower-x (0, 3, 4, 7) or upper-x (1, 2, 5, 6) face.
constexpr std::uint8_t spread(int column, int c00, int c10, int c01, int c11) {
    return std::uint8_t(((column & 1) << c00) | (((column >> 1) & 1) << c10) |
                        (((column >> 2) & 1) << c01) | (((column >> 3) & 1) << c11));
}
struct SpreadTables {
    std::uint8_t lower[16];
    std::uint8_t upper[16];
};
constexpr SpreadTables makeSpread() {
    SpreadTables t{};
    for (int c = 0; c < 16; ++c) {
        t.lower[c] = spread(c, 0, 3, 4, 7);
        t.upper[c] = spread(c, 1, 2, 5, 6);
    }
    return t;
}
constexpr SpreadTables kSpread = makeSpread();

template <typename T> class Extractor {
public:
    Extractor(const volume::Volume& volume, const volume::BrickGrid& grid, double iso,
              McOutput& out)
        : m_volume(volume), m_grid(grid), m_voxels(volume.dataAs<T>()), m_iso(iso),
          m_isoF(insideThreshold(iso)), m_out(out) {
        // Compare in the voxel type: exact, and it lets the row scan vectorise. For integer
        // voxels, v >= iso  <=>  v >= ceil(iso); the caller only runs us when some brick has
        // min < iso <= max, so ceil(iso) is a value of T.
        if constexpr (std::is_integral_v<T>) {
            const double c = std::ceil(iso);
            m_threshold = T(std::clamp(c, double(std::numeric_limits<T>::lowest()),
                                       double(std::numeric_limits<T>::max())));
        } else {
            m_threshold = m_isoF;
        }
        const glm::ivec3 d = volume.dims();
        m_nx = d.x;
        m_ny = d.y;
        m_nz = d.z;
        m_cx = m_nx - 1;
        m_cy = m_ny - 1;
        m_cz = m_nz - 1;
        m_sy = std::size_t(m_nx);
        m_sz = std::size_t(m_nx) * std::size_t(m_ny);
        m_gx = grid.gridSize().x;
        m_brickCells = grid.brickCells();

        const auto& g = volume.geometry();
        m_origin = g.origin();
        m_stepI = g.spacingI() * g.axisI();
        m_stepJ = g.spacingJ() * g.axisJ();
        m_stack = g.stackAxis();
        m_offset.resize(std::size_t(m_nz));
        for (int k = 0; k < m_nz; ++k)
            m_offset[std::size_t(k)] = g.sliceOffset(double(k));
        // Real distance between the neighbours used for d/ds at slice k (uneven gaps).
        m_spanK.resize(std::size_t(m_nz));
        for (int k = 0; k < m_nz; ++k)
            m_spanK[std::size_t(k)] = float(m_offset[std::size_t(std::min(k + 1, m_nz - 1))] -
                                            m_offset[std::size_t(std::max(k - 1, 0))]);
        // Derivatives are taken in the oblique frame (axisI, axisJ, stackAxis) with real
        // distances: d/du over the in-plane spacing, d/ds over the actual slice offsets of the
        // neighbours (uneven gaps). The patient gradient is M^-T (du, dw, ds) with M the frame's
        // columns -- the same as J(k)^-T applied to the index-space gradient.
        const glm::dmat3 frame(g.axisI(), g.axisJ(), g.stackAxis());
        const glm::dmat3 invT = glm::inverse(glm::transpose(frame));
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
                m_normalMatrix[r * 3 + c] = float(invT[c][r]);
        m_invSpanK.resize(m_spanK.size());
        for (std::size_t k = 0; k < m_spanK.size(); ++k)
            m_invSpanK[k] = m_spanK[k] > 0.0f ? 1.0f / m_spanK[k] : 0.0f;
        m_spanI = float(2.0 * g.spacingI());
        m_invSpanI = 1.0f / m_spanI;
        m_invSpanJ = float(1.0 / (2.0 * g.spacingJ()));
        m_spanJ = float(2.0 * g.spacingJ());
        m_edgeSpanI = float(g.spacingI());
        m_edgeSpanJ = float(g.spacingJ());
        m_axisDir[0] = glm::normalize(glm::dvec3(g.axisI()));
        m_axisDir[1] = glm::normalize(glm::dvec3(g.axisJ()));
        double slope = 1.0;
        if (m_nz > 1)
            slope = m_offset.back() - m_offset.front() >= 0.0 ? 1.0 : -1.0;
        m_axisDir[2] = glm::normalize(glm::dvec3(g.stackAxis())) * slope;
        for (int a = 0; a < 3; ++a)
            m_edgeDirection[a] = {float(m_axisDir[a].x), float(m_axisDir[a].y),
                                  float(m_axisDir[a].z)};
    }

    McResult run(unsigned threads) {
        McResult result;
        result.totalBricks = m_grid.bricks().size();
        if (m_cx < 1 || m_cy < 1 || m_cz < 1 || result.totalBricks == 0) {
            clearOutput();
            return result;
        }
        const std::vector<int> active = m_grid.activeBricks(m_iso);
        result.activeBricks = active.size();
        if (active.empty()) {
            clearOutput();
            return result;
        }
        makeUnits(active, threads == 0 ? volume::workerCount() : threads);
        result.workUnits = m_units.size();

        m_vertexOffset.assign(std::size_t(m_nz) * std::size_t(m_ny) * std::size_t(m_gx), 0u);
        m_triangleOffset.assign(std::size_t(m_cz) * std::size_t(m_cy) * std::size_t(m_gx), 0u);
        volume::parallelFor(
            m_units.size(), [&](std::size_t u) { countUnit(m_units[u]); }, threads);

        const std::uint64_t vertices = exclusiveScan(m_vertexOffset);
        const std::uint64_t triangles = exclusiveScan(m_triangleOffset);
        if (vertices > std::numeric_limits<std::uint32_t>::max() ||
            triangles > std::numeric_limits<std::uint32_t>::max() / 3) {
            result.status = McStatus::TooManyVertices;
            clearOutput();
            return result;
        }
        // resize() keeps existing elements: a reused buffer of the right size is not rewritten.
        m_out.positions.resize(std::size_t(vertices));
        m_out.normals.resize(std::size_t(vertices));
        m_out.indices.resize(std::size_t(triangles) * 3);
        volume::parallelFor(
            m_units.size(), [&](std::size_t u) { emitUnit(m_units[u]); }, threads);
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
        return std::size_t(x) + m_sy * std::size_t(y) + m_sz * std::size_t(z);
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

    void countUnit(Unit& unit) {
        const auto& brick = m_grid.bricks()[std::size_t(unit.brick)];
        const glm::ivec3 cb = brick.cellBegin, ce = brick.cellEnd;
        const int bx = cb.x / m_brickCells.x;
        unit.rowY1 = std::min(ce.y + 1, m_ny - 1);
        unit.rowZ1 = std::min(unit.z1 + 1, m_nz - 1);
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

        const int ownXEnd = ce.x == m_cx ? m_nx : ce.x;
        const int ownYEnd = ce.y == m_cy ? m_ny : ce.y;
        const int ownZEnd = unit.z1 == m_cz ? m_nz : unit.z1;
        for (int z = unit.z0; z < ownZEnd; ++z)
            for (int y = cb.y; y < ownYEnd; ++y) {
                const RowInfo& r = row(unit, y, z);
                std::uint32_t n = r.xCross;
                const std::size_t base = voxelIndex(0, y, z);
                int lo, hi;
                if (y + 1 < m_ny) {
                    differingRange(r, row(unit, y + 1, z), cb.x, ownXEnd, lo, hi);
                    for (int x = lo; x < hi; ++x)
                        n += inside(base + std::size_t(x)) != inside(base + m_sy + std::size_t(x));
                }
                if (z + 1 < m_nz) {
                    differingRange(r, row(unit, y, z + 1), cb.x, ownXEnd, lo, hi);
                    for (int x = lo; x < hi; ++x)
                        n += inside(base + std::size_t(x)) != inside(base + m_sz + std::size_t(x));
                }
                m_vertexOffset[(std::size_t(z) * std::size_t(m_ny) + std::size_t(y)) *
                                   std::size_t(m_gx) +
                               std::size_t(bx)] = n;
            }

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
                    const int cubeCase = kSpread.lower[column] | kSpread.upper[next];
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
                m_triangleOffset[(std::size_t(z) * std::size_t(m_cy) + std::size_t(y)) *
                                     std::size_t(m_gx) +
                                 std::size_t(bx)] = n;
            }
    }

    // Inside bits of voxels (x,y,z), (x,y+1,z), (x,y,z+1), (x,y+1,z+1).
    int columnBits(std::size_t index) const {
        return int(inside(index)) | int(inside(index + m_sy)) << 1 |
               int(inside(index + m_sz)) << 2 | int(inside(index + m_sy + m_sz)) << 3;
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

    void layerIds(const Unit& unit, glm::ivec3 cb, glm::ivec3 ce, int z, LayerIds& ids) {
        const int bx = cb.x / m_brickCells.x;
        const int width = ce.x - cb.x + 1;
        const bool nextSegment = ce.x < m_cx; // voxel ce.x starts the next brick column's segment
        const int ownXEnd = ce.x == m_cx ? m_nx : ce.x;
        const int ownYEnd = ce.y == m_cy ? m_ny : ce.y;
        const int ownZEnd = unit.z1 == m_cz ? m_nz : unit.z1;
        const bool ownLayer = z < ownZEnd;
        const bool hasZ = z + 1 < m_nz;
        for (int y = cb.y; y <= ce.y; ++y) {
            const RowInfo& r = row(unit, y, z);
            const bool hasY = y + 1 < m_ny;
            int lo = r.xl, hi = r.xr;
            int l2, h2;
            if (hasY) {
                differingRange(r, row(unit, y + 1, z), cb.x, ce.x + 1, l2, h2);
                if (l2 < h2) {
                    lo = std::min(lo, l2);
                    hi = std::max(hi, h2);
                }
            }
            if (hasZ) {
                differingRange(r, row(unit, y, z + 1), cb.x, ce.x + 1, l2, h2);
                if (l2 < h2) {
                    lo = std::min(lo, l2);
                    hi = std::max(hi, h2);
                }
            }
            if (lo >= hi)
                continue;
            const std::size_t segment =
                (std::size_t(z) * std::size_t(m_ny) + std::size_t(y)) * std::size_t(m_gx) +
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
                if (x + 1 < m_nx && a != inside(index + 1)) {
                    if (x < ce.x)
                        idsX[x] = id;
                    if (own) {
                        gradientNext = gradient(x + 1, y, z);
                        nextX = x + 1;
                        writeVertex(x, y, z, 0, id, here(), gradientNext);
                    }
                    ++id;
                }
                if (hasY && a != inside(index + m_sy)) {
                    idsY[x] = id;
                    if (own)
                        writeVertex(x, y, z, 1, id, here(), gradient(x, y + 1, z));
                    ++id;
                }
                if (hasZ && a != inside(index + m_sz)) {
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
            std::size_t t = m_triangleOffset[(std::size_t(z) * std::size_t(m_cy) + std::size_t(y)) *
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

    float value(std::size_t index) const { return float(m_voxels[index]); }

    // Gradient in the (axisI, axisJ, stackAxis) frame, per mm.
    McVec3 gradient(int x, int y, int z) const {
        const std::size_t i = voxelIndex(x, y, z);
        if (x > 0 && x < m_cx && y > 0 && y < m_cy && z > 0 && z < m_cz) {
            // Interior: central differences everywhere, no boundary cases.
            return {(value(i + 1) - value(i - 1)) * m_invSpanI,
                    (value(i + m_sy) - value(i - m_sy)) * m_invSpanJ,
                    (value(i + m_sz) - value(i - m_sz)) * m_invSpanK[std::size_t(z)]};
        }
        const float c = value(i);
        McVec3 g;
        if (x > 0 && x < m_cx)
            g.x = mcDerivative(value(i - 1), value(i + 1), m_spanI);
        else if (m_nx > 1)
            g.x = x == 0 ? mcDerivative(c, value(i + 1), m_edgeSpanI)
                         : mcDerivative(value(i - 1), c, m_edgeSpanI);
        else
            g.x = 0.0f;
        if (y > 0 && y < m_cy)
            g.y = mcDerivative(value(i - m_sy), value(i + m_sy), m_spanJ);
        else if (m_ny > 1)
            g.y = y == 0 ? mcDerivative(c, value(i + m_sy), m_edgeSpanJ)
                         : mcDerivative(value(i - m_sy), c, m_edgeSpanJ);
        else
            g.y = 0.0f;
        const int z0 = std::max(z - 1, 0), z1 = std::min(z + 1, m_cz);
        const float lo = z0 == z ? c : value(i - m_sz);
        const float hi = z1 == z ? c : value(i + m_sz);
        g.z = mcDerivative(lo, hi, m_spanK[std::size_t(z)]);
        return g;
    }

    // ga/gb: gradients at the edge's lower and upper voxel.
    void writeVertex(int x, int y, int z, int axis, std::uint32_t id, const McVec3& ga,
                     const McVec3& gb) {
        const std::size_t i = voxelIndex(x, y, z);
        const std::size_t step = axis == 0 ? 1 : (axis == 1 ? m_sy : m_sz);
        const float a = value(i), b = value(i + step);
        const float t = mcEdgeParameter(a, b, m_iso);
        const McVec3 g = mcTransform(m_normalMatrix, mcLerp(ga, gb, t));
        McVec3 fallback = m_edgeDirection[axis];
        if (!(a >= m_isoF))
            fallback = {-fallback.x, -fallback.y, -fallback.z};
        const McVec3 n = mcOutwardNormal(g, fallback);

        double px = x, py = y;
        double offset = m_offset[std::size_t(z)];
        if (axis == 0)
            px += t;
        else if (axis == 1)
            py += t;
        else
            offset += double(t) * (m_offset[std::size_t(z) + 1] - offset);
        const glm::dvec3 p = m_origin + px * m_stepI + py * m_stepJ + offset * m_stack;
        m_out.positions[id] = glm::vec3(p);
        m_out.normals[id] = glm::vec3(n.x, n.y, n.z);
    }

    const volume::Volume& m_volume;
    const volume::BrickGrid& m_grid;
    const T* m_voxels;
    double m_iso;
    float m_isoF;
    T m_threshold{};
    McOutput& m_out;
    int m_nx = 0, m_ny = 0, m_nz = 0, m_cx = 0, m_cy = 0, m_cz = 0, m_gx = 1;
    std::size_t m_sy = 0, m_sz = 0;
    glm::ivec3 m_brickCells{1};
    glm::dvec3 m_origin{0.0}, m_stepI{0.0}, m_stepJ{0.0}, m_stack{0.0};
    glm::dvec3 m_axisDir[3];
    McVec3 m_edgeDirection[3] =
        {}; // patient direction of +x/+y/+z edges: the zero-gradient fallback
    std::vector<double> m_offset;
    std::vector<float> m_spanK, m_invSpanK;
    float m_invSpanI = 0.5f, m_invSpanJ = 0.5f;
    float m_normalMatrix[9] = {};
    float m_spanI = 2.0f, m_spanJ = 2.0f, m_edgeSpanI = 1.0f, m_edgeSpanJ = 1.0f;
    std::vector<Unit> m_units;
    std::vector<std::uint32_t> m_vertexOffset;   // per (z, y, brick column): count, then offset
    std::vector<std::uint32_t> m_triangleOffset; // per cell (z, y, brick column)
};

} // namespace

McResult marchingCubes(const volume::Volume& volume, const volume::BrickGrid& grid,
                       double storedIso, McOutput& out, unsigned threads) {
    return volume::dispatchVoxelType(volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        Extractor<T> extractor(volume, grid, storedIso, out);
        return extractor.run(threads);
    });
}

} // namespace lw::kernels::cpu
