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

// A source voxel's real value less the iso-value (the CPU's aboveIso): computed where it is read
// rather than stored, the same float from the same double expression.
struct AboveIso {
    double slope, intercept, iso;
    template <typename T> __device__ float operator()(T voxel) const {
        return float(double(voxel) * slope + intercept - iso);
    }
};

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

// Why a pixel's nearest crossing along a row needs only two candidates: the crossing on edge e
// (between pixels e and e + 1) lies at e + t, 0 <= t <= 1 (in floats too: the offset is a quotient
// of a value by a larger one of the same sign), so crossings are ordered as their edges are. For
// pixel p the crossings on edges e <= p - 1 lie at or before p, the nearest of them on the last
// such edge; those on edges e >= p lie at or after p, the nearest on the first. The minimum of the
// two is the minimum over all of them, the same float. (Crossings further than the limit's reach
// give terms beyond the limit, which the stored distance clamps whichever way they are found.)
//
// nearTermsKernel: one block is 32 columns (a warp's lanes) by tuning::kNearRowsPerWarp rows a
// warp. Along each row the warp finds the crossings of 2 * chunks + 1 runs of 32 edges around its
// columns (one edge a lane, a ballot a run) and each lane takes the last crossing before it and
// the first after it from the ballots' bits. Down each column a lane walks the edges in order from
// the limit's reach above its rows to the limit's reach below, once down (the last crossing
// before each row) and once up (the first after). Per pixel: scaleI * (pixels to its row's
// nearest crossing)^2 and scaleJ * (pixels to its column's)^2, as the CPU's scans find them.
// Dynamic shared memory: per warp, nearTermsSharedFloats(chunks) floats.
__host__ __device__ inline int nearTermsSharedFloats(int chunks) {
    return (2 * chunks + 1) * 33; // each run: 32 crossings and its ballot
}

template <int kRows, typename T>
__global__ void nearTermsKernel(const T* voxels, AboveIso above, SliceGrid grid, int chunks,
                                int reachJ, float scaleI, float scaleJ, float* rowNear,
                                float* columnNear) {
    extern __shared__ float shared[];
    const int runs = 2 * chunks + 1;
    float* crossingAt = shared + threadIdx.y * nearTermsSharedFloats(chunks);
    unsigned* ballots = reinterpret_cast<unsigned*>(crossingAt + runs * 32);
    const int lane = int(threadIdx.x);
    const int x0 = int(blockIdx.x) * 32, x = x0 + lane;
    const int firstRow = (int(blockIdx.y) * int(blockDim.y) + int(threadIdx.y)) * kRows;
    const int k = int(blockIdx.z);
    const T* slice = voxels + grid.at(0, 0, k);
    const std::size_t width = std::size_t(grid.width);
    const unsigned before = (1u << lane) - 1u; // this lane's lower bits

    for (int s = 0; s < kRows; ++s) { // along the rows (warp-uniform)
        const int y = firstRow + s;
        if (y >= grid.height)
            break;
        const T* row = slice + std::size_t(y) * width;
        for (int run = 0; run < runs; ++run) {
            const int e = x0 + (run - chunks) * 32 + lane;
            float at = 0.0f;
            const bool crossing =
                e >= 0 && e + 1 < grid.width && crossingOn(above(row[e]), above(row[e + 1]), e, at);
            const unsigned bits = __ballot_sync(0xffffffffu, crossing);
            crossingAt[run * 32 + lane] = at;
            if (lane == 0)
                ballots[run] = bits;
        }
        __syncwarp();
        if (x < grid.width) {
            float along = noCrossing();
            int run = chunks; // edges e <= x - 1: this run's bits below the lane, then runs before
            unsigned bits = ballots[run] & before;
            while (bits == 0u && run > 0)
                bits = ballots[--run];
            if (bits != 0u)
                along = fminf(along, pixelsTo(float(x), crossingAt[run * 32 + 31 - __clz(bits)]));
            run = chunks; // edges e >= x: this run's bits from the lane on, then runs after
            bits = ballots[run] & ~before;
            while (bits == 0u && run + 1 < runs)
                bits = ballots[++run];
            if (bits != 0u)
                along = fminf(along, pixelsTo(float(x), crossingAt[run * 32 + __ffs(bits) - 1]));
            rowNear[grid.at(x, y, k)] = nearTerm(scaleI, along);
        }
        __syncwarp();
    }

    if (x >= grid.width || firstRow >= grid.height)
        return;
    const T* column = slice + x;
    const auto crossingBelow = [&](int e, float& at) { // the edge from row e to row e + 1
        return e >= 0 && e + 1 < grid.height &&
               crossingOn(above(column[std::size_t(e) * width]),
                          above(column[std::size_t(e + 1) * width]), e, at);
    };
    float lastAbove = noCrossing(); // the last crossing on edges e <= y - 1 (+inf: none)
    for (int e = firstRow - reachJ - 2; e < firstRow - 1; ++e)
        crossingBelow(e, lastAbove);
    float fromAbove[kRows];
#pragma unroll
    for (int s = 0; s < kRows; ++s) {
        crossingBelow(firstRow + s - 1, lastAbove);
        fromAbove[s] = lastAbove;
    }
    const int lastRow = firstRow + kRows - 1;
    float firstBelow = noCrossing(); // the first crossing on edges e >= y
    for (int e = lastRow + reachJ + 1; e > lastRow; --e)
        crossingBelow(e, firstBelow);
#pragma unroll
    for (int s = kRows - 1; s >= 0; --s) {
        const int y = firstRow + s;
        crossingBelow(y, firstBelow);
        if (y < grid.height)
            columnNear[grid.at(x, y, k)] = nearTerm(
                scaleJ, fminf(pixelsTo(float(y), fromAbove[s]), pixelsTo(float(y), firstBelow)));
    }
}

