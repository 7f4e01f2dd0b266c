#pragma once

// Marching-cubes kernels (dispatch in marching_cubes_cuda.cu, constants in tuning.h). Each kernel
// evaluates the shared host+device expressions of kernels/common, so the vertices equal the CPU
// reference's bit for bit.

#include "dispatch.h"
#include "lw/kernels/marching_cubes.h"
#include "lw/kernels/voxel_grid.h"
#include "tuning.h"

#include <cfloat>
#include <cstdint>
#include <cub/block/block_reduce.cuh>
#include <mutex>

namespace lw::kernels::cuda::mc {

// The tables in constant memory (the host constexpr arrays cannot be indexed in device code).
// Without relocatable device code each translation unit that includes this header has its own
// copy, so each fills its own through uploadTables() (internal linkage: one per unit).
__constant__ std::int8_t c_triTable[256][16];
__constant__ std::uint8_t c_triCount[256];
__constant__ std::int8_t c_edgeOwner[12][4];
__constant__ std::uint16_t c_edgeTable[256];
__constant__ std::int8_t c_edgeCorners[12][2];
__constant__ std::int8_t c_cornerOffset[8][3];
// The same tables in global memory, for the per-voxel kernels: neighbouring threads hold
// different cases, and constant memory serves a warp's different addresses one after another
// while the L1 cache serves them at once. A case's row of the triangle table is one 16-byte
// load; an edge's owner (dx, dy, dz, axis) one 32-bit word, a byte each.
__device__ uint4 g_triRows[256];
__device__ std::uint32_t g_edgeOwnerWord[12];
__device__ std::uint8_t g_triCount[256];

static CudaStatus uploadTables() {
    static std::once_flag once;
    static CudaStatus status;
    std::call_once(once, [] {
        struct Table {
            const void* symbol;
            const void* source;
            std::size_t bytes;
            const char* what;
        };
        const Table tables[] = {
            {c_triTable, kMcTriTable, sizeof kMcTriTable, "cudaMemcpyToSymbol(triTable)"},
            {c_triCount, kMcTriangleCount.count, sizeof kMcTriangleCount.count,
             "cudaMemcpyToSymbol(triCount)"},
            {c_edgeOwner, kMcEdgeOwner, sizeof kMcEdgeOwner, "cudaMemcpyToSymbol(edgeOwner)"},
            {c_edgeTable, kMcEdgeTable, sizeof kMcEdgeTable, "cudaMemcpyToSymbol(edgeTable)"},
            {c_edgeCorners, kMcEdgeCorners, sizeof kMcEdgeCorners,
             "cudaMemcpyToSymbol(edgeCorners)"},
            {c_cornerOffset, kMcCornerOffset, sizeof kMcCornerOffset,
             "cudaMemcpyToSymbol(cornerOffset)"},
            {g_triRows, kMcTriTable, sizeof kMcTriTable, "cudaMemcpyToSymbol(triRows)"},
            {g_edgeOwnerWord, kMcEdgeOwner, sizeof kMcEdgeOwner,
             "cudaMemcpyToSymbol(edgeOwnerWord)"},
            {g_triCount, kMcTriangleCount.count, sizeof kMcTriangleCount.count,
             "cudaMemcpyToSymbol(triCount, global)"},
        };
        for (const Table& t : tables) {
            status = dispatch::statusOf(cudaMemcpyToSymbol(t.symbol, t.source, t.bytes), t.what);
            if (!status.ok())
                return;
        }
        // Landed before any kernel reads them: the copies above may return before their DMA is
        // done, and the kernels run on non-blocking streams that do not wait for it.
        status = dispatch::statusOf(cudaDeviceSynchronize(), "cudaMemcpyToSymbol(tables)");
    });
    return status;
}

// Everything a kernel needs to know about the grid, by value.
template <typename T> struct Grid {
    // The resident voxels, x fastest: the whole volume (S) or one brick's box (streamed L).
    const T* box;
    std::uint32_t boxX, boxY; // box strides: 1, boxX, boxX * boxY
    glm::ivec3 boxOrigin;     // the volume voxel stored at box[0]
    std::size_t indexOrigin;  // boxOrigin's linear index with the box strides (see
                              // VoxelGradientSampler::indexOrigin)
    // The voxels classified, inclusive, in volume coordinates; their edges and cells end at hi
    // (S: 0 .. dims - 1; a brick: its cells' corner voxels cellBegin .. cellEnd).
    glm::ivec3 lo, hi;
    std::uint32_t rowsY; // hi.y - lo.y + 1
    GridSpans spans;     // the volume's, with the box strides; spanK/invSpanK on the device
    McGridFrame frame;   // sliceOffset on the device
    T threshold;         // inside = voxel >= threshold (== value >= iso, exactly)
    double iso;
    float isoF;
    // Skip bricks (S only, null for a streamed brick): brick of voxel (x, y, z) =
    // (min(x, cx - 1), ...) >> kSkipBrickShift.
    const std::uint8_t* brickActive;
    std::uint32_t bricksX, bricksY;

    __device__ std::uint32_t boxIndex(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
        return (x - boxOrigin.x) + boxX * ((y - boxOrigin.y) + boxY * (z - boxOrigin.z));
    }
};

// The inside bits of a voxel's four corners in one slice: (x, y), (x + 1, y), (x, y + 1),
// (x + 1, y + 1); a corner beyond the classified range (hasX / hasY false) reads nothing and is 0.
struct PlaneBits {
    bool c00 = false, c10 = false, c01 = false, c11 = false;
};
template <typename T>
__device__ __forceinline__ PlaneBits planeBits(const T* p, std::size_t sy, T threshold, bool hasX,
                                               bool hasY) {
    PlaneBits b;
    b.c00 = p[0] >= threshold;
    b.c10 = hasX && p[1] >= threshold;
    b.c01 = hasY && p[sy] >= threshold;
    b.c11 = hasX && hasY && p[1 + sy] >= threshold;
    return b;
}

// The code of a voxel from its corners in its slice (lower) and the next (upper): bits 0-7 its
// cell's case (0 when the cell has no triangles or does not exist), bits 8-10 which of its +x,
// +y, +z edges cross the surface. 0 = inactive.
__device__ __forceinline__ std::uint32_t voxelCode(PlaneBits lower, PlaneBits upper, bool hasX,
                                                   bool hasY, bool hasZ) {
    // Corners in diagram order: 0 (0,0,0) 1 (1,0,0) 2 (1,1,0) 3 (0,1,0), 4-7 the same at z + 1.
    const bool c0 = lower.c00;
    const std::uint32_t edges = (hasX && c0 != lower.c10 ? 1u : 0u) |
                                (hasY && c0 != lower.c01 ? 2u : 0u) |
                                (hasZ && c0 != upper.c00 ? 4u : 0u);
    std::uint32_t cubeCase = 0;
    if (hasX && hasY && hasZ) {
        cubeCase = std::uint32_t(c0) | std::uint32_t(lower.c10) << 1 |
                   std::uint32_t(lower.c11) << 2 | std::uint32_t(lower.c01) << 3 |
                   std::uint32_t(upper.c00) << 4 | std::uint32_t(upper.c10) << 5 |
                   std::uint32_t(upper.c11) << 6 | std::uint32_t(upper.c01) << 7;
        if (cubeCase == 255)
            cubeCase = 0;
    }
    return cubeCase | edges << 8;
}

struct MinOp {
    __device__ float operator()(float a, float b) const { return fminf(a, b); }
};
struct MaxOp {
    __device__ float operator()(float a, float b) const { return fmaxf(a, b); }
};

// Min/max over the corner voxels of each skip brick (one block per brick).
template <typename T>
__global__ void brickMinMax(const T* voxels, std::uint32_t nx, std::uint32_t ny, std::uint32_t nz,
                            std::uint32_t bricksX, std::uint32_t bricksY, float2* minMax) {
    using Reduce = cub::BlockReduce<float, tuning::kBrickReduceBlock>;
    __shared__ typename Reduce::TempStorage tempMin, tempMax;
    const std::uint32_t b = blockIdx.x;
    const std::uint32_t bx = b % bricksX, by = (b / bricksX) % bricksY,
                        bz = b / (bricksX * bricksY);
    const std::uint32_t n = tuning::kSkipBrickCells;
    const std::uint32_t x0 = bx * n, y0 = by * n, z0 = bz * n;
    const std::uint32_t x1 = min(x0 + n, nx - 1), y1 = min(y0 + n, ny - 1),
                        z1 = min(z0 + n, nz - 1);
    const std::uint32_t w = x1 - x0 + 1, h = y1 - y0 + 1, d = z1 - z0 + 1;
    float lo = FLT_MAX, hi = -FLT_MAX;
    for (std::uint32_t i = threadIdx.x; i < w * h * d; i += blockDim.x) {
        const std::uint32_t x = x0 + i % w, y = y0 + (i / w) % h, z = z0 + i / (w * h);
        const float value = float(voxels[(std::size_t(z) * ny + y) * nx + x]);
        lo = fminf(lo, value);
        hi = fmaxf(hi, value);
    }
    lo = Reduce(tempMin).Reduce(lo, MinOp());
    hi = Reduce(tempMax).Reduce(hi, MaxOp());
    if (threadIdx.x == 0)
        minMax[b] = make_float2(lo, hi);
}

static __global__ void markActiveBricks(const float2* minMax, std::uint32_t count, double iso,
                                        std::uint8_t* active) {
    const std::uint32_t b = blockIdx.x * blockDim.x + threadIdx.x;
    if (b < count)
        active[b] = double(minMax[b].x) < iso && iso <= double(minMax[b].y) ? 1 : 0;
}

// Sets *flag when a voxel on the volume's six faces is inside.
template <typename T>
__global__ void borderInside(const T* voxels, std::uint32_t nx, std::uint32_t ny, std::uint32_t nz,
                             T threshold, int* flag) {
    // Face f (blockIdx.y): 0/1 z = 0 / nz-1, 2/3 y = 0 / ny-1, 4/5 x = 0 / nx-1.
    const int f = blockIdx.y;
    const std::uint32_t a = f < 2 ? nx : (f < 4 ? nx : ny);
    const std::uint32_t b = f < 2 ? ny : nz;
    for (std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x; i < a * b;
         i += gridDim.x * blockDim.x) {
        const std::uint32_t u = i % a, w = i / a;
        std::uint32_t x, y, z;
        if (f < 2) {
            x = u, y = w, z = f == 0 ? 0 : nz - 1;
        } else if (f < 4) {
            x = u, z = w, y = f == 2 ? 0 : ny - 1;
        } else {
            y = u, z = w, x = f == 4 ? 0 : nx - 1;
        }
        if (voxels[(std::size_t(z) * ny + y) * nx + x] >= threshold)
            *flag = 1;
    }
}

// The classification grid. A tile is a run of kClassifyBlock voxels of one voxel row, one voxel
// per thread, x fastest; tiles are numbered row by row (tile = row * tilesPerRow + column, row =
// (z - lo.z) * rowsY + (y - lo.y)), so tile order is voxel order. A block walks its column of
// kClassifyPlanes tiles up along z (blockIdx.x = zGroup * rowsY + y - lo.y, blockIdx.y = the
// column): each slice's corner bits serve two voxels, and one block does the work of several
// (block launches, not memory, bounded the one-tile-per-block version).
template <typename T> struct TileWalk {
    const Grid<T>& g;
    std::uint32_t x, y, z0, planes, column;
    bool valid, hasX, hasY;

    __device__ explicit TileWalk(const Grid<T>& grid) : g(grid) {
        const std::uint32_t zGroup = blockIdx.x / g.rowsY;
        column = blockIdx.y;
        x = g.lo.x + column * tuning::kClassifyBlock + threadIdx.x;
        y = g.lo.y + blockIdx.x % g.rowsY;
        z0 = g.lo.z + zGroup * tuning::kClassifyPlanes;
        const std::uint32_t left = std::uint32_t(g.hi.z) - z0 + 1;
        planes = left < tuning::kClassifyPlanes ? left : tuning::kClassifyPlanes;
        valid = int(x) <= g.hi.x;
        hasX = int(x) < g.hi.x;
        hasY = int(y) < g.hi.y;
    }
    __device__ std::uint32_t tile(std::uint32_t plane) const {
        const std::uint32_t row = (z0 + plane - g.lo.z) * g.rowsY + (y - g.lo.y);
        return row * gridDim.y + column;
    }
    __device__ bool brickActive(std::uint32_t z) const {
        if (!g.brickActive)
            return true;
        const std::uint32_t cx = g.spans.dims.cx, cy = g.spans.dims.cy, cz = g.spans.dims.cz;
        const std::uint32_t bx = (x < cx ? x : cx - 1) >> tuning::kSkipBrickShift;
        const std::uint32_t by = (y < cy ? y : cy - 1) >> tuning::kSkipBrickShift;
        const std::uint32_t bz = (z < cz ? z : cz - 1) >> tuning::kSkipBrickShift;
        return g.brickActive[(bz * g.bricksY + by) * g.bricksX + bx] != 0;
    }
    // Whether this thread's voxels can be active: a column's planes lie in one layer of skip
    // bricks (kClassifyPlanes divides the brick edge and groups start at multiples of it), so
    // its first and last plane tell.
    __device__ bool mayBeActive() const {
        return valid && (brickActive(z0) || brickActive(z0 + planes - 1));
    }
    // The inside bits of this thread's corners in slices z0 .. z0 + planes (the last one only
    // where it exists), read all at once: the loads are independent, so they are all in flight
    // together instead of one slice's wait after another's.
    __device__ void readPlanes(std::uint8_t (&bits)[tuning::kClassifyPlanes + 1]) const {
        const std::size_t sy = g.boxX, sz = std::size_t(g.boxX) * g.boxY;
        const T* p = g.box + g.boxIndex(x, y, z0);
#pragma unroll
        for (int q = 0; q <= tuning::kClassifyPlanes; ++q) {
            PlaneBits b;
            if (int(z0) + q <= g.hi.z)
                b = planeBits(p + std::size_t(q) * sz, sy, g.threshold, hasX, hasY);
            bits[q] = std::uint8_t(b.c00 | b.c10 << 1 | b.c01 << 2 | b.c11 << 3);
        }
    }
    // Whether the voxel in `plane` is active (voxelCode != 0). Inside the classified range all
    // its eight corners exist, and then it is active exactly when they are not all alike (its
    // edges' ends are corners of its cell): one test on the eight bits instead of the code.
    __device__ bool isActive(const std::uint8_t (&bits)[tuning::kClassifyPlanes + 1],
                             int plane) const {
        const bool hasZ = int(z0) + plane < g.hi.z;
        if (hasX && hasY && hasZ) {
            const std::uint32_t corners = bits[plane] | std::uint32_t(bits[plane + 1]) << 4;
            return corners != 0 && corners != 0xffu;
        }
        return voxelCode(unpack(bits[plane]), hasZ ? unpack(bits[plane + 1]) : PlaneBits{}, hasX,
                         hasY, hasZ) != 0;
    }
    __device__ static PlaneBits unpack(std::uint8_t b) {
        return PlaneBits{(b & 1) != 0, (b & 2) != 0, (b & 4) != 0, (b & 8) != 0};
    }
};
static_assert(tuning::kSkipBrickCells % tuning::kClassifyPlanes == 0,
              "a classification block's planes must lie in one layer of skip bricks");

__device__ __forceinline__ std::uint32_t laneIndex() {
    return threadIdx.x & 31u;
}

// The code of one voxel read on its own (the compaction's second pass and anything that starts
// from a voxel of the active list): the walk's code() without the reuse or the brick skip. A voxel
// the walk found active has the same code here.
template <typename T>
__device__ __forceinline__ std::uint32_t voxelCodeAt(const Grid<T>& g, std::uint32_t x,
                                                     std::uint32_t y, std::uint32_t z) {
    const bool hasX = int(x) < g.hi.x, hasY = int(y) < g.hi.y, hasZ = int(z) < g.hi.z;
    const std::size_t sy = g.boxX, sz = std::size_t(g.boxX) * g.boxY;
    const T* p = g.box + g.boxIndex(x, y, z);
    const PlaneBits lower = planeBits(p, sy, g.threshold, hasX, hasY);
    const PlaneBits upper = hasZ ? planeBits(p + sz, sy, g.threshold, hasX, hasY) : PlaneBits{};
    return voxelCode(lower, upper, hasX, hasY, hasZ);
}

// The active bitmap: one bit per classified voxel, a 32-bit word per warp of a tile, so word w
// holds the voxels x = lo.x + 32 * (w % wordsPerRow) + bit of row w / wordsPerRow (rows as the
// tiles number them). Word order is voxel order, so an exclusive scan of the words' bit counts
// gives every active voxel its place in the ordered list -- and any voxel's place is two loads
// (activeSlot), which is how the triangles find their corners' vertices.
//
//   row r:  | word r*W+0 | word r*W+1 | ... |   W = wordsPerRow = 8 * tiles per row
//             x lo..lo+31  lo+32..lo+63
struct ActiveBitmap {
    const std::uint32_t* words;
    const std::uint32_t* offsets; // exclusive scan of the words' popcounts
    std::uint32_t wordsPerRow;

