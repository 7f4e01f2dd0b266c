#pragma once

// Method 2's kernels (dispatch in raycast_silhouette_cuda.cu): everything per cell and per ray is
// kernels/common's (marching_cubes.h, voxel_grid.h, silhouette_segment.h, voxel_ray_walk.h,
// pixel_camera.h), the same functions the CPU back-end calls.

#include "lw/kernels/pixel_camera.h"
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

// Per macro cell of RayVisibilityRule::kMacroCells^3 cells: does any of its corner voxels lie
// inside (float(value) >= isoF, as the CPU engine tests)?
template <typename T>
__global__ void macroOccupancy(const T* voxels, GridDims dims, glm::ivec3 macroDims, float isoF,
                               std::uint8_t* occupied) {
    const std::uint32_t m = blockIdx.x * blockDim.x + threadIdx.x;
    const std::uint32_t total = std::uint32_t(macroDims.x) * macroDims.y * macroDims.z;
    if (m >= total)
        return;
    const int n = RayVisibilityRule::kMacroCells;
    const int mx = int(m % macroDims.x), my = int((m / macroDims.x) % macroDims.y),
              mz = int(m / (std::uint32_t(macroDims.x) * macroDims.y));
    const int x0 = mx * n, y0 = my * n, z0 = mz * n;
    const int x1 = min(x0 + n, dims.cx), y1 = min(y0 + n, dims.cy), z1 = min(z0 + n, dims.cz);
    std::uint8_t any = 0;
    for (int z = z0; z <= z1 && !any; ++z)
        for (int y = y0; y <= y1 && !any; ++y) {
            const T* row = voxels + std::size_t(y) * dims.sy + std::size_t(z) * dims.sz;
            for (int x = x0; x <= x1; ++x)
                any |= float(row[x]) >= isoF;
        }
    occupied[m] = any;
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

// Phase 2: one thread per segment endpoint (rays packed densely in warps, whatever cell they
// came from): 1 when the endpoint is visible.
template <typename T>
__global__ void testEndpoints(RayVisibility<T> rule, View view, const SegmentEndpoints* segments,
                              std::uint32_t count, std::uint8_t* visible) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= 2 * count)
        return;
    const SegmentEndpoints& segment = segments[i / 2];
    const glm::dvec3 p(i % 2 == 0 ? segment.a : segment.b);
    visible[i] = rule.visible(p, view.eyeOrDirection, view.orthographic) ? 1 : 0;
}

// Phase 3: rasterizeLine's pixels of every segment drawn (all, or those with both endpoints
// visible).
__global__ void drawSegments(View view, const SegmentEndpoints* segments, std::uint32_t count,
                             const std::uint8_t* visible, std::uint8_t* mask) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    if (i >= count || (visible && !(visible[2 * i] && visible[2 * i + 1])))
        return;
    const int width = view.camera.width;
    forEachLinePixel(pixelOf(view.camera, segments[i].a), pixelOf(view.camera, segments[i].b),
                     width, view.camera.height,
                     [&](int x, int y) { mask[std::size_t(y) * std::size_t(width) + x] = 1; });
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

// Phase 1: one thread per active cell builds its vertices and appends the Burns segment of each
// of its triangles to `segments` (slots past `capacity` are only counted: the caller grows the
// buffer and runs again). The counters are shared by every thread: each warp adds its sums with
// one atomic (one atomic per cell on one address serialised the kernel: 2 ms at 512^3), and the
// warp's segments go to consecutive slots, lane by lane.
template <typename T>
__global__ void findSegments(mc::Grid<T> g, const std::uint32_t* activeVoxels,
                             const std::uint16_t* codes, std::uint32_t count, View view,
                             SegmentEndpoints* segments, std::uint32_t* segmentCells,
                             std::uint32_t capacity, Counters* counters) {
    const std::uint32_t i = blockIdx.x * blockDim.x + threadIdx.x;
    CellSegments cell;
    std::uint32_t v = 0;
    if (i < count && (codes[i] & 0xff) != 0) { // every lane stays for the warp's sums below
        v = activeVoxels[i];
        cellSegments(g, v, view, cell);
    }
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

} // namespace lw::kernels::cuda::rc