// The distance of a slice's 32 x 32 tile of pixels in one block (blockIdx.z the slice), all of
// it in shared memory:
//
//         x0 - reachI - 2                 values: the source's pixels less the iso-value over the
//   y0 - reachJ - 2 +------------------+  tile and as far around as a crossing within the limit
//                   |     . rows .     |  can lie (reach + 2 pixels: the CPU's windows);
//                   |  ...+------+...  |  rows: the row terms of the tile's 32 columns, from
//                   | cols| tile |cols |  reachJ rows above the tile to reachJ below;
//                   |  ...+------+...  |  cols: the column terms of the tile's 32 rows, from
//                   |     . rows .     |  reachI columns left of it to reachI right.
//                   +------------------+
//
// 1. values: read once (a tile whose values hold no crossing is at the limit everywhere: the
//    rest is skipped);
// 2. row and column terms: a thread walks a run of 8 pixels' edges, once towards them (the last
//    crossing before each) and once back (the first after); the two candidates hold the minimum
//    (nearTermsKernel says why);
// 3. per pixel the minimum over the rows and columns within reach, outwards from the pixel and
//    only while the step's own term is below the minimum so far (each later candidate is at least
//    its step's term: terms are >= 0 and a float sum of them is >= either), starting from the
//    smallest square that reaches the limit (anything at least that is stored as the limit,
//    storedSliceDistance's of it).
// Equal minima of equal floats: the same int16 as the CPU's.
struct DistanceTile {
    int reachI, reachJ;
    __host__ __device__ int valueWidth() const { return 32 + 2 * reachI + 4; }
    __host__ __device__ int valueHeight() const { return 32 + 2 * reachJ + 4; }
    __host__ __device__ int rowSpan() const { return 32 + 2 * reachJ; }
    __host__ __device__ int columnSpan() const { return 32 + 2 * reachI; }
    // values; row terms; column terms
    __host__ __device__ int floats() const {
        return valueWidth() * valueHeight() + rowSpan() * 32 + 32 * columnSpan();
    }
};

struct DistanceSetup {
    float scaleI, scaleJ;
    float reaching; // squaredReachingLimit
    double limitMm, stepsPerMm;
    std::int16_t insideLimit, outsideLimit; // what storedSliceDistance stores from `reaching` on
};

