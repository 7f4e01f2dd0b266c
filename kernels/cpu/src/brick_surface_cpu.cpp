#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/marching_cubes.h"

#include <cstring>

// One brick's marching cubes, single-threaded and without the whole-volume edge numbering of
// marchingCubes(): classify the brick's corner voxels once, number the crossing edges
// brick-locally, then emit the cells' triangles. The vertex values come from the same
// VoxelGridSetup, VoxelGradientSampler and mcEdgeVertex as marchingCubes(); the test
// "BrickSurfacesEqualWholeMesh" checks that the bits agree.

namespace lw::kernels::cpu {
namespace {

// True when the 9 bytes rows[r][x .. x + 8] of every row given are all 0 or all 1 (the same value
// throughout): the 8 cells (or voxels) starting at x then hold no crossing. Null rows are ignored.
inline bool uniformBlock(const std::uint8_t* const rows[4], std::size_t x) {
    constexpr std::uint64_t kOnes = 0x0101010101010101ull;
    std::uint64_t any = 0, all = kOnes;
    unsigned anyTail = 0, allTail = 1;
    for (int r = 0; r < 4; ++r) {
        if (!rows[r])
            continue;
        std::uint64_t word;
        std::memcpy(&word, rows[r] + x, sizeof word);
        any |= word;
        all &= word;
        anyTail |= rows[r][x + 8];
        allTail &= rows[r][x + 8];
    }
    return (any == 0 && anyTail == 0) || (all == kOnes && allTail == 1);
}

// The brick's corner voxels [cb, ce] as a local box: sizes, strides and each voxel row's state
// (BrickSurface::rowState: 0 all outside, 1 all inside, 2 mixed).
struct CornerBox {
    glm::ivec3 begin{0};
    int bx = 0, by = 0, bz = 0;
    std::size_t sy = 0, sz = 0, count = 0;

