#pragma once

// Kernels of the thick-slice field (thick_slice_field_cuda.h). Each repeats, per thread, what the
// CPU's loops do per plane, with kernels/slice_field_rules.h's expressions: equal minima of
// equal values, so the same int16 field.
// Internal: CUDA types allowed.

#include "lw/kernels/slice_field_rules.h"
#include "lw/kernels/thin_shell_bridge.h"

#include <cstdint>
#include <cuda_runtime.h>

namespace lw::kernels::cuda::field {

__device__ inline float noCrossing() {
    return __int_as_float(0x7f800000);
} // +infinity

struct SliceGrid {
    int width, height, slices;
    __device__ std::size_t at(int x, int y, int k) const {
        return (std::size_t(k) * std::size_t(height) + std::size_t(y)) * std::size_t(width) +
               std::size_t(x);
    }
};

// Per source voxel: its real value less the iso-value, as the CPU's aboveIso computes it.
template <typename T>
__global__ void aboveIsoKernel(const T* voxels, std::size_t count, double slope, double intercept,
                               double iso, float* above) {
    const std::size_t v = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x;
    if (v < count)
        above[v] = float(double(voxels[v]) * slope + intercept - iso);
}

// The crossing on the edge from `a` to `b` (offset from `origin`), or nothing.
__device__ inline bool crossingOn(float a, float b, int origin, float& at) {
    if (!crossesIso(a, b))
        return false;
    at = float(origin) + crossingOffset(a, b);
    return true;
}

// The distance between pixel coordinate `p` and a crossing at `at`, as the CPU's scans write it
// (p - before for a crossing before the pixel, after - p for one after it).
__device__ inline float pixelsTo(float p, float at) {
    return at <= p ? p - at : at - p;
}

// Per pixel: scaleI * (pixels to its row's nearest crossing)^2 and scaleJ * (pixels to its
// column's)^2, looking `reachI + 1` / `reachJ + 1` pixels either way.
__global__ void nearestKernel(const float* above, SliceGrid grid, int reachI, int reachJ,
                              float scaleI, float scaleJ, float* rowNear, float* columnNear) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    const int k = int(blockIdx.z);
    if (x >= grid.width || y >= grid.height)
        return;
    const float* slice = above + grid.at(0, 0, k);
    const std::size_t width = std::size_t(grid.width);
    float alongRow = noCrossing();
    const int firstEdgeI = max(0, x - reachI - 2);
    const int lastEdgeI = min(grid.width - 2, x + reachI + 1);
    for (int e = firstEdgeI; e <= lastEdgeI; ++e) {
        float at;
        if (crossingOn(slice[std::size_t(y) * width + e], slice[std::size_t(y) * width + e + 1], e,
                       at))
            alongRow = fminf(alongRow, pixelsTo(float(x), at));
    }
    float alongColumn = noCrossing();
    const int firstEdgeJ = max(0, y - reachJ - 2);
    const int lastEdgeJ = min(grid.height - 2, y + reachJ + 1);
    for (int e = firstEdgeJ; e <= lastEdgeJ; ++e) {
        float at;
        if (crossingOn(slice[std::size_t(e) * width + x], slice[std::size_t(e + 1) * width + x], e,
                       at))
            alongColumn = fminf(alongColumn, pixelsTo(float(y), at));
    }
    const std::size_t p = grid.at(x, y, k);
    rowNear[p] = nearTerm(scaleI, alongRow);
    columnNear[p] = nearTerm(scaleJ, alongColumn);
}

// Per pixel: the minimum over the rows and columns within reach, stored as the CPU stores it.
__global__ void distanceKernel(const float* above, const float* rowNear, const float* columnNear,
                               SliceGrid grid, int reachI, int reachJ, float scaleI, float scaleJ,
                               double limitMm, double stepsPerMm, std::int16_t* distance) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    const int k = int(blockIdx.z);
    if (x >= grid.width || y >= grid.height)
        return;
    float squared = noCrossing();
    for (int r = max(0, y - reachJ); r <= min(grid.height - 1, y + reachJ); ++r)
        squared = fminf(squared, rowNear[grid.at(x, r, k)] + stepTerm(scaleJ, r - y));
    for (int c = max(0, x - reachI); c <= min(grid.width - 1, x + reachI); ++c)
        squared = fminf(squared, columnNear[grid.at(c, y, k)] + stepTerm(scaleI, c - x));
    const std::size_t p = grid.at(x, y, k);
    distance[p] = storedSliceDistance(squared, above[p] >= 0.0f, limitMm, stepsPerMm);
}

// Where refined sample n of an axis refined `factor` times falls: the lower sample and the upper
// one's weight (oversampling.cpp's blendsAlong).
struct Blend {
    int lower;
    float upperWeight;
};
__device__ inline Blend blendAt(int n, int factor) {
    return {n / factor, float(n % factor) / float(factor)};
}

struct RefineGrid {
    int width, height, slices; // the source's
    int outWidth, outHeight;   // the refined ones (slices: the grid's z)
    int factorI, factorJ, factorK;
    bool monotoneK;
};