// A run of kRun pixels' nearest crossings along one line: pixel j of the run at line coordinate
// `first + j`; `value(p)` the value at line coordinate p, for p from first - reach - 2 to
// first + kRun + reach + 1, of which those from `lowest` to `highest` lie in the slice. The
// squared terms go to out[j * outStride].
template <int kRun, typename Value>
__device__ void nearestAlongRun(Value value, int first, int lowest, int highest, int reach,
                                float scale, float* out, int outStride) {
    const auto update = [&](int e, float& at) {
        if (e >= lowest && e + 1 <= highest)
            crossingOn(value(e), value(e + 1), e, at);
    };
    float before[kRun];
    float last = noCrossing();
    for (int e = max(lowest, first - reach - 2); e < first - 1; ++e)
        update(e, last);
#pragma unroll
    for (int j = 0; j < kRun; ++j) {
        update(first + j - 1, last);
        before[j] = last;
    }
    float next = noCrossing();
    for (int e = min(highest - 1, first + kRun + reach); e >= first + kRun; --e)
        update(e, next);
#pragma unroll
    for (int j = kRun - 1; j >= 0; --j) {
        update(first + j, next);
        const float p = float(first + j);
        out[j * outStride] = nearTerm(scale, fminf(pixelsTo(p, before[j]), pixelsTo(p, next)));
    }
}

// The minimum over one axis's candidates, outwards from the pixel at `p` (terms[q * stride] the
// term of line coordinate q, `count` of them in the slice) while the step's term is below it.
__device__ inline float outwardMinimum(const float* terms, int stride, int p, int count, int reach,
                                       float scale, float squared) {
    for (int d = 0; d <= reach; ++d) {
        const float step = stepTerm(scale, d);
        if (!(step < squared))
            break;
        if (p - d >= 0)
            squared = fminf(squared, terms[(p - d) * stride] + step);
        if (d > 0 && p + d < count)
            squared = fminf(squared, terms[(p + d) * stride] + step);
    }
    return squared;
}

// Where a block's tile lies: the tile's first pixel (x0, y0) and its values' first pixel
// (vx0, vy0), vw x vh of them (DistanceTile's picture).
struct TilePlace {
    int x0, y0, vx0, vy0, vw, vh;
    __device__ TilePlace(const DistanceTile& tile)
        : x0(int(blockIdx.x) * 32), y0(int(blockIdx.y) * 32), vx0(x0 - tile.reachI - 2),
          vy0(y0 - tile.reachJ - 2), vw(tile.valueWidth()), vh(tile.valueHeight()) {}
};

// Step 1: the tile's values into shared memory, a warp a row at a time, its lanes along the row;
// whether they hold both sides of the iso-value. Every thread of the block calls it.
template <typename T>
__device__ bool loadTileValues(const T* slice, AboveIso above, SliceGrid grid, const TilePlace& at,
                               float* values) {
    bool sawInside = false, sawOutside = false;
    for (int ly = int(threadIdx.y); ly < at.vh; ly += int(blockDim.y)) {
        const int y = at.vy0 + ly;
        if (y < 0 || y >= grid.height)
            continue;
        const T* row = slice + std::size_t(y) * std::size_t(grid.width);
        for (int lx = int(threadIdx.x); lx < at.vw; lx += int(blockDim.x)) {
            const int x = at.vx0 + lx;
            if (x < 0 || x >= grid.width)
                continue;
            const float v = above(row[x]);
            values[ly * at.vw + lx] = v;
            sawInside |= v >= 0.0f;
            sawOutside |= !(v >= 0.0f);
        }
    }
    const int anyInside = __syncthreads_or(sawInside);
    const int anyOutside = __syncthreads_or(sawOutside);
    return anyInside && anyOutside;
}

