#pragma once

// MarchingCubesCuda's state, shared with the other kernels of the back-end that start from its
// classification (method 2 walks its active cells). Private to kernels/cuda.

#include "dispatch.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "marching_cubes_kernels.cuh"

#include <algorithm>
#include <cub/device/device_scan.cuh>
#include <limits>
#include <thrust/iterator/transform_iterator.h>

namespace lw::kernels::cuda {

using dispatch::blocksFor;
using dispatch::DeviceBuffer;

// A word's set bits (the scan of the active bitmap counts them as it reads the words).
struct BitCount {
    __host__ __device__ std::uint32_t operator()(std::uint32_t word) const {
#ifdef __CUDA_ARCH__
        return std::uint32_t(__popc(word));
#else
        return std::uint32_t(__builtin_popcount(word));
#endif
    }
};

struct MarchingCubesCuda::Impl {
    dispatch::Stream stream;
    VolumeView volume; // device voxels after setVolume (voxels points to `voxels`)
    DeviceBuffer<unsigned char> voxels;
    DeviceBuffer<double> sliceOffset;
    DeviceBuffer<float> spanK, invSpanK;
    GridSpans spans;
    McGridFrame frame{};
    std::uint32_t bricksX = 0, bricksY = 0, bricksZ = 0;
    DeviceBuffer<float2> brickMinMax;
    DeviceBuffer<std::uint8_t> brickActive;
    DeviceBuffer<int> flag;

    // The active bitmap of the last classification and its words' scanned bit counts
    // (mc::ActiveBitmap).
    DeviceBuffer<std::uint32_t> activeWords, wordOffsets;
    std::uint32_t wordsPerRow = 0;
    mc::ActiveBitmap bitmap() const {
        return mc::ActiveBitmap{activeWords.data(), wordOffsets.data(), wordsPerRow};
    }
    DeviceBuffer<std::uint32_t> activeVoxels, vertexCounts, vertexOffsets, triangleCounts,
        triangleOffsets;
    DeviceBuffer<std::uint16_t> activeCodes;
    DeviceBuffer<unsigned char> scanTemp;
    DeviceBuffer<glm::vec3> positions, normals;
    DeviceBuffer<std::uint32_t> indices;

    // The streamed (L) variant: the host volume, registered with the driver when possible,
    // otherwise staged through pinned buffers; two device slots for the slab boxes.
    const void* hostVoxels = nullptr;
    bool streamed = false;
    bool hostRegistered = false;
    dispatch::Stream uploadStream;
    DeviceBuffer<unsigned char> slabBox[2];
    dispatch::PinnedBuffer<unsigned char> staging[2];
    cudaEvent_t uploaded[2] = {nullptr, nullptr};
    std::size_t peakBytes = 0;

    ~Impl() {
        unregisterHost();
        for (cudaEvent_t& e : uploaded)
            if (e)
                cudaEventDestroy(e);
    }
    void unregisterHost() {
        if (hostRegistered)
            cudaHostUnregister(const_cast<void*>(hostVoxels));
        hostRegistered = false;
        hostVoxels = nullptr;
    }
    // The classification and mesh buffers (sized by the last extraction) go back to the device.
    void releaseScratch() {
        activeWords.release();
        wordOffsets.release();
        activeVoxels.release();
        vertexCounts.release();
        vertexOffsets.release();
        triangleCounts.release();
        triangleOffsets.release();
        activeCodes.release();
        scanTemp.release();
        positions.release();
        normals.release();
        indices.release();
        totals.release();
    }
    void notePeak() { peakBytes = deviceBytes() > peakBytes ? deviceBytes() : peakBytes; }
    CudaStatus uploadGridTables(const VoxelGridSetup& setup);
    CudaStatus beginWholeVolume(const VolumeView& host);
    CudaStatus finishWholeVolume(const VoxelGridSetup& setup);
    CudaStatus copyWholeVolume(const VolumeView& from, const VoxelGridSetup& setup,
                               cudaMemcpyKind direction);
    template <typename T>
    CudaStatus extractSlabsTyped(double iso, const std::vector<CellSlab>& slabs,
                                 const MarchingCubesCuda::SlabCallback& onSlab);
    // The voxel box of a slab: [begin, end), whole x rows.
    struct SlabBox {
        glm::ivec3 begin, end;
    };
    SlabBox slabBoxOf(const CellSlab& slab) const;
    CudaStatus uploadSlab(int slot, const SlabBox& box);

