#pragma once

// Method 2's kernels (dispatch in raycast_silhouette_cuda.cu): everything per cell and per ray is
// kernels/common's (marching_cubes.h, voxel_grid.h, silhouette_segment.h, voxel_ray_walk.h,
// pixel_camera.h), the same functions the CPU back-end calls.

#include "lw/kernels/pixel_camera.h"
#include "lw/kernels/point_hash.h"
#include "lw/kernels/silhouette_segment.h"
#include "lw/kernels/voxel_ray_walk.h"
#include "marching_cubes_kernels.cuh"

namespace lw::kernels::cuda::rc {

using mc::c_cornerOffset;
using mc::c_edgeCorners;
using mc::c_edgeOwner;
using mc::c_edgeTable;
using mc::c_triCount;
using mc::c_triTable;

// Per macro cell of RayVisibilityRule::kMacroCells^3 cells: the largest of its corner voxels
// (as float, the CPU engine's comparison type), once per volume. Whether a macro cell holds an
// inside voxel (float(value) >= isoF) is then `maximum >= isoF` for any iso-value, without a
// pass over the voxels: on a volume mapped from host memory that pass crossed PCIe at every new
// iso-value (105 ms at 1024x1024x2048 on the H200). fmaxf skips NaN, as `>=` does.
template <typename T>
__global__ void macroMaximum(const T* voxels, GridDims dims, glm::ivec3 macroDims, float* maxima) {
    const std::uint32_t m = blockIdx.x * blockDim.x + threadIdx.x;
    const std::uint32_t total = std::uint32_t(macroDims.x) * macroDims.y * macroDims.z;
    if (m >= total)
        return;
    const int n = RayVisibilityRule::kMacroCells;
    const int mx = int(m % macroDims.x), my = int((m / macroDims.x) % macroDims.y),
              mz = int(m / (std::uint32_t(macroDims.x) * macroDims.y));
    const int x0 = mx * n, y0 = my * n, z0 = mz * n;
    const int x1 = min(x0 + n, dims.cx), y1 = min(y0 + n, dims.cy), z1 = min(z0 + n, dims.cz);
    float largest = -HUGE_VALF;
    for (int z = z0; z <= z1; ++z)
        for (int y = y0; y <= y1; ++y) {
            const T* row = voxels + std::size_t(y) * dims.sy + std::size_t(z) * dims.sz;
            for (int x = x0; x <= x1; ++x)
                largest = fmaxf(largest, float(row[x]));
        }
    maxima[m] = largest;
}

// Per macro cell at one iso-value: does it hold an inside voxel?
__global__ void macroOccupancy(const float* maxima, std::uint32_t count, float isoF,
                               std::uint8_t* occupied) {
    const std::uint32_t m = blockIdx.x * blockDim.x + threadIdx.x;
    if (m < count)
        occupied[m] = maxima[m] >= isoF ? 1 : 0;
}

// Per coarse block: does any of its macro cells hold an inside voxel (kernels/common's rule)?
__global__ void coarseOccupancyOf(const std::uint8_t* macroOccupied, glm::ivec3 macroDims,
                                  glm::ivec3 coarseDims, std::uint8_t* coarseOccupied) {
    const std::uint32_t c = blockIdx.x * blockDim.x + threadIdx.x;
    const std::uint32_t total = std::uint32_t(coarseDims.x) * coarseDims.y * coarseDims.z;
    if (c >= total)
        return;
    const glm::ivec3 coarse(int(c % coarseDims.x), int((c / coarseDims.x) % coarseDims.y),
                            int(c / (std::uint32_t(coarseDims.x) * coarseDims.y)));
    coarseOccupied[c] = coarseOccupancy(macroOccupied, macroDims, coarse);
}

struct Counters {
    unsigned long long triangles;
    unsigned long long segments;
};

struct View {
    PixelCamera camera;
    glm::dvec3 eyeOrDirection;
    glm::vec3 eyeOrDirectionF;
    bool orthographic;
    bool visibility;
    bool alongSegment;
    double pixelSpan; // rayPixelSpan(): the neighbour ray's pixel
};

__device__ __forceinline__ glm::dvec2 pixelOf(const PixelCamera& camera, glm::vec3 p) {
    // The CPU renderer keeps pixel positions as float vec2 before drawing.
    return glm::dvec2(glm::vec2(projectPixel(camera, glm::dvec3(p))));
}

// Endpoints are numbered 2 * segment (a) and 2 * segment + 1 (b).
__device__ __forceinline__ glm::vec3 endpointOf(const SegmentEndpoints* segments, std::uint32_t e) {
    const SegmentEndpoints& segment = segments[e >> 1];
    return (e & 1u) ? segment.b : segment.a;
}

// Phase 2a: each endpoint's representative, the first of the endpoints at the same point (bit
// for bit) to claim a slot of an open-addressing table: neighbouring segments meet at shared
// endpoints (silhouetteSegment computes a shared edge's crossing alike from both triangles),
// so about every point is an endpoint twice, and its visibility ray is cast once. A slot holds
// the upper half of the point's hash and the representative; equal halves at different points
// are told apart by comparing the points, so the table never merges two of them.
inline constexpr unsigned long long kEmptySlot = ~0ull;

__device__ __forceinline__ unsigned long long endpointHash(glm::vec3 p) {
    return pointBitsHash(__float_as_uint(p.x), __float_as_uint(p.y), __float_as_uint(p.z));
}

__device__ __forceinline__ bool samePoint(glm::vec3 a, glm::vec3 b) {
    return __float_as_uint(a.x) == __float_as_uint(b.x) &&
           __float_as_uint(a.y) == __float_as_uint(b.y) &&
           __float_as_uint(a.z) == __float_as_uint(b.z);
}

__global__ void findRepresentatives(const SegmentEndpoints* segments, std::uint32_t endpoints,
                                    unsigned long long* table, std::uint32_t tableMask,
                                    std::uint32_t* representative, std::uint8_t* isRepresentative) {
    const std::uint32_t e = blockIdx.x * blockDim.x + threadIdx.x;
    if (e >= endpoints)
        return;
    const glm::vec3 p = endpointOf(segments, e);
    const unsigned long long hash = endpointHash(p);
    const unsigned long long mine = (hash & 0xffffffff00000000ull) | e;
    std::uint32_t slot = std::uint32_t(hash) & tableMask;
    std::uint32_t found = e;
    for (;;) {
        unsigned long long entry = table[slot];
        if (entry == kEmptySlot)
            entry = atomicCAS(table + slot, kEmptySlot, mine);
        if (entry == kEmptySlot)
            break; // claimed: this endpoint represents the point
        const std::uint32_t other = std::uint32_t(entry);
        if ((entry >> 32) == (mine >> 32) && samePoint(endpointOf(segments, other), p)) {
            found = other;
            break;
        }
        slot = (slot + 1) & tableMask;
    }
    representative[e] = found;
    isRepresentative[e] = found == e ? 1 : 0;
}

// Phase 2b: the representatives' visibility (1 visible, 0 hidden), each point's own ray and,
// where that was blocked close by, the ray from one pixel beside it (RayVisibility::visible).
// Rays differ in length by orders of magnitude (a jump through empty space against a walk along
// the surface), so a thread per ray left most lanes of a warp idle behind its longest ray (20 %
// of the lanes active, Nsight Compute). Here the lanes stay busy: a launch of about as many
// threads as are resident walks every ray in steps (a macro cell each, RayVisibility::advanceRay),
// and a lane whose ray has ended takes the next from `nextRay`, a warp's idle lanes in one atomic.
// The rays are taken in the representatives' order (endpoint order), so neighbouring points
// still start in one warp. Each ray's result is the one-go walk's, bit for bit.
template <typename T> struct LaneRay {
    using Rule = RayVisibility<T>;
    enum Phase : unsigned char { Idle, OwnRay, NeighbourRay };
    Phase phase = Idle;
    std::uint32_t endpoint = 0;
    glm::dvec3 point{0.0};
    typename Rule::RayWalk walk;

    // Records the ray's end, or starts the neighbour ray after a blocked own ray.
    __device__ void settle(const Rule& rule, const View& view, typename Rule::RayStep step,
                           double blockedCells, std::uint8_t* visible) {
        using Step = typename Rule::RayStep;
        while (step != Step::Walking) {
            if (step == Step::Blocked && phase == OwnRay && rule.asksNeighbour(blockedCells)) {
                glm::dvec3 start;
                if (rule.neighbourRayStart(point, view.eyeOrDirection, view.orthographic, start)) {
                    phase = NeighbourRay;
                    step = rule.beginRay(start, view.eyeOrDirection, view.orthographic, false, walk,
                                         nullptr);
                    continue;
                }
            }
            visible[endpoint] = step == Step::ReachesEye ? 1 : 0;
            phase = Idle;
            return;
        }
    }
};

template <typename T>
__global__ void
testRepresentatives(RayVisibility<T> rule, View view, const SegmentEndpoints* segments,
                    const std::uint32_t* representatives, const std::uint32_t* count,
                    std::uint32_t* nextRay, bool takeMore, std::uint8_t* visible) {
    const std::uint32_t total = *count;
    const unsigned lane = threadIdx.x & 31u;
    LaneRay<T> ray;
    bool exhausted = false;
    auto start = [&](std::uint32_t i) {
        if (i >= total) {
            exhausted = true;
            return;
        }
        ray.endpoint = representatives[i];
        ray.point = glm::dvec3(endpointOf(segments, ray.endpoint));
        ray.phase = LaneRay<T>::OwnRay;
        double blocked = 0.0;
        const auto step = rule.beginRay(ray.point, view.eyeOrDirection, view.orthographic, true,
                                        ray.walk, &blocked);
        ray.settle(rule, view, step, blocked, visible);
    };
    if (!takeMore) { // one ray per thread (see the dispatch: a volume in host memory)
        start(blockIdx.x * blockDim.x + threadIdx.x);
        exhausted = true;
    }
    for (;;) {
        const bool wants = ray.phase == LaneRay<T>::Idle && !exhausted;
        const unsigned takers = __ballot_sync(0xffffffffu, wants);
        if (takers != 0) {
            const int leader = __ffs(takers) - 1;
            std::uint32_t base = 0;
            if (int(lane) == leader)
                base = atomicAdd(nextRay, std::uint32_t(__popc(takers)));
            base = __shfl_sync(0xffffffffu, base, leader);
            if (wants)
                start(base + __popc(takers & ((1u << lane) - 1u)));
        }
        if (__all_sync(0xffffffffu, exhausted && ray.phase == LaneRay<T>::Idle))
            return;
        if (ray.phase != LaneRay<T>::Idle) {
            double blocked = 0.0;
            const auto step = rule.advanceRay(ray.walk, &blocked);
            ray.settle(rule, view, step, blocked, visible);
        }
    }
}

// Phase 3: rasterizeLine's pixels of every segment drawn (all, or the part that its endpoints'
// visibility gives, drawnSpanOfSegment: each endpoint's flag is its representative's).
__global__ void drawSegments(View view, const SegmentEndpoints* segments, std::uint32_t count,
                             const std::uint8_t* visible, const std::uint32_t* representative,
                             std::uint8_t* mask) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count)
        return;
    SegmentSpan span;
    if (visible && !drawnSpanOfSegment(visible[representative[2 * i]] != 0,
                                       visible[representative[2 * i + 1]] != 0, span))
        return;
    const int width = view.camera.width;
    forEachLinePixel(
        pixelOf(view.camera, segments[i].a), pixelOf(view.camera, segments[i].b), width,
        view.camera.height,
        [&](int x, int y) { mask[std::size_t(y) * std::size_t(width) + x] = 1; }, span);
}