    __device__ std::uint32_t wordOf(glm::ivec3 lo, std::uint32_t rowsY, std::uint32_t x,
                                    std::uint32_t y, std::uint32_t z) const {
        const std::uint32_t row = (z - lo.z) * rowsY + (y - lo.y);
        return row * wordsPerRow + (x - lo.x) / 32u;
    }
    // The place in the active list of an active voxel.
    __device__ std::uint32_t activeSlot(glm::ivec3 lo, std::uint32_t rowsY, std::uint32_t x,
                                        std::uint32_t y, std::uint32_t z) const {
        const std::uint32_t w = wordOf(lo, rowsY, x, y, z);
        const std::uint32_t bit = (x - lo.x) & 31u;
        return offsets[w] + __popc(words[w] & ((1u << bit) - 1u));
    }
};

// Pass 1 of the compaction: each warp's ballot over its 32 voxels is one word of the bitmap
// (no shared memory, no barrier).
template <typename T> __global__ void classifyWords(Grid<T> g, std::uint32_t* activeWords) {
    constexpr std::uint32_t kWarps = tuning::kClassifyBlock / 32;
    const TileWalk<T> walk(g);
    const std::uint32_t warp = threadIdx.x / 32;
    const bool mayBeActive = walk.mayBeActive();
    std::uint8_t bits[tuning::kClassifyPlanes + 1] = {};
    if (mayBeActive)
        walk.readPlanes(bits);
    // Word of plane q: the first plane's, one plane of words further per plane.
    std::uint32_t* word = activeWords + walk.tile(0) * kWarps + warp;
    const std::uint32_t wordsPerPlane = g.rowsY * gridDim.y * kWarps;
#pragma unroll
    for (int plane = 0; plane < tuning::kClassifyPlanes; ++plane) {
        if (plane >= int(walk.planes))
            break; // the same for the whole block
        const bool active = mayBeActive && walk.isActive(bits, plane);
        const unsigned ballot = __ballot_sync(0xffffffffu, active);
        if (laneIndex() == 0)
            *word = ballot;
        word += wordsPerPlane;
    }
}

// Pass 2: the active voxels, their codes and their vertex and triangle counts, in voxel order
// (entry `count` of the counts is 0, so the exclusive scans end with the totals), as far as
// `capacity` entries (+ 1 for the counts) go. A
// warp takes 32 words, one a lane, and visits the non-empty ones together: lane b writes bit b's
// voxel, so its reads coalesce.
template <typename T>
__global__ void writeActive(Grid<T> g, ActiveBitmap bitmap, std::uint32_t wordCount,
                            std::uint32_t capacity, std::uint32_t* activeVoxels,
                            std::uint16_t* activeCodes, std::uint32_t* vertexCounts,
                            std::uint32_t* triangleCounts) {
    const std::uint32_t lane = laneIndex();
    const std::uint32_t firstWord = (blockIdx.x * blockDim.x + threadIdx.x) & ~31u;
    const std::uint32_t mine = firstWord + lane < wordCount ? bitmap.words[firstWord + lane] : 0u;
    unsigned nonEmpty = __ballot_sync(0xffffffffu, mine != 0);
    while (nonEmpty) {
        const int j = __ffs(nonEmpty) - 1;
        nonEmpty &= nonEmpty - 1;
        const std::uint32_t bits = __shfl_sync(0xffffffffu, mine, j);
        if (!(bits & (1u << lane)))
            continue;
        const std::uint32_t w = firstWord + std::uint32_t(j);
        const std::uint32_t row = w / bitmap.wordsPerRow;
        const std::uint32_t x = g.lo.x + (w % bitmap.wordsPerRow) * 32u + lane;
        const std::uint32_t y = g.lo.y + row % g.rowsY, z = g.lo.z + row / g.rowsY;
        const std::uint32_t slot = bitmap.offsets[w] + __popc(bits & ((1u << lane) - 1u));
        if (slot >= capacity)
            continue; // the list is too short: the host writes it again, longer
        const std::uint32_t code = voxelCodeAt(g, x, y, z);
        activeVoxels[slot] = g.boxIndex(x, y, z);
        activeCodes[slot] = std::uint16_t(code);
        vertexCounts[slot] = __popc(code >> 8);
        triangleCounts[slot] = __ldg(&g_triCount[code & 0xff]);
        if (slot + 1 == bitmap.offsets[wordCount]) { // the last: the scans' end entry is 0
            vertexCounts[slot + 1] = 0;
            triangleCounts[slot + 1] = 0;
        }
    }
}

// totals = {active voxels, vertices, triangles}: what the host needs after the scans, in one
// place so one copy fetches it. The offsets are read at the active count where the list held it
// (otherwise they mean nothing: the host writes the list again).
static __global__ void gatherTotals(const std::uint32_t* activeTotal,
                                    const std::uint32_t* vertexOffsets,
                                    const std::uint32_t* triangleOffsets, std::uint32_t capacity,
                                    std::uint32_t* totals) {
    const std::uint32_t active = *activeTotal;
    const std::uint32_t at = active <= capacity ? active : 0u;
    totals[0] = active;
    totals[1] = vertexOffsets[at];
    totals[2] = triangleOffsets[at];
}

template <typename T>
__global__ void generateVertices(Grid<T> g, const std::uint32_t* activeVoxels,
                                 const std::uint16_t* codes, const std::uint32_t* vertexOffsets,
                                 std::uint32_t count, glm::vec3* positions, glm::vec3* normals) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count)
        return;
    const std::uint32_t edges = codes[i] >> 8;
    if (edges == 0)
        return;
    const std::uint32_t v = activeVoxels[i];
    const int x = g.boxOrigin.x + int(v % g.boxX), y = g.boxOrigin.y + int((v / g.boxX) % g.boxY),
              z = g.boxOrigin.z + int(v / (g.boxX * g.boxY));
    const VoxelGradientSampler<T> sampler{g.box, g.spans, g.indexOrigin};
    const McVec3 here = sampler.gradient(x, y, z);
    std::uint32_t id = vertexOffsets[i];
    for (int axis = 0; axis < 3; ++axis) {
        if (!(edges & (1u << axis)))
            continue;
        const McVec3 there = sampler.gradient(x + (axis == 0), y + (axis == 1), z + (axis == 2));
        const McVertex vertex =
            sampler.edgeVertex(g.frame, x, y, z, axis, here, there, g.iso, g.isoF);
        positions[id] = glm::vec3(vertex.position.x, vertex.position.y, vertex.position.z);
        normals[id] = glm::vec3(vertex.normal.x, vertex.normal.y, vertex.normal.z);
        ++id;
    }
}