// The plane of refined slice `along` at source pixel (i, j): oversampling.cpp's blendPlane.
__device__ inline float planeValue(const std::int16_t* field, const RefineGrid& g, Blend along,
                                   int i, int j) {
    const std::size_t planeSize = std::size_t(g.width) * std::size_t(g.height);
    const std::size_t v = std::size_t(j) * std::size_t(g.width) + std::size_t(i);
    const std::int16_t* y1 = field + planeSize * std::size_t(along.lower);
    if (g.monotoneK && along.upperWeight > 0.0f) {
        const std::int16_t* y2 = y1 + planeSize;
        const std::int16_t* y0 = along.lower > 0 ? y1 - planeSize : y1;
        const std::int16_t* y3 = along.lower + 2 < g.slices ? y2 + planeSize : y2;
        const bool first = along.lower == 0;
        const bool last = along.lower + 2 >= g.slices;
        const HermiteWeights w(along.upperWeight);
        const float secant = float(y2[v]) - float(y1[v]);
        const float m1 = first ? secant : monotoneTangent(float(y1[v]) - float(y0[v]), secant);
        const float m2 = last ? secant : monotoneTangent(secant, float(y3[v]) - float(y2[v]));
        return hermiteBlend(w, float(y1[v]), m1, float(y2[v]), m2);
    }
    const std::int16_t* upper = along.upperWeight > 0.0f ? y1 + planeSize : y1;
    return linearBlend(float(y1[v]), along.upperWeight, float(upper[v]));
}

// The row of refined row `row` at source column i: oversampling.cpp's refineRow, first part.
__device__ inline float rowValue(const std::int16_t* field, const RefineGrid& g, Blend along,
                                 Blend row, int i) {
    const float lower = planeValue(field, g, along, i, row.lower);
    const float upper =
        row.upperWeight > 0.0f ? planeValue(field, g, along, i, row.lower + 1) : lower;
    return linearBlend(lower, row.upperWeight, upper);
}

// Per refined voxel: oversampling.cpp's refineSlices for int16.
__global__ void refineKernel(const std::int16_t* field, RefineGrid g, std::int16_t* refined) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    const int k = int(blockIdx.z);
    if (x >= g.outWidth || y >= g.outHeight)
        return;
    const Blend along = blendAt(k, g.factorK);
    float value;
    if (g.outWidth == g.width && g.outHeight == g.height) {
        value = planeValue(field, g, along, x, y);
    } else {
        const Blend row = blendAt(y, g.factorJ);
        const Blend column = blendAt(x, g.factorI);
        const float left = rowValue(field, g, along, row, column.lower);
        const float right =
            column.upperWeight > 0.0f ? rowValue(field, g, along, row, column.lower + 1) : left;
        value = linearBlend(left, column.upperWeight, right);
    }
    refined[(std::size_t(k) * std::size_t(g.outHeight) + std::size_t(y)) * std::size_t(g.outWidth) +
            std::size_t(x)] = std::int16_t(roundHalfAway(value));
}

// Per inner pixel of each gap (blockIdx.z): volume/slice_bridging.cpp's bridgeRow -- the slices
// between the gap's two raised to the thin wall slid from one to the other. The two slices are
// only read (no thread writes them), and each thread writes its own pixel of the slices between.
__global__ void bridgeKernel(std::int16_t* refined, ThinShellSlices pair, int factor) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    if (x < 1 || y < 1 || x + 1 >= pair.width || y + 1 >= pair.height)
        return;
    const std::size_t plane = std::size_t(pair.width) * std::size_t(pair.height);
    std::int16_t* lower = refined + plane * std::size_t(blockIdx.z) * std::size_t(factor);
    ThinShellSlices slices = pair;
    slices.lower = lower;
    slices.upper = lower + plane * std::size_t(factor);
    bridgeThinShellPixel(slices, lower + plane, plane, factor, x, y);
}

// Each face's largest value of the refined field (nx x ny x nz, x fastest); blockIdx.y is the
// face: x low, x high, y low, y high, z low, z high. The maxima are kept as value + 32768 in
// unsigned slots set to 0 before (no value is below -32768), for atomicMax.
__global__ void faceMaximaKernel(const std::int16_t* field, int nx, int ny, int nz,
                                 unsigned* maxima) {
    const int face = int(blockIdx.y), axis = face / 2;
    const bool high = (face % 2) != 0;
    // The face's two free axes, a the faster one in memory.
    const int extentA = axis == 0 ? ny : nx;
    const int extentB = axis == 2 ? ny : nz;
    const std::size_t count = std::size_t(extentA) * std::size_t(extentB);
    int best = -32768;
    for (std::size_t v = std::size_t(blockIdx.x) * blockDim.x + threadIdx.x; v < count;
         v += std::size_t(gridDim.x) * blockDim.x) {
        const int a = int(v % std::size_t(extentA)), b = int(v / std::size_t(extentA));
        const int fixed = high ? (axis == 0 ? nx : (axis == 1 ? ny : nz)) - 1 : 0;
        const int x = axis == 0 ? fixed : a;
        const int y = axis == 0 ? a : (axis == 1 ? fixed : b);
        const int z = axis == 2 ? fixed : b;
        const std::size_t at =
            (std::size_t(z) * std::size_t(ny) + std::size_t(y)) * std::size_t(nx) + std::size_t(x);
        best = max(best, int(field[at]));
    }
    for (int offset = 16; offset > 0; offset /= 2)
        best = max(best, __shfl_down_sync(0xffffffffu, best, offset));
    if ((threadIdx.x & 31u) == 0)
        atomicMax(&maxima[face], unsigned(best + 32768));
}

} // namespace lw::kernels::cuda::field