// The along-segment rule instead of phases 2 and 3: one thread per segment tests every pixel step
// of it (the CPU renderer's arithmetic) and sets the visible steps' pixels.
template <typename T>
__global__ void drawAlongSegments(RayVisibility<T> rule, View view,
                                  const SegmentEndpoints* segments, std::uint32_t count,
                                  std::uint8_t* mask) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count)
        return;
    const SegmentEndpoints segment = segments[i];
    const int width = view.camera.width, height = view.camera.height;
    const glm::dvec3 a(segment.a), b(segment.b);
    const glm::dvec2 pa = pixelOf(view.camera, segment.a), pb = pixelOf(view.camera, segment.b);
    const glm::dvec2 delta = pb - pa;
    const double adx = fabs(delta.x), ady = fabs(delta.y);
    const double steps = ceil(adx > ady ? adx : ady);
    if (!(steps < double(1 << 20)))
        return; // a segment projected absurdly far off screen
    const int stepCount = int(steps);
    for (int step = 0; step <= stepCount; ++step) {
        const double t = stepCount == 0 ? 0.0 : double(step) / double(stepCount);
        if (rule.visible(a + t * (b - a), view.eyeOrDirection, view.orthographic)) {
            const glm::dvec2 q = pa + t * delta;
            const int x = int(floor(q.x)), y = int(floor(q.y));
            if (x >= 0 && y >= 0 && x < width && y < height)
                mask[std::size_t(y) * std::size_t(width) + x] = 1;
        }
    }
}

