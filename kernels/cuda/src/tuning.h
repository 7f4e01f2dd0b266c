#pragma once

// Tuning constants of the CUDA kernels, apart from the kernels and the dispatch (CUB's layout):
// change them here, measure with `linework-cli bench --backend cuda`.

namespace lw::kernels::cuda::tuning {

// Marching cubes: one classification tile is one block of threads, one voxel each; x fastest,
// so a tile is a run of a voxel row and its reads coalesce.
inline constexpr int kClassifyBlock = 256;
// Slices a classification block walks up along z (one tile each): fewer, longer blocks, each
// slice's corner bits serve two voxels, and a thread's reads of all of them are in flight at once.
// Must divide kSkipBrickCells (a block's planes then lie in one layer of skip bricks).
inline constexpr int kClassifyPlanes = 16;
// Cells per brick edge of the min/max skip grid (a power of two: voxel -> brick is a shift).
inline constexpr int kSkipBrickShift = 4;
inline constexpr int kSkipBrickCells = 1 << kSkipBrickShift;
inline constexpr int kBrickReduceBlock = 256;
// Per active voxel (vertex and triangle generation, counts).
inline constexpr int kActiveBlock = 128;
// Method 2: one thread per active cell (heavy threads: vertices, segments, visibility rays).
inline constexpr int kRayCastBlock = 64;
// Method 2: the visibility rays' lanes (each takes ray after ray).
inline constexpr int kRayBlock = 128;
// Method 2: one thread per kept triangle (light threads; one atomic per block).
inline constexpr int kSegmentTriangleBlock = 512;

// The thick-slice field's nearest crossings through global memory (reaches past the tile's):
// rows a warp walks down each of its columns (the walk starts and ends the limit's reach beyond
// them, so longer runs waste less), and warps a block (fewer where the runs of edges along the
// rows need more shared memory).
inline constexpr int kNearRowsPerWarp = 16;
inline constexpr int kNearWarps = 8;
// Its distances: a 32 x 32 tile a block, with its values, row and column terms in shared memory,
// for reaches up to kDistanceTileMaxReach pixels (29 KiB at 12, 83 KiB at 40; over 48 KiB the
// kernel opts in, where the device allows); longer reaches go through global memory.
inline constexpr int kDistanceTileMaxReach = 40;
// The field's face maxima: blocks per face (grid-stride; a 512 x 82 face is 168 blocks' worth)
// and threads per block (whole warps: the kernel reduces by shuffles).
inline constexpr int kFaceMaximaBlocks = 32;
inline constexpr int kFaceMaximaBlock = 256;

// Method 3: per vertex, per triangle, per pixel.
inline constexpr int kVertexBlock = 256;
inline constexpr int kTriangleBlock = 128;
inline constexpr int kPixelBlockX = 32;
inline constexpr int kPixelBlockY = 8;

// Stroke pruning: one thread per pixel (labels, sizes, clearing); the unions use the 2D pixel
// blocks above.
inline constexpr int kStrokePixelBlock = 256;

} // namespace lw::kernels::cuda::tuning