// Step 2: the row and column terms, a run of kRun pixels a thread.
template <int kRun>
__device__ void tileNearTerms(const float* values, const DistanceTile& tile,
                              const DistanceSetup& setup, SliceGrid grid, const TilePlace& at,
                              float* rowTerms, float* columnTerms) {
    const int thread = int(threadIdx.y * blockDim.x + threadIdx.x);
    const int threads = int(blockDim.x * blockDim.y);
    const int rowItems = tile.rowSpan() * (32 / kRun);
    for (int i = thread; i < rowItems; i += threads) {
        const int r = i % tile.rowSpan(), run = i / tile.rowSpan();
        const int y = at.y0 - tile.reachJ + r;
        if (y < 0 || y >= grid.height)
            continue;
        const float* line = values + (y - at.vy0) * at.vw - at.vx0;
        nearestAlongRun<kRun>([&](int x) { return line[x]; }, at.x0 + run * kRun, 0, grid.width - 1,
                              tile.reachI, setup.scaleI, rowTerms + r * 32 + run * kRun, 1);
    }
    const int columnItems = tile.columnSpan() * (32 / kRun);
    for (int i = thread; i < columnItems; i += threads) {
        const int c = i % tile.columnSpan(), run = i / tile.columnSpan();
        const int x = at.x0 - tile.reachI + c;
        if (x < 0 || x >= grid.width)
            continue;
        const float* line = values + (x - at.vx0) - at.vy0 * at.vw;
        nearestAlongRun<kRun>([&](int y) { return line[y * at.vw]; }, at.y0 + run * kRun, 0,
                              grid.height - 1, tile.reachJ, setup.scaleJ,
                              columnTerms + run * kRun * tile.columnSpan() + c, tile.columnSpan());
    }
}

// Steps 1-3 (DistanceTile's picture), blockIdx.z the slice.
template <typename T>
__global__ void __launch_bounds__(256)
    sliceDistanceTileKernel(const T* voxels, AboveIso above, SliceGrid grid, DistanceTile tile,
                            DistanceSetup setup, std::int16_t* distance) {
    extern __shared__ float shared[];
    const TilePlace at(tile);
    float* values = shared;
    float* rowTerms = values + at.vw * at.vh;
    float* columnTerms = rowTerms + tile.rowSpan() * 32;
    const int k = int(blockIdx.z);
    const bool crossings = loadTileValues(voxels + grid.at(0, 0, k), above, grid, at, values);
    if (crossings)
        tileNearTerms<8>(values, tile, setup, grid, at, rowTerms, columnTerms);
    __syncthreads();

    const int x = at.x0 + int(threadIdx.x);
    if (x >= grid.width)
        return;
    const int lx = int(threadIdx.x);
    for (int row = int(threadIdx.y); row < 32; row += int(blockDim.y)) {
        const int y = at.y0 + row;
        if (y >= grid.height)
            break;
        float squared = setup.reaching;
        if (crossings) {
            squared = outwardMinimum(rowTerms + (tile.reachJ - at.y0) * 32 + lx, 32, y, grid.height,
                                     tile.reachJ, setup.scaleJ, squared);
            squared = outwardMinimum(columnTerms + row * tile.columnSpan() + tile.reachI - at.x0, 1,
                                     x, grid.width, tile.reachI, setup.scaleI, squared);
        }
        const bool inside = values[(y - at.vy0) * at.vw + (x - at.vx0)] >= 0.0f;
        distance[grid.at(x, y, k)] =
            squared < setup.reaching
                ? storedSliceDistance(squared, inside, setup.limitMm, setup.stepsPerMm)
                : (inside ? setup.insideLimit : setup.outsideLimit);
    }
}