// The Burns segments of one active cell (at most one per triangle, so at most 5), and its
// triangle count; nothing for a cell without triangles.
struct CellSegments {
    SegmentEndpoints segment[5];
    std::uint32_t segments = 0;
    std::uint32_t triangles = 0;
};

template <typename T>
__device__ void cellSegments(const mc::Grid<T>& g, std::uint32_t v, const View& view,
                             CellSegments& out) {
    // S only: the box is the whole volume (origin 0).
    const int x = int(v % g.boxX), y = int((v / g.boxX) % g.boxY), z = int(v / (g.boxX * g.boxY));
    const std::size_t sy = g.boxX, sz = std::size_t(g.boxX) * g.boxY;
    float value[8];
    for (int c = 0; c < 8; ++c)
        value[c] = float(
            g.box[v + std::size_t(c_cornerOffset[c][0]) + std::size_t(c_cornerOffset[c][1]) * sy +
                  std::size_t(c_cornerOffset[c][2]) * sz]);
    const int cubeCase = mcCaseIndex(value, g.isoF);
    out.triangles = c_triCount[cubeCase];
    if (out.triangles == 0)
        return;
    const unsigned edges = c_edgeTable[cubeCase];
    const VoxelGradientSampler<T> sampler{g.box, g.spans, g.indexOrigin};
    McVec3 gradient[8];
    unsigned haveGradient = 0;
    glm::vec3 position[12], normal[12];
    float distance[12];
    for (int e = 0; e < 12; ++e) {
        if (!(edges & (1u << e)))
            continue;
        const int c0 = c_edgeCorners[e][0], c1 = c_edgeCorners[e][1];
        for (const int c : {c0, c1})
            if (!(haveGradient & (1u << c))) {
                gradient[c] = sampler.gradient(x + c_cornerOffset[c][0], y + c_cornerOffset[c][1],
                                               z + c_cornerOffset[c][2]);
                haveGradient |= 1u << c;
            }
        const std::int8_t* owner = c_edgeOwner[e];
        const McVertex vertex =
            mcEdgeVertex(g.frame, x + owner[0], y + owner[1], z + owner[2], owner[3], value[c0],
                         value[c1], gradient[c0], gradient[c1], g.iso, g.isoF);
        position[e] = glm::vec3(vertex.position.x, vertex.position.y, vertex.position.z);
        normal[e] = glm::vec3(vertex.normal.x, vertex.normal.y, vertex.normal.z);
        distance[e] =
            silhouetteDistance(position[e], normal[e], view.eyeOrDirectionF, view.orthographic);
    }
    const std::int8_t* row = c_triTable[cubeCase];
    for (int k = 0; row[k] >= 0; k += 3) {
        const glm::vec3 q[3] = {position[row[k]], position[row[k + 1]], position[row[k + 2]]};
        const float d[3] = {distance[row[k]], distance[row[k + 1]], distance[row[k + 2]]};
        if (silhouetteSegment(q, d, out.segment[out.segments]))
            ++out.segments;
    }
}

