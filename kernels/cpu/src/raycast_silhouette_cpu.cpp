#include "lw/kernels/cpu/raycast_silhouette_cpu.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/marching_cubes.h"
#include "lw/kernels/voxel_ray_walk.h"

#include <algorithm>
#include <cmath>
#include <limits>

// Method 2 keeps no mesh: per frame every cached active cell is re-triangulated with the shared
// marching-cubes expressions and only the Burns segments survive. Cells are handed to the threads
// in chunks that never straddle a brick, so the chunked ("L") schedule really works brick by
// brick; the output order (brick, then cell) does not depend on the thread count.

namespace lw::kernels::cpu {
namespace {

constexpr std::size_t kChunkCells = 2048;
// The visibility rule and its constants (start offset, self skip, neighbour ray, macro cells) are
// kernels/common's RayVisibility, shared with the CUDA back-end.
constexpr int kMacroCells = RayVisibilityRule::kMacroCells;
// Slack of the normal-cone cull, relative to |eye - cell centre|: float round-off of d = N . V
// (relative 1e-6 at most) must never turn a culled cell into one with a segment.
constexpr double kConeSlack = 1e-4;
constexpr std::uint16_t kConeNever = 0xffff;
constexpr double kConeAngleStep = 0.5 * 3.14159265358979323846 / 65534.0;

// cos and sin of every quantised cone angle, so the per-view cull needs no trigonometry.
struct ConeTrig {
    std::vector<float> cosA, sinA;
    ConeTrig() : cosA(65535), sinA(65535) {
        for (int q = 0; q < 65535; ++q) {
            cosA[std::size_t(q)] = float(std::cos(q * kConeAngleStep));
            sinA[std::size_t(q)] = float(std::sin(q * kConeAngleStep));
        }
    }
};
const ConeTrig& coneTrig() {
    static const ConeTrig trig;
    return trig;
}

// Octahedral mapping of a unit vector to two values in [-1, 1] and back.
glm::dvec2 octEncode(glm::dvec3 n) {
    const double l1 = std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
    glm::dvec2 p(n.x / l1, n.y / l1);
    if (n.z < 0.0)
        p = glm::dvec2((1.0 - std::abs(p.y)) * (p.x >= 0.0 ? 1.0 : -1.0),
                       (1.0 - std::abs(p.x)) * (p.y >= 0.0 ? 1.0 : -1.0));
    return p;
}
// A stored octahedron coordinate in [-1, 1]: one expression for the cone's build and its cull,
// a multiplication because the cull runs for every cell of every view.
double octCoordinate(std::int16_t q) {
    return double(q) * (1.0 / 32767.0);
}

// The octahedron point of (x, y), a direction not yet of unit length.
glm::dvec3 octAxis(double x, double y) {
    glm::dvec3 v(x, y, 1.0 - std::abs(x) - std::abs(y));
    if (v.z < 0.0) {
        const double vx = v.x;
        v.x = (1.0 - std::abs(v.y)) * (vx >= 0.0 ? 1.0 : -1.0);
        v.y = (1.0 - std::abs(vx)) * (v.y >= 0.0 ? 1.0 : -1.0);
    }
    return v;
}

glm::dvec3 octDecode(double x, double y) {
    return glm::normalize(octAxis(x, y));
}

} // namespace

struct RayCastSilhouetteCpu::Impl {
    virtual ~Impl() = default;
    // False when `cancel` was set (the cell list is then incomplete and must not be used).
    virtual bool findCells(const volume::BrickGrid& grid, bool withCones, unsigned threads,
                           const core::CancelToken* cancel) = 0;
    virtual std::size_t extract(const SilhouetteView& view, unsigned threads) = 0;
    virtual bool visible(glm::dvec3 point, const SilhouetteView& view) const = 0;