    CornerBox(glm::ivec3 cb, glm::ivec3 ce)
        : begin(cb), bx(ce.x - cb.x + 1), by(ce.y - cb.y + 1), bz(ce.z - cb.z + 1),
          sy(std::size_t(bx)), sz(std::size_t(bx) * std::size_t(by)), count(sz * std::size_t(bz)) {}
    std::size_t rowIndex(int ly, int lz) const {
        return std::size_t(ly) + std::size_t(by) * std::size_t(lz);
    }
    std::size_t voxelIndex(int ly, int lz) const {
        return sy * std::size_t(ly) + sz * std::size_t(lz);
    }
};

// Classifies the corner voxels once; each voxel row remembers whether it is uniform, so the
// vertex and cell passes skip rows (and cell rows) without a crossing.
template <typename T>
void classifyCorners(const T* voxels, const GridDims& dims, T threshold, const CornerBox& box,
                     BrickSurface& out) {
    out.inside.resize(box.count);
    out.rowState.resize(std::size_t(box.by) * std::size_t(box.bz));
    for (int lz = 0; lz < box.bz; ++lz)
        for (int ly = 0; ly < box.by; ++ly) {
            const T* row = voxels + std::size_t(box.begin.x) +
                           dims.sy * std::size_t(box.begin.y + ly) +
                           dims.sz * std::size_t(box.begin.z + lz);
            std::uint8_t* dst = out.inside.data() + box.voxelIndex(ly, lz);
            std::uint8_t any = 0, all = 1;
            for (int x = 0; x < box.bx; ++x) {
                const std::uint8_t in = row[x] >= threshold ? 1 : 0;
                dst[x] = in;
                any |= in;
                all &= in;
            }
            out.rowState[box.rowIndex(ly, lz)] = all ? 1 : (any ? 2 : 0);
        }
}

// Vertices: every crossing edge between two corner voxels of the brick, numbered brick-locally
// in out.edgeIds (per axis, at the edge's lower voxel).
template <typename T>
void writeCrossingVertices(const VoxelGradientSampler<T>& sampler, const McGridFrame& frame,
                           double iso, float isoF, const CornerBox& box, BrickSurface& out) {
    for (auto& ids : out.edgeIds)
        if (ids.size() < box.count)
            ids.resize(box.count);
    auto rowState = [&](int ly, int lz) { return out.rowState[box.rowIndex(ly, lz)]; };
    auto writeVertex = [&](int x, int y, int z, int axis, const McVec3& ga, const McVec3& gb) {
        const McVertex v = sampler.edgeVertex(frame, x, y, z, axis, ga, gb, iso, isoF);
        out.positions.push_back(glm::vec3(v.position.x, v.position.y, v.position.z));
        out.normals.push_back(glm::vec3(v.normal.x, v.normal.y, v.normal.z));
    };
    std::uint32_t id = 0;
    for (int lz = 0; lz < box.bz; ++lz)
        for (int ly = 0; ly < box.by; ++ly) {
            const std::uint8_t state = rowState(ly, lz);
            const bool hasY = ly + 1 < box.by, hasZ = lz + 1 < box.bz;
            if (state != 2 && (!hasY || rowState(ly + 1, lz) == state) &&
                (!hasZ || rowState(ly, lz + 1) == state))
                continue;
            const int y = box.begin.y + ly, z = box.begin.z + lz;
            const std::size_t base = box.voxelIndex(ly, lz);
            const std::uint8_t* in = out.inside.data() + base;
            const std::uint8_t* const block[4] = {in, hasY ? in + box.sy : nullptr,
                                                  hasZ ? in + box.sz : nullptr, nullptr};
            for (int lx = 0; lx < box.bx; ++lx) {
                if ((lx & 7) == 0 && lx + 8 < box.bx && uniformBlock(block, std::size_t(lx))) {
                    lx += 7;
                    continue;
                }
                const std::uint8_t a = in[lx];
                const bool crossX = lx + 1 < box.bx && in[lx + 1] != a;
                const bool crossY = hasY && in[std::size_t(lx) + box.sy] != a;
                const bool crossZ = hasZ && in[std::size_t(lx) + box.sz] != a;
                if (!(crossX || crossY || crossZ))
                    continue;
                const int x = box.begin.x + lx;
                const McVec3 here = sampler.gradient(x, y, z);
                if (crossX) {
                    out.edgeIds[0][base + std::size_t(lx)] = id++;
                    writeVertex(x, y, z, 0, here, sampler.gradient(x + 1, y, z));
                }
                if (crossY) {
                    out.edgeIds[1][base + std::size_t(lx)] = id++;
                    writeVertex(x, y, z, 1, here, sampler.gradient(x, y + 1, z));
                }
                if (crossZ) {
                    out.edgeIds[2][base + std::size_t(lx)] = id++;
                    writeVertex(x, y, z, 2, here, sampler.gradient(x, y, z + 1));
                }
            }
        }
}

// Triangles: the cells of the brick, corners in the table's diagram order.
void emitCellTriangles(const CornerBox& box, BrickSurface& out) {
    std::size_t edgeOffset[12];
    for (int e = 0; e < 12; ++e)
        edgeOffset[e] = std::size_t(kMcEdgeOwner[e][0]) + std::size_t(kMcEdgeOwner[e][1]) * box.sy +
                        std::size_t(kMcEdgeOwner[e][2]) * box.sz;
    auto rowState = [&](int ly, int lz) { return out.rowState[box.rowIndex(ly, lz)]; };
    for (int lz = 0; lz + 1 < box.bz; ++lz)
        for (int ly = 0; ly + 1 < box.by; ++ly) {
            const std::uint8_t state = rowState(ly, lz);
            if (state != 2 && rowState(ly + 1, lz) == state && rowState(ly, lz + 1) == state &&
                rowState(ly + 1, lz + 1) == state)
                continue;
            const std::size_t base = box.voxelIndex(ly, lz);
            const std::uint8_t* in = out.inside.data() + base;
            const std::uint8_t* const block[4] = {in, in + box.sy, in + box.sz,
                                                  in + box.sy + box.sz};
            auto column = [&](int lx) {
                return mcColumnBits([in](std::size_t i) { return in[i]; }, std::size_t(lx), box.sy,
                                    box.sz);
            };
            for (int lx = 0; lx + 1 < box.bx; ++lx) {
                if ((lx & 7) == 0 && lx + 8 < box.bx && uniformBlock(block, std::size_t(lx))) {
                    lx += 7;
                    continue;
                }
                const int cubeCase = mcCaseFromColumns(column(lx), column(lx + 1));
                if (cubeCase == 0 || cubeCase == 255)
                    continue;
                const std::int8_t* edges = kMcTriTable[cubeCase];
                const std::size_t cell = base + std::size_t(lx);
                for (int e = 0; edges[e] >= 0; ++e)
                    out.indices.push_back(
                        out.edgeIds[kMcEdgeOwner[edges[e]][3]][cell + edgeOffset[edges[e]]]);
            }
        }
}

} // namespace

BrickSurfaceExtractor::BrickSurfaceExtractor(const volume::Volume& volume, double storedIso,
                                             GradientStencil stencil)
    : m_volume(volume), m_iso(storedIso), m_isoF(insideThreshold(storedIso)),
      m_voxelGrid(voxelGridSetup(volume, stencil)) {}

void BrickSurfaceExtractor::extract(const volume::Brick& brick, BrickSurface& out) const {
    volume::dispatchVoxelType(m_volume.voxelType(), [&](auto tag) {
        using T = decltype(tag);
        extractTyped<T>(brick, out);
        return 0;
    });
}

template <typename T>
void BrickSurfaceExtractor::extractTyped(const volume::Brick& brick, BrickSurface& out) const {
    out.positions.clear();
    out.normals.clear();
    out.indices.clear();
    const GridDims& dims = m_voxelGrid.spans().dims;
    const glm::ivec3 cb = brick.cellBegin, ce = brick.cellEnd;
    if (dims.cx < 1 || dims.cy < 1 || dims.cz < 1 || glm::any(glm::lessThanEqual(ce, cb)))
        return;
    const T* voxels = m_volume.dataAs<T>();
    const CornerBox box(cb, ce);
    classifyCorners<T>(voxels, dims, voxelInsideThreshold<T>(m_iso), box, out);
    const VoxelGradientSampler<T> sampler{voxels, m_voxelGrid.spans()};
    writeCrossingVertices<T>(sampler, m_voxelGrid.frame(), m_iso, m_isoF, box, out);
    emitCellTriangles(box, out);
}

} // namespace lw::kernels::cpu