// Appends one cell's segments (every lane of the warp calls it, cells without segments too). The
// counters are shared by every thread: each warp adds its sums with one atomic (one atomic per
// cell on one address serialised the kernel: 2 ms at 512^3), and the warp's segments go to
// consecutive slots, lane by lane; slots past `capacity` are only counted (the caller grows the
// buffer and runs again).
__device__ __forceinline__ void appendCellSegments(const CellSegments& cell, std::uint32_t v,
                                                   SegmentEndpoints* segments,
                                                   std::uint32_t* segmentCells,
                                                   std::uint32_t capacity, Counters* counters) {
    constexpr unsigned kWarp = 0xffffffffu;
    const unsigned lane = threadIdx.x & 31u;
    const unsigned triangles = __reduce_add_sync(kWarp, cell.triangles);
    if (lane == 0 && triangles > 0)
        atomicAdd(&counters->triangles, (unsigned long long)triangles);
    unsigned before = cell.segments; // inclusive prefix sum over the lanes
    for (unsigned offset = 1; offset < 32; offset <<= 1) {
        const unsigned below = __shfl_up_sync(kWarp, before, offset);
        if (lane >= offset)
            before += below;
    }
    const unsigned warpTotal = __shfl_sync(kWarp, before, 31);
    unsigned long long base = 0;
    if (lane == 31 && warpTotal > 0)
        base = atomicAdd(&counters->segments, (unsigned long long)warpTotal);
    base = __shfl_sync(kWarp, base, 31);
    const unsigned long long first = base + before - cell.segments;
    for (std::uint32_t k = 0; k < cell.segments; ++k)
        if (first + k < capacity) {
            segments[first + k] = cell.segment[k];
            segmentCells[first + k] = v; // the sort key that brings neighbouring rays together
        }
}