    std::uint32_t activeCount = 0;
    // An upper bound of the active voxels' indices (the sort key range of method 2).
    std::uint32_t activeVoxelLimit() const { return std::uint32_t(volume.voxelCount()); }
    DeviceMeshView mesh;
    McCudaTimes times;
    double uploadMs = 0.0;
    dispatch::StageTimer timers[4];

    std::size_t deviceBytes() const {
        return voxels.bytes() + sliceOffset.bytes() + spanK.bytes() + invSpanK.bytes() +
               brickMinMax.bytes() + brickActive.bytes() + activeWords.bytes() +
               wordOffsets.bytes() + activeVoxels.bytes() + vertexCounts.bytes() +
               vertexOffsets.bytes() + triangleCounts.bytes() + triangleOffsets.bytes() +
               activeCodes.bytes() + slabBox[0].bytes() + slabBox[1].bytes() + scanTemp.bytes() +
               positions.bytes() + normals.bytes() + indices.bytes() + totals.bytes();
    }

    // CUB's exclusive sum over `count` values (temporary storage grown on demand).
    template <typename Input>
    CudaStatus exclusiveSum(Input in, std::uint32_t* out, std::uint32_t count, const char* what) {
        std::size_t bytes = 0;
        LW_CUDA_TRY(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, count, stream.get()),
                    what);
        LW_RETURN_IF_FAILED(scanTemp.reserve(bytes, what));
        LW_CUDA_TRY(
            cub::DeviceScan::ExclusiveSum(scanTemp.data(), bytes, in, out, count, stream.get()),
            what);
        return CudaStatus::success();
    }

    // The grid fields common to S and L: the volume's spans and frame, the iso-value.
    template <typename T> mc::Grid<T> baseGrid(double iso) const {
        mc::Grid<T> g{};
        g.spans = spans;
        g.frame = frame;
        g.threshold = voxelInsideThreshold<T>(iso);
        g.iso = iso;
        g.isoF = insideThreshold(iso);
        return g;
    }

    // S: the whole resident volume, with the brick skip.
    template <typename T> mc::Grid<T> grid(double iso) const {
        mc::Grid<T> g = baseGrid<T>(iso);
        g.box = static_cast<const T*>(volume.voxels); // device copy, or mapped host memory
        g.boxX = std::uint32_t(volume.dims.x);
        g.boxY = std::uint32_t(volume.dims.y);
        g.boxOrigin = glm::ivec3(0);
        g.indexOrigin = 0;
        g.lo = glm::ivec3(0);
        g.hi = volume.dims - 1;
        g.rowsY = std::uint32_t(volume.dims.y);
        g.brickActive = brickActive.data();
        g.bricksX = bricksX;
        g.bricksY = bricksY;
        return g;
    }

    // L: one brick's cells [cellBegin, cellEnd) with its box (the corner voxels and the gradient
    // apron, boxBegin .. boxEnd exclusive) resident at `box`.
    template <typename T>
    mc::Grid<T> brickGrid(double iso, const T* box, glm::ivec3 boxBegin, glm::ivec3 boxEnd,
                          glm::ivec3 cellBegin, glm::ivec3 cellEnd) const {
        mc::Grid<T> g = baseGrid<T>(iso);
        const glm::ivec3 size = boxEnd - boxBegin;
        g.box = box;
        g.boxX = std::uint32_t(size.x);
        g.boxY = std::uint32_t(size.y);
        g.boxOrigin = boxBegin;
        g.indexOrigin = std::size_t(boxBegin.x) +
                        std::size_t(size.x) * (std::size_t(boxBegin.y) +
                                               std::size_t(size.y) * std::size_t(boxBegin.z));
        g.spans.dims.sy = std::size_t(size.x);
        g.spans.dims.sz = std::size_t(size.x) * std::size_t(size.y);
        g.lo = cellBegin;
        g.hi = cellEnd;
        g.rowsY = std::uint32_t(cellEnd.y - cellBegin.y + 1);
        g.brickActive = nullptr;
        return g;
    }

