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
        };
        for (const Table& t : tables) {
            status = dispatch::statusOf(cudaMemcpyToSymbol(t.symbol, t.source, t.bytes), t.what);
            if (!status.ok())
                return;
        }
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
// (block launches, not memory, bounded the one-tile-per-block version). Active voxels are listed
// by their index in the box (ascending = voxel order).
template <typename T> struct TileWalk {
    const Grid<T>& g;
    std::uint32_t x, y, z0, planes, column;
    bool valid, hasX, hasY;
    // The upper slice's bits of the last voxel, reused as the next voxel's lower slice.
    PlaneBits upper;
    bool haveUpper = false;

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
    __device__ std::uint32_t index(std::uint32_t plane) const {
        return valid ? g.boxIndex(x, y, z0 + plane) : 0u;
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
    // The code of this thread's voxel in `plane` (planes are visited in ascending order; a plane
    // skipped by the caller must be reported with skip() so the reuse starts over).
    __device__ std::uint32_t code(std::uint32_t plane) {
        const std::uint32_t z = z0 + plane;
        if (!valid || !brickActive(z)) {
            haveUpper = false;
            return 0u;
        }
        const bool hasZ = int(z) < g.hi.z;
        const std::size_t sy = g.boxX, sz = std::size_t(g.boxX) * g.boxY;
        const T* p = g.box + index(plane);
        const PlaneBits lower = haveUpper ? upper : planeBits(p, sy, g.threshold, hasX, hasY);
        upper = hasZ ? planeBits(p + sz, sy, g.threshold, hasX, hasY) : PlaneBits{};
        haveUpper = hasZ;
        return voxelCode(lower, upper, hasX, hasY, hasZ);
    }
    __device__ void skip() { haveUpper = false; }
};

__device__ __forceinline__ std::uint32_t laneIndex() {
    return threadIdx.x & 31u;
}

// Pass 1 of the compaction: active voxels per tile (warp ballots, summed per tile).
template <typename T> __global__ void countTiles(Grid<T> g, std::uint32_t* tileCounts) {
    constexpr int kWarps = tuning::kClassifyBlock / 32;
    __shared__ std::uint32_t warpCounts[tuning::kClassifyPlanes][kWarps];
    TileWalk<T> walk(g);
    for (std::uint32_t plane = 0; plane < walk.planes; ++plane) {
        const unsigned ballot = __ballot_sync(0xffffffffu, walk.code(plane) != 0);
        if (laneIndex() == 0)
            warpCounts[plane][threadIdx.x / 32] = __popc(ballot);
    }
    __syncthreads();
    if (threadIdx.x < walk.planes) {
        std::uint32_t sum = 0;
        for (int w = 0; w < kWarps; ++w)
            sum += warpCounts[threadIdx.x][w];
        tileCounts[walk.tile(threadIdx.x)] = sum;
    }
}

// Pass 2: the tiles that hold active voxels write them at the scanned tile offset, in voxel
// order (a tile without any is skipped by the whole block: no voxel is read).
template <typename T>
__global__ void writeTiles(Grid<T> g, const std::uint32_t* tileOffsets, std::uint32_t* activeVoxels,
                           std::uint16_t* activeCodes) {
    constexpr int kWarps = tuning::kClassifyBlock / 32;
    // Two sets of warp counts, alternating between the tiles written: a set is written again
    // only after the __syncthreads of the tile between, when every thread has read it.
    __shared__ std::uint32_t warpCounts[2][kWarps];
    TileWalk<T> walk(g);
    std::uint32_t written = 0;
    for (std::uint32_t plane = 0; plane < walk.planes; ++plane) {
        const std::uint32_t tile = walk.tile(plane);
        const std::uint32_t first = tileOffsets[tile];
        if (tileOffsets[tile + 1] == first) {
            walk.skip();
            continue;
        }
        const std::uint32_t code = walk.code(plane);
        const unsigned ballot = __ballot_sync(0xffffffffu, code != 0);
        std::uint32_t* counts = warpCounts[written++ & 1u];
        const std::uint32_t warp = threadIdx.x / 32;
        if (laneIndex() == 0)
            counts[warp] = __popc(ballot);
        __syncthreads();
        if (code != 0) {
            std::uint32_t rank = __popc(ballot & ((1u << laneIndex()) - 1u));
            for (std::uint32_t w = 0; w < warp; ++w)
                rank += counts[w];
            activeVoxels[first + rank] = walk.index(plane);
            activeCodes[first + rank] = std::uint16_t(code);
        }
    }
}

// Vertices and triangles per active voxel; entry `count` is 0 so the exclusive scans end with the
// totals.
static __global__ void countGeometry(const std::uint16_t* codes, std::uint32_t count,
                                     std::uint32_t* vertexCounts, std::uint32_t* triangleCounts) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i > count)
        return;
    if (i == count) {
        vertexCounts[i] = 0;
        triangleCounts[i] = 0;
        return;
    }
    const std::uint32_t code = codes[i];
    vertexCounts[i] = __popc(code >> 8);
    triangleCounts[i] = c_triCount[code & 0xff];
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