// Phase 1 from the voxels: one thread per active cell builds its vertices and appends the Burns
// segment of each of its triangles.
template <typename T>
__global__ void findSegments(mc::Grid<T> g, const std::uint32_t* activeVoxels,
                             const std::uint16_t* codes, std::uint32_t count, View view,
                             SegmentEndpoints* segments, std::uint32_t* segmentCells,
                             std::uint32_t capacity, Counters* counters) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    CellSegments cell;
    std::uint32_t v = 0;
    if (i < count && (codes[i] & 0xff) != 0) { // every lane stays for the warp's sums
        v = activeVoxels[i];
        cellSegments(g, v, view, cell);
    }
    appendCellSegments(cell, v, segments, segmentCells, capacity, counters);
}

// Phase 1 on the kept mesh, first step: each vertex's silhouette distance, once per view. A
// vertex is shared by about six triangles; reading its position and normal for each of them
// was most of phase 1 (0.20 ms at 512^3 on the H200). The same function of the same floats as
// cellSegments' (no fused multiply-adds in this back-end), so the same values.
__global__ void vertexSilhouetteDistances(DeviceMeshView mesh, View view, float* distance) {
    const std::size_t i = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
    if (i < mesh.vertexCount)
        distance[i] = silhouetteDistance(mesh.positions[i], mesh.normals[i], view.eyeOrDirectionF,
                                         view.orthographic);
}