    VoxelRayGrid rayGrid;
    std::vector<std::uint32_t> cells;     // voxel index of each active cell's lowest corner
    std::vector<std::size_t> chunkStarts; // chunk c = cells [chunkStarts[c], chunkStarts[c + 1])
    std::size_t activeBricks = 0;
    // Per active cell (mode a only): a cone holding every vertex normal of the cell, so a view
    // skips the cells whose normals cannot straddle the view direction. 8 bytes, because on a
    // 512 x 512 x 1024 CT there are millions of active cells: the axis octahedron-encoded in two
    // int16, the half angle in units of kConeAngleStep rounded up (kConeNever: never culled).
    // The stored angle is measured from the decoded axis, so the cone stays conservative.
    struct NormalCone {
        std::int16_t u = 0, v = 0;
        std::uint16_t angle = 0xffff;
        std::uint16_t unused = 0;
    };
    static_assert(sizeof(NormalCone) == 8);
    std::vector<NormalCone> cones;
    std::vector<std::uint8_t> macroOccupied;  // per macro cell: holds a voxel >= iso
    std::vector<std::uint8_t> coarseOccupied; // per coarse block: holds an occupied macro cell
    // Per-chunk outputs, kept between frames so a new view allocates nothing once warm.
    std::vector<std::vector<SegmentEndpoints>> chunkSegments;
    std::size_t usedChunks = 0; // chunks of the last extract (chunkSegments may hold more)
    std::vector<std::size_t> chunkTriangles;
    std::vector<std::size_t> chunkTriangleTotal; // with cones: triangles of every cell of the chunk
    std::vector<std::vector<std::uint32_t>> unitCells;
};

namespace {

template <typename T> class Engine final : public RayCastSilhouetteCpu::Impl {
public:
    Engine(const volume::Volume& volume, double iso, GradientStencil stencil)
        : m_voxels(volume.dataAs<T>()), m_iso(iso), m_isoF(insideThreshold(iso)),
          m_dims(makeGridDims(volume.dims())),
          // The same set-up as marchingCubes(): bit-identical vertices and normals need
          // identical inputs to the shared expressions.
          m_voxelGrid(voxelGridSetup(volume, stencil)), m_gradient{m_voxels, m_voxelGrid.spans()},
          m_offset(m_voxelGrid.sliceOffsets()) {
        rayGrid = VoxelRayGrid(volume);

        for (int k = 0; k + 1 < m_dims.nz; ++k) {
            const double gap = m_offset[std::size_t(k) + 1] - m_offset[std::size_t(k)];
            for (int corner = 0; corner < 8; ++corner) {
                const glm::dvec3 d = ((corner & 1) ? 0.5 : -0.5) * m_voxelGrid.stepI() +
                                     ((corner & 2) ? 0.5 : -0.5) * m_voxelGrid.stepJ() +
                                     ((corner & 4) ? 0.5 : -0.5) * gap * m_voxelGrid.stack();
                m_cellRadius = std::max(m_cellRadius, glm::length(d));
            }
        }
        m_cellScale = rayGrid.cellScale();
        m_neighbourReach = rayGrid.neighbourReach();
    }

    bool findCells(const volume::BrickGrid& grid, bool withCones, unsigned threads,
                   const core::CancelToken* cancel) override {
        const auto cancelled = [cancel] { return cancel && cancel->isCancelled(); };
        cells.clear();
        cones.clear();
        chunkStarts.assign(1, 0);
        activeBricks = 0;
        buildMacroGrid(threads);
        if (m_dims.cx < 1 || m_dims.cy < 1 || m_dims.cz < 1)
            return true;
        if (voxelIndex(m_dims.cx, m_dims.cy, m_dims.cz) > std::numeric_limits<std::uint32_t>::max())
            throw core::Error("method 2", "volumes of more than 2^32 voxels are not supported");
        const std::vector<int> active = grid.activeBricks(m_iso);
        activeBricks = active.size();
        const std::vector<LayerUnit> units = layerUnits(grid, active);
        if (unitCells.size() < units.size())
            unitCells.resize(units.size());
        core::parallelFor(
            units.size(),
            [&](std::size_t u) {
                unitCells[u].clear();
                if (cancelled())
                    return; // the remaining layers are skipped; the caller drops the result
                findLayerCells(grid.bricks()[std::size_t(units[u].brick)], units[u].z,
                               unitCells[u]);
            },
            threads);
        joinUnitsInChunks(units);
        if (cancelled())
            return false;
        if (withCones)
            buildCones(threads);
        return true;
    }

    // One unit of the cell search per (brick, cell layer): enough units to balance, each a
    // contiguous run of cells.
    struct LayerUnit {
        int brick;
        int z;
    };

    static std::vector<LayerUnit> layerUnits(const volume::BrickGrid& grid,
                                             const std::vector<int>& active) {
        std::vector<LayerUnit> units;
        for (int b : active) {
            const auto& brick = grid.bricks()[std::size_t(b)];
            for (int z = brick.cellBegin.z; z < brick.cellEnd.z; ++z)
                units.push_back({b, z});
        }
        return units;
    }

    // The active cells (a crossing, not case 0 or 255) of one brick's cell layer z.
    void findLayerCells(const volume::Brick& brick, int z, std::vector<std::uint32_t>& list) const {
        // Classify the voxel rows of layers z and z+1 first (a branch-free count the compiler
        // vectorises): a cell row whose four voxel rows are all outside or all inside holds no
        // active cell, which is most rows of a CT.
        const int rowsY = brick.cellEnd.y - brick.cellBegin.y + 1;
        const int width = brick.cellEnd.x - brick.cellBegin.x + 1;
        thread_local std::vector<std::uint8_t> rowState;
        rowState.resize(std::size_t(2 * rowsY));
        for (int dz = 0; dz < 2; ++dz)
            for (int r = 0; r < rowsY; ++r) {
                const T* row =
                    m_voxels + voxelIndex(brick.cellBegin.x, brick.cellBegin.y + r, z + dz);
                int n = 0;
                for (int x = 0; x < width; ++x)
                    n += int(float(row[x]) >= m_isoF);
                rowState[std::size_t(dz * rowsY + r)] =
                    std::uint8_t(n == 0 ? 0 : (n == width ? 1 : 2));
            }
        for (int y = brick.cellBegin.y; y < brick.cellEnd.y; ++y) {
            const int r = y - brick.cellBegin.y;
            const std::uint8_t s0 = rowState[std::size_t(r)];
            if (s0 != 2 && rowState[std::size_t(r + 1)] == s0 &&
                rowState[std::size_t(rowsY + r)] == s0 &&
                rowState[std::size_t(rowsY + r + 1)] == s0)
                continue;
            const std::size_t base = voxelIndex(0, y, z);
            int column = columnBits(base + std::size_t(brick.cellBegin.x));
            for (int x = brick.cellBegin.x; x < brick.cellEnd.x; ++x) {
                const int next = columnBits(base + std::size_t(x) + 1);
                const int cubeCase = mcCaseFromColumns(column, next);
                column = next;
                if (cubeCase != 0 && cubeCase != 255)
                    list.push_back(std::uint32_t(base + std::size_t(x)));
            }
        }
    }

    // The per-layer lists joined into the flat cell list, cut into chunks of at most kChunkCells
    // that never straddle a brick.
    void joinUnitsInChunks(const std::vector<LayerUnit>& units) {
        std::size_t total = 0;
        for (std::size_t u = 0; u < units.size(); ++u)
            total += unitCells[u].size();
        cells.reserve(total);
        std::size_t brickBegin = 0;
        for (std::size_t u = 0; u < units.size(); ++u) {
            cells.insert(cells.end(), unitCells[u].begin(), unitCells[u].end());
            const bool brickEnds = u + 1 == units.size() || units[u + 1].brick != units[u].brick;
            if (brickEnds) {
                for (std::size_t s = brickBegin + kChunkCells; s < cells.size(); s += kChunkCells)
                    chunkStarts.push_back(s);
                if (cells.size() > chunkStarts.back())
                    chunkStarts.push_back(cells.size());
                brickBegin = cells.size();
            }
        }
        // Release the per-layer lists of a large volume: the cache is the flat list only.
        unitCells.clear();
        unitCells.shrink_to_fit();
    }

    void buildCones(unsigned threads) {
        cones.resize(cells.size());
        chunkTriangleTotal.assign(chunkStarts.size() - 1, 0);
        core::parallelFor(
            chunkStarts.size() - 1,
            [&](std::size_t c) {
                std::size_t triangles = 0;
                for (std::size_t i = chunkStarts[c]; i < chunkStarts[c + 1]; ++i) {
                    cones[i] = normalCone(cells[i]);
                    triangles += cellTriangleCount(cells[i]);
                }
                chunkTriangleTotal[c] = triangles;
            },
            threads);
    }

    void buildMacroGrid(unsigned threads) {
        const glm::ivec3 cellsPerAxis(std::max(m_dims.cx, 0), std::max(m_dims.cy, 0),
                                      std::max(m_dims.cz, 0));
        m_macroDims = (cellsPerAxis + kMacroCells - 1) / kMacroCells;
        macroOccupied.assign(std::size_t(m_macroDims.x) * std::size_t(m_macroDims.y) *
                                 std::size_t(m_macroDims.z),
                             0);
        core::parallelFor(
            std::size_t(m_macroDims.z),
            [&](std::size_t mz) {
                const int z0 = int(mz) * kMacroCells, z1 = std::min(z0 + kMacroCells, m_dims.cz);
                for (int my = 0; my < m_macroDims.y; ++my)
                    for (int mx = 0; mx < m_macroDims.x; ++mx) {
                        const int y0 = my * kMacroCells, y1 = std::min(y0 + kMacroCells, m_dims.cy);
                        const int x0 = mx * kMacroCells, x1 = std::min(x0 + kMacroCells, m_dims.cx);
                        bool any = false;
                        // Corner voxels of the macro cell's cells: [x0, x1] etc.
                        for (int z = z0; z <= z1 && !any; ++z)
                            for (int y = y0; y <= y1 && !any; ++y) {
                                const std::size_t base = voxelIndex(0, y, z);
                                for (int x = x0; x <= x1; ++x)
                                    any |= inside(base + std::size_t(x));
                            }
                        macroOccupied[macroIndex(
                            {mx * kMacroCells, my * kMacroCells, int(mz) * kMacroCells})] = any;
                    }
            },
            threads);
        m_coarseDims = coarseDimsOf(m_macroDims);
        coarseOccupied.resize(std::size_t(m_coarseDims.x) * std::size_t(m_coarseDims.y) *
                              std::size_t(m_coarseDims.z));
        std::size_t i = 0;
        for (int z = 0; z < m_coarseDims.z; ++z)
            for (int y = 0; y < m_coarseDims.y; ++y)
                for (int x = 0; x < m_coarseDims.x; ++x)
                    coarseOccupied[i++] =
                        coarseOccupancy(macroOccupied.data(), m_macroDims, {x, y, z});
    }

    std::size_t macroIndex(glm::ivec3 cell) const {
        return occupancyIndex(cell / kMacroCells, m_macroDims);
    }

    std::size_t extract(const SilhouetteView& view, unsigned threads) override {
        const std::size_t chunks = chunkStarts.size() - 1;
        if (chunkSegments.size() < chunks)
            chunkSegments.resize(chunks);
        chunkTriangles.assign(chunks, 0);
        const glm::vec3 eye(view.eyeOrDirection);
        core::parallelFor(
            chunks,
            [&](std::size_t c) {
                auto& segments = chunkSegments[c];
                segments.clear();
                if (cones.empty()) {
                    std::size_t triangles = 0;
                    for (std::size_t i = chunkStarts[c]; i < chunkStarts[c + 1]; ++i)
                        triangles += cellSegments(cells[i], eye, view.orthographic, segments);
                    chunkTriangles[c] = triangles;
                    return;
                }
                // Every cell's triangles count as visited; only the uncertain cells are built.
                for (std::size_t i = chunkStarts[c]; i < chunkStarts[c + 1]; ++i)
                    if (!cannotHoldSilhouette(cells[i], cones[i], view))
                        cellSegments(cells[i], eye, view.orthographic, segments);
                chunkTriangles[c] = chunkTriangleTotal[c];
            },
            threads);
        usedChunks = chunks;
        std::size_t triangles = 0;
        for (std::size_t c = 0; c < chunks; ++c)
            triangles += chunkTriangles[c];
        return triangles;
    }

    bool visible(glm::dvec3 point, const SilhouetteView& view) const override {
        RayVisibility<T> rule = rayVisibility();
        rule.pixelSpan = view.pixelSpan;
        return rule.visible(point, view.eyeOrDirection, view.orthographic);
    }

    RayVisibility<T> rayVisibility() const {
        RayVisibility<T> rule;
        rule.voxels = m_voxels;
        rule.dims = m_dims;
        rule.grid = rayGrid.view();
        rule.macroOccupied = macroOccupied.data();
        rule.macroDims = m_macroDims;
        rule.coarseOccupied = coarseOccupied.data();
        rule.coarseDims = m_coarseDims;
        rule.cellScale = m_cellScale;
        rule.neighbourReach = m_neighbourReach;
        rule.iso = m_iso;
        return rule;
    }

private:
    std::size_t voxelIndex(int x, int y, int z) const {
        return std::size_t(x) + m_dims.sy * std::size_t(y) + m_dims.sz * std::size_t(z);
    }
    float value(std::size_t index) const { return float(m_voxels[index]); }
    bool inside(std::size_t index) const { return value(index) >= m_isoF; }
    int columnBits(std::size_t index) const {
        return mcColumnBits([this](std::size_t i) { return inside(i); }, index, m_dims.sy,
                            m_dims.sz);
    }

    // In 32 bits: a cell index is one (the cell list is uint32), so are the strides below it,
    // and the cull decodes every cell of every view.
    glm::ivec3 cellCoords(std::uint32_t cellIndex) const {
        const auto slice = std::uint32_t(m_dims.sz), row = std::uint32_t(m_dims.sy);
        const std::uint32_t z = cellIndex / slice;
        const std::uint32_t rest = cellIndex - z * slice;
        const std::uint32_t y = rest / row;
        return {int(rest - y * row), int(y), int(z)};
    }

    int cellCase(glm::ivec3 p, float v[8]) const {
        for (int c = 0; c < 8; ++c)
            v[c] = value(voxelIndex(p.x + kMcCornerOffset[c][0], p.y + kMcCornerOffset[c][1],
                                    p.z + kMcCornerOffset[c][2]));
        return mcCaseIndex(v, m_isoF);
    }

    std::size_t cellTriangleCount(std::uint32_t cellIndex) const {
        float v[8];
        return kMcTriangleCount.count[cellCase(cellCoords(cellIndex), v)];
    }

    // Centre of cell p in patient mm.
    glm::dvec3 cellCentre(glm::ivec3 p) const {
        const double s = 0.5 * (m_offset[std::size_t(p.z)] + m_offset[std::size_t(p.z) + 1]);
        return m_voxelGrid.origin() + (p.x + 0.5) * m_voxelGrid.stepI() +
               (p.y + 0.5) * m_voxelGrid.stepJ() + s * m_voxelGrid.stack();
    }

    RayCastSilhouetteCpu::Impl::NormalCone normalCone(std::uint32_t cellIndex) const {
        const glm::ivec3 p = cellCoords(cellIndex);
        float v[8];
        const int cubeCase = cellCase(p, v);
        glm::vec3 position[12], normal[12];
        const unsigned edges = cellVertices(p, v, cubeCase, position, normal);
        glm::dvec3 sum(0.0);
        for (int e = 0; e < 12; ++e)
            if (edges & (1u << e))
                sum += glm::dvec3(normal[e]);
        NormalCone cone; // angle kConeNever: never culled
        const double length = glm::length(sum);
        if (!(length > 1e-6))
            return cone;
        const glm::dvec2 oct = octEncode(sum / length);
        cone.u = std::int16_t(std::lround(oct.x * 32767.0));
        cone.v = std::int16_t(std::lround(oct.y * 32767.0));
        const glm::dvec3 axis = octDecode(octCoordinate(cone.u), octCoordinate(cone.v));
        double minCos = 1.0;
        for (int e = 0; e < 12; ++e)
            if (edges & (1u << e))
                minCos = std::min(minCos, glm::dot(axis, glm::dvec3(normal[e])) /
                                              glm::length(glm::dvec3(normal[e])));
        // Slack for the float decode at view time and the float cos/sin table.
        const double angle = std::acos(std::clamp(minCos, -1.0, 1.0)) + 1e-5;
        const double steps = std::ceil(angle / kConeAngleStep);
        if (!(steps < 65534.0))
            return cone;
        cone.angle = std::uint16_t(steps);
        return cone;
    }

    // True when d = N . (eye - B) has the same sign, with margin, at every point B of the cell
    // and every normal N of its cone: then none of its triangles has a silhouette segment.
    bool cannotHoldSilhouette(std::uint32_t cellIndex, const NormalCone& cone,
                              const SilhouetteView& view) const {
        if (cone.angle >= kConeNever - 1)
            return false;
        const double cosA = coneTrig().cosA[cone.angle], sinA = coneTrig().sinA[cone.angle];
        // Every cell of every view passes here, most of them culled: two square roots, not four
        // (|w| once, the axis's length folded into it, the cone test squared).
        glm::dvec3 w;
        double wl = 0.0, rw = 0.0;
        if (view.orthographic) {
            w = view.eyeOrDirection;
            wl = glm::length(w);
        } else {
            w = view.eyeOrDirection - cellCentre(cellCoords(cellIndex));
            wl = glm::length(w);
            if (!(wl > 2.0 * m_cellRadius))
                return false;
            rw = m_cellRadius / wl;
        }
        if (!(wl > 0.0))
            return false;
        const glm::dvec3 axis =
            octAxis(octCoordinate(cone.u), octCoordinate(cone.v)); // not unit length
        const double c = glm::dot(axis, w) / (std::sqrt(glm::dot(axis, axis)) * wl);
        const double margin = rw + kConeSlack;
        // min over the cone of N . w^ is cos(theta + alpha), max is cos(theta - alpha): one sign
        // throughout when |c| cos(alpha) - sqrt(1 - c^2) sin(alpha) > margin, both sides of the
        // comparison with sin(alpha) then non-negative, so it may be squared.
        const double reach = std::abs(c) * cosA - margin;
        if (!(reach > 0.0))
            return false;
        return reach * reach > std::max(0.0, 1.0 - c * c) * sinA * sinA;
    }

    // The marching-cubes vertices (patient mm) and outward normals of cell p's crossing edges,
    // as marchingCubes() writes them; returns the edge mask.
    unsigned cellVertices(glm::ivec3 p, const float v[8], int cubeCase, glm::vec3 position[12],
                          glm::vec3 normal[12]) const {
        const unsigned edges = kMcEdgeTable[cubeCase];
        McVec3 grad[8];
        unsigned haveGrad = 0;
        auto cornerGradient = [&](int c) -> const McVec3& {
            if (!(haveGrad & (1u << c))) {
                grad[c] =
                    m_gradient.gradient(p.x + kMcCornerOffset[c][0], p.y + kMcCornerOffset[c][1],
                                        p.z + kMcCornerOffset[c][2]);
                haveGrad |= 1u << c;
            }
            return grad[c];
        };
        for (int e = 0; e < 12; ++e) {
            if (!(edges & (1u << e)))
                continue;
            const int c0 = kMcEdgeCorners[e][0], c1 = kMcEdgeCorners[e][1];
            const std::int8_t* owner = kMcEdgeOwner[e];
            const int axis = owner[3];
            const int vx = p.x + owner[0], vy = p.y + owner[1], vz = p.z + owner[2];
            const float a = v[c0], b = v[c1];
            const McVertex vertex =
                mcEdgeVertex(m_voxelGrid.frame(), vx, vy, vz, axis, a, b, cornerGradient(c0),
                             cornerGradient(c1), m_iso, m_isoF);
            position[e] = glm::vec3(vertex.position.x, vertex.position.y, vertex.position.z);
            normal[e] = glm::vec3(vertex.normal.x, vertex.normal.y, vertex.normal.z);
        }
        return edges;
    }

    std::size_t cellSegments(std::uint32_t cellIndex, glm::vec3 eye, bool orthographic,
                             std::vector<SegmentEndpoints>& out) const {
        const glm::ivec3 p = cellCoords(cellIndex);
        float v[8];
        const int cubeCase = cellCase(p, v);
        const int triangles = kMcTriangleCount.count[cubeCase];
        if (triangles == 0)
            return 0;
        glm::vec3 position[12], normal[12];
        float distance[12];
        const unsigned edges = cellVertices(p, v, cubeCase, position, normal);
        for (int e = 0; e < 12; ++e)
            if (edges & (1u << e))
                distance[e] = silhouetteDistance(position[e], normal[e], eye, orthographic);
        const std::int8_t* row = kMcTriTable[cubeCase];
        for (int k = 0; row[k] >= 0; k += 3) {
            const glm::vec3 q[3] = {position[row[k]], position[row[k + 1]], position[row[k + 2]]};
            const float d[3] = {distance[row[k]], distance[row[k + 1]], distance[row[k + 2]]};
            SegmentEndpoints segment;
            if (silhouetteSegment(q, d, segment))
                out.push_back(segment);
        }
        return std::size_t(triangles);
    }

    const T* m_voxels;
    double m_iso;
    float m_isoF;
    GridDims m_dims;
    VoxelGridSetup m_voxelGrid; // after m_voxels: m_gradient points into both
    VoxelGradientSampler<T> m_gradient;
    const std::vector<double>& m_offset; // per slice, along the stack axis
    glm::dvec3 m_cellScale{1.0};
    double m_neighbourReach = RayVisibilityRule::kNeighbourReachCells;
    double m_cellRadius = 0.0; // largest centre-to-corner distance of any cell, mm
    glm::ivec3 m_macroDims{0};
    glm::ivec3 m_coarseDims{0};
};

} // namespace

RayCastSilhouetteCpu::RayCastSilhouetteCpu() = default;
RayCastSilhouetteCpu::~RayCastSilhouetteCpu() = default;

bool RayCastSilhouetteCpu::prepare(const volume::Volume& volume, const volume::BrickGrid& grid,
                                   double storedIso, bool withNormalCones, unsigned threads,
                                   const core::CancelToken* cancel, GradientStencil stencil) {
    m_impl = volume::dispatchVoxelType(volume.voxelType(), [&](auto tag) -> std::unique_ptr<Impl> {
        using T = decltype(tag);
        return std::make_unique<Engine<T>>(volume, storedIso, stencil);
    });
    if (m_impl->findCells(grid, withNormalCones, threads, cancel))
        return true;
    m_impl.reset(); // half a cell list is no cache
    return false;
}

bool RayCastSilhouetteCpu::isPrepared() const {
    return m_impl != nullptr;
}
std::size_t RayCastSilhouetteCpu::activeCellCount() const {
    return m_impl ? m_impl->cells.size() : 0;
}
std::size_t RayCastSilhouetteCpu::activeBrickCount() const {
    return m_impl ? m_impl->activeBricks : 0;
}
double RayCastSilhouetteCpu::selfSkipCells() {
    return RayVisibilityRule::kSelfSkipCells;
}

std::size_t RayCastSilhouetteCpu::extractSegments(const SilhouetteView& view, unsigned threads) {
    return m_impl ? m_impl->extract(view, threads) : 0;
}

std::size_t RayCastSilhouetteCpu::segmentChunkCount() const {
    return m_impl ? m_impl->usedChunks : 0;
}

const std::vector<SegmentEndpoints>& RayCastSilhouetteCpu::segmentChunk(std::size_t chunk) const {
    return m_impl->chunkSegments[chunk];
}

std::size_t RayCastSilhouetteCpu::segmentCount() const {
    std::size_t n = 0;
    for (std::size_t c = 0; c < segmentChunkCount(); ++c)
        n += m_impl->chunkSegments[c].size();
    return n;
}

std::size_t RayCastSilhouetteCpu::extractSegments(const SilhouetteView& view,
                                                  std::vector<SegmentEndpoints>& out,
                                                  unsigned threads) {
    const std::size_t triangles = extractSegments(view, threads);
    out.clear();
    out.reserve(segmentCount());
    for (std::size_t c = 0; c < segmentChunkCount(); ++c)
        out.insert(out.end(), segmentChunk(c).begin(), segmentChunk(c).end());
    return triangles;
}

bool RayCastSilhouetteCpu::isVisible(glm::dvec3 patientPoint, const SilhouetteView& view) const {
    return !m_impl || m_impl->visible(patientPoint, view);
}

const VoxelRayGrid& RayCastSilhouetteCpu::rayGrid() const {
    static const VoxelRayGrid empty;
    return m_impl ? m_impl->rayGrid : empty;
}

} // namespace lw::kernels::cpu