// The same minimum straight from global memory, a thread a pixel: for reaches beyond the tile's.
template <typename T>
__global__ void distanceKernel(const T* voxels, AboveIso above, const float* rowNear,
                               const float* columnNear, SliceGrid grid, int reachI, int reachJ,
                               float scaleI, float scaleJ, double limitMm, double stepsPerMm,
                               std::int16_t* distance) {
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
    distance[p] = storedSliceDistance(squared, above(voxels[p]) >= 0.0f, limitMm, stepsPerMm);
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

// One pixel's values between the slices of gap `gap` (`lower`: the pixel in the gap's lower
// slice), as planeValue gives them at each weight along the slices, the monotone cubic's tangents
// found once for all steps of the gap: the same floats from the same expressions.
struct GapProfile {
    float y1, y2, m1 = 0.0f, m2 = 0.0f;
    bool monotone;
    __device__ GapProfile(const std::int16_t* lower, std::size_t plane, int gap,
                          const RefineGrid& g)
        : y1(float(lower[0])), y2(float(lower[plane])), monotone(g.monotoneK) {
        if (!monotone)
            return;
        const float secant = y2 - y1;
        m1 = gap == 0 ? secant : monotoneTangent(y1 - float(*(lower - plane)), secant);
        m2 = gap + 2 >= g.slices ? secant : monotoneTangent(secant, float(lower[2 * plane]) - y2);
    }
    __device__ float at(float upperWeight) const {
        return monotone ? hermiteBlend(HermiteWeights(upperWeight), y1, m1, y2, m2)
                        : linearBlend(y1, upperWeight, y2);
    }
};

// Each of the six faces' largest value over a warp's lanes, into `maxima` (faceMaximaKernel's
// slots: value + 32768, for atomicMax). Every lane of the warp calls it; a lane holding no voxel
// of a face holds -32768 there.
__device__ inline void warpFaceMaxima(const int (&best)[6], unsigned* maxima) {
#pragma unroll
    for (int face = 0; face < 6; ++face) {
        int value = best[face];
        if (!__any_sync(0xffffffffu, value > -32768))
            continue;
        for (int offset = 16; offset > 0; offset /= 2)
            value = max(value, __shfl_down_sync(0xffffffffu, value, offset));
        if ((threadIdx.x & 31u) == 0)
            atomicMax(&maxima[face], unsigned(value + 32768));
    }
}

// Where the refinement is along the slices only (factors 1, 1, factorK), refineKernel,
// bridgeKernel and faceMaximaKernel in one pass, a thread per pixel of a gap (blockIdx.z): the
// gap's lower slice, the factorK - 1 between (planeValue, as refineKernel) and, in the last gap,
// the upper slice; then, where `bridge`, the thin walls slid between (bridgeThinShellPixel, as
// bridgeKernel: the gap's two slices are the distance slices themselves, which the refinement
// copies unchanged, and the slices between are this thread's own); then the faces' maxima, of
// voxels the bridge never changes (it raises inner pixels between two slices only).
__global__ void refineAlongSlicesKernel(const std::int16_t* distance, RefineGrid g,
                                        ThinShellSlices pair, bool bridge, std::int16_t* refined,
                                        unsigned* faceMaxima) {
    const int x = int(blockIdx.x * blockDim.x + threadIdx.x);
    const int y = int(blockIdx.y * blockDim.y + threadIdx.y);
    const int gap = int(blockIdx.z), factor = g.factorK;
    int best[6] = {-32768, -32768, -32768, -32768, -32768, -32768};
    if (x < g.width && y < g.height) {
        const std::size_t plane = std::size_t(g.width) * std::size_t(g.height);
        const std::size_t at = std::size_t(y) * std::size_t(g.width) + std::size_t(x);
        const std::int16_t* lower = distance + plane * std::size_t(gap);
        std::int16_t* out = refined + plane * std::size_t(gap) * std::size_t(factor);
        const bool lastGap = gap + 2 == g.slices;
        int largest = lower[at];
        out[at] = lower[at];
        const GapProfile profile(lower + at, plane, gap, g);
        for (int step = 1; step < factor; ++step) {
            const int value = roundHalfAway(profile.at(float(step) / float(factor)));
            out[plane * std::size_t(step) + at] = std::int16_t(value);
            largest = max(largest, value);
        }
        if (lastGap) {
            const int top = lower[plane + at];
            out[plane * std::size_t(factor) + at] = std::int16_t(top);
            largest = max(largest, top);
            best[5] = top;
        }
        if (gap == 0)
            best[4] = lower[at];
        if (x == 0)
            best[0] = largest;
        if (x + 1 == g.width)
            best[1] = largest;
        if (y == 0)
            best[2] = largest;
        if (y + 1 == g.height)
            best[3] = largest;
        if (bridge && x >= 1 && y >= 1 && x + 1 < g.width && y + 1 < g.height) {
            ThinShellSlices slices = pair;
            slices.lower = lower;
            slices.upper = lower + plane;
            bridgeThinShellPixel(slices, out + plane, plane, factor, x, y);
        }
    }
    warpFaceMaxima(best, faceMaxima);
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