// The Burns segment of the mesh triangle `corner[0..2]` from its vertices' distances
// (vertexSilhouetteDistances): silhouetteSegment's result, reading the positions only where the
// distances change sign (about one triangle in twelve at 512^3).
__device__ __forceinline__ bool distanceTriangleSegment(const DeviceMeshView& mesh,
                                                        const std::uint32_t* corner,
                                                        const float* distance,
                                                        SegmentEndpoints& segment) {
    const std::uint32_t k[3] = {corner[0], corner[1], corner[2]};
    const float d[3] = {distance[k[0]], distance[k[1]], distance[k[2]]};
    const bool s0 = d[0] >= 0.0f;
    if (s0 == (d[1] >= 0.0f) && s0 == (d[2] >= 0.0f))
        return false; // isolineCrossing's test: no segment
    const glm::vec3 q[3] = {mesh.positions[k[0]], mesh.positions[k[1]], mesh.positions[k[2]]};
    return silhouetteSegment(q, d, segment);
}

// Phase 1 from a kept mesh (marching cubes of the same iso-value, on the device): one thread per
// triangle, its Burns segment keyed by the triangle's number (`firstTriangle` is the mesh's
// first over all slabs). The whole volume's mesh has the vertices the cells would compute
// (generateVertices and cellSegments call the shared edge-vertex function on the same corners),
// its triangles in cell order and in triTable's order within a cell, so the segments sorted by
// triangle are findSegments' sorted by cell -- without reading a voxel: a volume mapped from host
// memory is not read over the bus at every view. `distance`: the vertices' distances for this
// view (vertexSilhouetteDistances).
// A block reserves its segments' slots with one atomic, and counts its triangles with another:
// per warp, the atomics on the two counters cost more than the triangles' own work.
template <int kBlock>
__global__ void __launch_bounds__(kBlock)
    findTriangleSegments(DeviceMeshView mesh, std::uint32_t firstTriangle, const float* distance,
                         SegmentEndpoints* segments, std::uint32_t* segmentCells,
                         std::uint32_t capacity, Counters* counters) {
    static_assert(kBlock % 32 == 0 && kBlock <= 1024);
    __shared__ std::uint32_t warpFirst[kBlock / 32];
    __shared__ unsigned long long blockFirst;
    const std::uint32_t t = blockIdx.x * kBlock + threadIdx.x;
    SegmentEndpoints segment;
    bool found = false;
    if (t < mesh.triangleCount)
        found = distanceTriangleSegment(mesh, mesh.indices + std::size_t(t) * 3, distance, segment);
    const unsigned lane = threadIdx.x & 31u, warp = threadIdx.x >> 5;
    const unsigned finders = __ballot_sync(0xffffffffu, found);
    if (lane == 0)
        warpFirst[warp] = __popc(finders);
    __syncthreads();
    if (threadIdx.x == 0) {
        std::uint32_t total = 0;
        for (int w = 0; w < kBlock / 32; ++w) {
            const std::uint32_t count = warpFirst[w];
            warpFirst[w] = total;
            total += count;
        }
        const std::size_t first = std::size_t(blockIdx.x) * kBlock;
        const std::size_t left = first < mesh.triangleCount ? mesh.triangleCount - first : 0;
        const std::size_t triangles = left < std::size_t(kBlock) ? left : std::size_t(kBlock);
        atomicAdd(&counters->triangles, (unsigned long long)triangles);
        blockFirst = total > 0 ? atomicAdd(&counters->segments, (unsigned long long)total) : 0;
    }
    __syncthreads();
    if (!found)
        return;
    const unsigned long long slot =
        blockFirst + warpFirst[warp] + __popc(finders & ((1u << lane) - 1u));
    if (slot < capacity) {
        segments[slot] = segment;
        segmentCells[slot] =
            firstTriangle + t; // the sort key that brings neighbouring rays together
    }
}

} // namespace lw::kernels::cuda::rc
