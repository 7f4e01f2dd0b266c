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
// Slack of the normal-cone cull, relative to |eye - cell centre|: the cull's float round-off
// (relative 1e-6 at most) must never turn a culled cell into one with a segment.
constexpr float kConeSlack = 1e-4f;
// Cells culled per block: the cull fills a block's flags in one loop the compiler vectorises,
// then the block's uncertain cells are built.
constexpr std::size_t kCullBlock = 256;

// The view as the cull reads it: w = eye - centreWeight * centre (the direction itself for
// an orthographic view), the cell's radius (0 for an orthographic view: w is the same at
// every point), and the squared distance below which a cell is too near the eye to cull.
struct CullView {
    glm::vec3 eye{0.0f};
    float centreWeight = 0.0f;
    float radius = 0.0f;
    float nearLimit2 = 0.0f;
};

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
    // Per active cell (mode a only): a cone holding every vertex normal of the cell and the
    // cell's centre, so a view skips the cells whose normals cannot straddle the view direction.
    // In float planes (structure of arrays), because the cull tests every cell of every view and
    // then runs four to eight cells per instruction: 32 bytes a cell (20 MB for the 610 thousand
    // cells of the demo split in three). A cell never culled has cosA = 0 (its reach is negative).
    struct ConePlanes {
        std::vector<float> centreX, centreY, centreZ; // mm, relative to coneOrigin
        std::vector<float> axisX, axisY, axisZ;       // unit length
        std::vector<float> cosA, sinA;                // of the half angle
        void resize(std::size_t n) {
            for (auto* plane : {&centreX, &centreY, &centreZ, &axisX, &axisY, &axisZ, &cosA, &sinA})
                plane->assign(n, 0.0f);
        }
        bool empty() const { return cosA.empty(); }
        void clear() { resize(0); }
    };
    ConePlanes cones;
    glm::dvec3 coneOrigin{0.0};   // the volume's centre: the float centres keep their precision
    double coneOriginSlack = 0.0; // mm, covers the float centres' and eye's round-off
    std::vector<std::uint8_t> macroOccupied;  // per macro cell: holds a voxel >= iso
    std::vector<std::uint8_t> coarseOccupied; // per coarse block: holds an occupied macro cell
    // Per-chunk outputs, kept between frames so a new view allocates nothing once warm.
    std::vector<std::vector<SegmentEndpoints>> chunkSegments;
    std::size_t usedChunks = 0; // chunks of the last extract (chunkSegments may hold more)
    std::vector<std::size_t> chunkTriangles;
    std::vector<std::size_t> chunkBuiltCells;    // per chunk of the last extract: cells not culled
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
        placeConeOrigin();
        chunkTriangleTotal.assign(chunkStarts.size() - 1, 0);
        core::parallelFor(
            chunkStarts.size() - 1,
            [&](std::size_t c) {
                std::size_t triangles = 0;
                for (std::size_t i = chunkStarts[c]; i < chunkStarts[c + 1]; ++i)
                    triangles += buildCone(i);
                chunkTriangleTotal[c] = triangles;
            },
            threads);
    }

    // The cones' centres are stored relative to the volume's centre, so their float round-off is
    // relative to the volume's extent; the cull's absolute slack covers it (with the eye's) 20
    // times over.
    void placeConeOrigin() {
        const glm::ivec3 last(m_dims.cx - 1, m_dims.cy - 1, m_dims.cz - 1);
        coneOrigin = 0.5 * (cellCentre({0, 0, 0}) + cellCentre(last));
        double extent = 0.0;
        for (int corner = 0; corner < 8; ++corner) {
            const glm::ivec3 p((corner & 1) ? last.x : 0, (corner & 2) ? last.y : 0,
                               (corner & 4) ? last.z : 0);
            const glm::dvec3 d = glm::abs(cellCentre(p) - coneOrigin);
            extent = std::max({extent, d.x, d.y, d.z});
        }
        coneOriginSlack = 1e-5 * extent;
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
        chunkBuiltCells.assign(chunks, 0);
        const CullView cull = cullView(view);
        core::parallelFor(
            chunks, [&](std::size_t c) { extractChunk(c, view, cull); }, threads);
        usedChunks = chunks;
        std::size_t triangles = 0;
        for (std::size_t c = 0; c < chunks; ++c)
            triangles += chunkTriangles[c];
        return triangles;
    }

    void extractChunk(std::size_t c, const SilhouetteView& view, const CullView& cull) {
        const glm::vec3 eye(view.eyeOrDirection);
        auto& segments = chunkSegments[c];
        segments.clear();
        const std::size_t begin = chunkStarts[c], end = chunkStarts[c + 1];
        if (cones.empty()) {
            std::size_t triangles = 0;
            for (std::size_t i = begin; i < end; ++i)
                triangles += cellSegments(cells[i], eye, view.orthographic, segments);
            chunkTriangles[c] = triangles;
            chunkBuiltCells[c] = end - begin;
            return;
        }
        // Every cell's triangles count as visited; only the uncertain cells are built.
        std::uint8_t keep[kCullBlock];
        std::size_t built = 0;
        for (std::size_t block = begin; block < end; block += kCullBlock) {
            const std::size_t n = std::min(kCullBlock, end - block);
            markUncertain(block, n, cull, keep);
            for (std::size_t k = 0; k < n; ++k)
                if (keep[k]) {
                    cellSegments(cells[block + k], eye, view.orthographic, segments);
                    ++built;
                }
        }
        chunkTriangles[c] = chunkTriangleTotal[c];
        chunkBuiltCells[c] = built;
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

    // Centre of cell p in patient mm.
    glm::dvec3 cellCentre(glm::ivec3 p) const {
        const double s = 0.5 * (m_offset[std::size_t(p.z)] + m_offset[std::size_t(p.z) + 1]);
        return m_voxelGrid.origin() + (p.x + 0.5) * m_voxelGrid.stepI() +
               (p.y + 0.5) * m_voxelGrid.stepJ() + s * m_voxelGrid.stack();
    }

    // Cell i's centre and the cone around its vertex normals into the planes; returns the cell's
    // triangle count.
    std::size_t buildCone(std::size_t i) {
        const glm::ivec3 p = cellCoords(cells[i]);
        const glm::dvec3 centre = cellCentre(p) - coneOrigin;
        cones.centreX[i] = float(centre.x);
        cones.centreY[i] = float(centre.y);
        cones.centreZ[i] = float(centre.z);
        float v[8];
        const int cubeCase = cellCase(p, v);
        glm::vec3 position[12], normal[12];
        const unsigned edges = cellVertices(p, v, cubeCase, position, normal);
        const std::size_t triangles = std::size_t(kMcTriangleCount.count[cubeCase]);
        glm::dvec3 sum(0.0);
        for (int e = 0; e < 12; ++e)
            if (edges & (1u << e))
                sum += glm::dvec3(normal[e]);
        const double length = glm::length(sum);
        if (!(length > 1e-6))
            return triangles; // cosA 0: never culled
        // The angle is measured from the float axis the cull reads, so the cone stays
        // conservative; 1e-5 rad more for the float cos and sin.
        const glm::vec3 axis(sum / length);
        double minCos = 1.0;
        for (int e = 0; e < 12; ++e)
            if (edges & (1u << e))
                minCos = std::min(minCos, glm::dot(glm::dvec3(axis), glm::dvec3(normal[e])) /
                                              glm::length(glm::dvec3(normal[e])));
        const double angle = std::acos(std::clamp(minCos, -1.0, 1.0)) + 1e-5;
        if (!(angle < 0.5 * 3.14159265358979323846))
            return triangles; // a cone of 90 degrees holds both sides of every view
        cones.axisX[i] = axis.x;
        cones.axisY[i] = axis.y;
        cones.axisZ[i] = axis.z;
        cones.cosA[i] = float(std::cos(angle));
        cones.sinA[i] = float(std::sin(angle));
        return triangles;
    }

    CullView cullView(const SilhouetteView& view) const {
        if (view.orthographic)
            return {glm::vec3(view.eyeOrDirection), 0.0f, 0.0f, 0.0f};
        const auto radius = float((m_cellRadius + coneOriginSlack) * (1.0 + 1e-6));
        return {glm::vec3(view.eyeOrDirection - coneOrigin), 1.0f, radius,
                float(4.0 * m_cellRadius * m_cellRadius)};
    }

    // keep[k] = 0 where cell begin + k certainly holds no silhouette segment: d = N . w has the
    // same sign, with margin, at every point of the cell and every normal N of its cone. The
    // minimum over the cone of N . w^ is cos(theta + alpha): one sign throughout when
    // |d| cos(alpha) - margin > |axis x w| sin(alpha) (both sides then non-negative, so squared).
    // |axis x w|, not sqrt(|w|^2 - d^2): no cancellation where w runs along the axis, so the
    // float round-off stays far below the slack. One branch-free loop over the planes, which the
    // compiler vectorises: every cell of every view passes here.
    void markUncertain(std::size_t begin, std::size_t n, const CullView& view,
                       std::uint8_t* keep) const {
        const float* cx = cones.centreX.data() + begin;
        const float* cy = cones.centreY.data() + begin;
        const float* cz = cones.centreZ.data() + begin;
        const float* ax = cones.axisX.data() + begin;
        const float* ay = cones.axisY.data() + begin;
        const float* az = cones.axisZ.data() + begin;
        const float* cosA = cones.cosA.data() + begin;
        const float* sinA = cones.sinA.data() + begin;
        for (std::size_t k = 0; k < n; ++k) {
            const float wx = view.eye.x - view.centreWeight * cx[k];
            const float wy = view.eye.y - view.centreWeight * cy[k];
            const float wz = view.eye.z - view.centreWeight * cz[k];
            const float l2 = wx * wx + wy * wy + wz * wz;
            const float d = ax[k] * wx + ay[k] * wy + az[k] * wz;
            const float px = ay[k] * wz - az[k] * wy;
            const float py = az[k] * wx - ax[k] * wz;
            const float pz = ax[k] * wy - ay[k] * wx;
            const float across = (px * px + py * py + pz * pz) * (sinA[k] * sinA[k]);
            const float margin =
                view.radius + kConeSlack * (std::abs(wx) + std::abs(wy) + std::abs(wz));
            const float reach = std::abs(d) * cosA[k] - margin;
            const bool culled = (l2 > view.nearLimit2) & (reach > 0.0f) & (reach * reach > across);
            keep[k] = std::uint8_t(!culled);
        }
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

std::size_t RayCastSilhouetteCpu::builtCellCount() const {
    std::size_t n = 0;
    for (std::size_t c = 0; c < segmentChunkCount(); ++c)
        n += m_impl->chunkBuiltCells[c];
    return n;
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