// First position in [lo, hi) of `voxels` (ascending) holding a value >= key.
__device__ __forceinline__ std::uint32_t lowerBound(const std::uint32_t* voxels, std::uint32_t lo,
                                                    std::uint32_t hi, std::uint32_t key) {
    while (lo < hi) {
        const std::uint32_t mid = lo + (hi - lo) / 2;
        if (voxels[mid] < key)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

// rowStart[r] = first position in the ordered active list whose voxel lies in box row r
// (r = z * boxY + y) or later; entry rows = count. A triangle corner's owning voxel is then found
// within one row's few active voxels instead of the whole list.
static __global__ void findRowStarts(const std::uint32_t* activeVoxels, std::uint32_t count,
                                     std::uint32_t nx, std::uint32_t rows,
                                     std::uint32_t* rowStart) {
    const std::uint32_t r = blockIdx.x * blockDim.x + threadIdx.x;
    if (r > rows)
        return;
    rowStart[r] = r == rows ? count : lowerBound(activeVoxels, 0, count, r * nx);
}

static __global__ void
generateTriangles(const std::uint32_t* activeVoxels, const std::uint16_t* codes,
                  const std::uint32_t* vertexOffsets, const std::uint32_t* triangleOffsets,
                  const std::uint32_t* rowStart, std::uint32_t count, std::uint32_t nx,
                  std::uint32_t ny, std::uint32_t* indices) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count)
        return;
    const std::uint32_t cubeCase = codes[i] & 0xff;
    if (cubeCase == 0)
        return;
    const std::uint32_t v = activeVoxels[i];
    const std::uint32_t row = v / nx;
    std::uint32_t* out = indices + std::size_t(triangleOffsets[i]) * 3;
    const std::int8_t* table = c_triTable[cubeCase];
    for (int k = 0; table[k] >= 0; ++k) {
        const std::int8_t* owner = c_edgeOwner[table[k]];
        const std::uint32_t ownerVoxel =
            v + std::uint32_t(owner[0]) +
            (std::uint32_t(owner[1]) + std::uint32_t(owner[2]) * ny) * nx;
        // The owner is this voxel or a later one in this row or one of the next rows; it is
        // active (its edge crosses).
        std::uint32_t slot = i;
        if (ownerVoxel != v) {
            const std::uint32_t ownerRow =
                row + std::uint32_t(owner[1]) + std::uint32_t(owner[2]) * ny;
            const std::uint32_t lo = ownerRow == row ? i + 1 : rowStart[ownerRow];
            slot = lowerBound(activeVoxels, lo, rowStart[ownerRow + 1], ownerVoxel);
        }
        const std::uint32_t ownerEdges = codes[slot] >> 8;
        const int axis = owner[3];
        out[k] = vertexOffsets[slot] + __popc(ownerEdges & ((1u << axis) - 1u));
    }
}

} // namespace lw::kernels::cuda::mc