// The triangles of each active voxel's cell, their corners the vertices of the edges they cross:
// an edge's vertex belongs to the edge's owner voxel (this one or a neighbour further on), whose
// place in the active list the bitmap gives.
template <typename T>
__global__ void generateTriangles(Grid<T> g, ActiveBitmap bitmap, const std::uint32_t* activeVoxels,
                                  const std::uint16_t* codes, const std::uint32_t* vertexOffsets,
                                  const std::uint32_t* triangleOffsets, std::uint32_t count,
                                  std::uint32_t* indices) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count)
        return;
    const std::uint32_t cubeCase = codes[i] & 0xff;
    if (cubeCase == 0)
        return;
    const std::uint32_t v = activeVoxels[i];
    const std::uint32_t x = g.boxOrigin.x + v % g.boxX, y = g.boxOrigin.y + (v / g.boxX) % g.boxY,
                        z = g.boxOrigin.z + v / (g.boxX * g.boxY);
    std::uint32_t* out = indices + std::size_t(triangleOffsets[i]) * 3;
    const uint4 row = __ldg(&g_triRows[cubeCase]);
    const std::uint32_t rowWords[4] = {row.x, row.y, row.z, row.w};
    for (int k = 0; k < 15; ++k) {
        const int edge = std::int8_t(rowWords[k >> 2] >> (8 * (k & 3)));
        if (edge < 0)
            break;
        const std::uint32_t owner = __ldg(&g_edgeOwnerWord[edge]);
        const std::uint32_t dx = owner & 0xffu, dy = (owner >> 8) & 0xffu,
                            dz = (owner >> 16) & 0xffu, axis = owner >> 24;
        // The owner is active (its edge crosses) and within the classified range.
        const std::uint32_t slot =
            (owner & 0xffffffu) == 0 ? i : bitmap.activeSlot(g.lo, g.rowsY, x + dx, y + dy, z + dz);
        const std::uint32_t ownerEdges = codes[slot] >> 8;
        out[k] = vertexOffsets[slot] + __popc(ownerEdges & ((1u << axis) - 1u));
    }
}

} // namespace lw::kernels::cuda::mc