    template <typename T> CudaStatus computeBrickMinMax();
    // S: active bricks and the border test (the whole volume only).
    template <typename T> CudaStatus markBricksTyped(const mc::Grid<T>& g);
    // Whether classifyGrid waits for the active count (method 2 and the streamed slabs read it
    // at once) or leaves it to generate() (one wait fewer per extraction).
    enum class CountWait { Now, Pending };
    // The ordered active voxel list of g's range (activeVoxels, activeCodes, their vertex and
    // triangle counts; activeCount, or activePending until generate() has it).
    template <typename T> CudaStatus classifyGrid(const mc::Grid<T>& g, CountWait wait);
    CudaStatus reserveActiveList(std::uint32_t active);
    template <typename T> CudaStatus writeActiveList(const mc::Grid<T>& g, std::uint32_t capacity);
    // The vertex and triangle offsets of the first `capacity` list entries and the totals
    // (active, vertices, triangles) in hostCounts, after one wait.
    CudaStatus scanGeometry(std::uint32_t capacity);
    // scanGeometry for the list as classifyGrid left it, writing it again where it did not fit.
    template <typename T> CudaStatus offsetsOfActiveList(const mc::Grid<T>& g);
    // The active voxels the list's buffers hold.
    std::uint32_t listCapacity() const {
        const std::size_t counts = std::min(vertexCounts.capacity(), triangleCounts.capacity());
        const std::size_t list = std::min(activeVoxels.capacity(), activeCodes.capacity());
        const std::size_t fits = std::min(list, counts > 0 ? counts - 1 : 0);
        return std::uint32_t(
            std::min<std::size_t>(fits, std::numeric_limits<std::uint32_t>::max() - 1));
    }
    const std::uint32_t* activeTotal() const { return wordOffsets.data() + wordCount; }
    std::uint32_t wordCount = 0;
    bool activePending = false;
    DeviceBuffer<std::uint32_t> totals;
    // The mesh of the classified voxels (positions/normals/indices, mesh).
    template <typename T> CudaStatus generate(const mc::Grid<T>& g);
    template <typename T> CudaStatus classifyTyped(double iso, CountWait wait);
    template <typename T> CudaStatus extractTyped(double iso);
    // Counts the host needs (a size to allocate, a total) land in page-locked slots, so their
    // copies are asynchronous and one wait serves several: the border flag is copied when its
    // kernel is queued and read after the classification's wait.
    enum CountSlot { kBorderSlot, kActiveSlot, kVertexSlot, kTriangleSlot, kCountSlots };
    dispatch::PinnedBuffer<std::uint32_t> hostCounts;
    CudaStatus queueCount(const void* device, CountSlot slot, const char* what) {
        LW_RETURN_IF_FAILED(hostCounts.reserve(kCountSlots, what));
        LW_CUDA_TRY(cudaMemcpyAsync(hostCounts.data() + slot, device, sizeof(std::uint32_t),
                                    cudaMemcpyDeviceToHost, stream.get()),
                    what);
        return CudaStatus::success();
    }
    CudaStatus waitForCounts(const char* what) {
        LW_CUDA_TRY(cudaStreamSynchronize(stream.get()), what);
        return CudaStatus::success();
    }
    std::uint32_t count(CountSlot slot) const { return hostCounts.data()[slot]; }
};

} // namespace lw::kernels::cuda
