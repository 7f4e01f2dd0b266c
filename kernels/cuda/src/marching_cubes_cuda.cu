// Host dispatch of marching cubes on the GPU (kernels in marching_cubes_kernels.cuh).

#include "dispatch.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "marching_cubes_impl.cuh"

#include <cstring>
#include <cub/device/device_scan.cuh>
#include <limits>
#include <mutex>

namespace lw::kernels::cuda {

using dispatch::blocksFor;
using dispatch::DeviceBuffer;

MarchingCubesCuda::MarchingCubesCuda() : m_impl(std::make_unique<Impl>()) {}
MarchingCubesCuda::~MarchingCubesCuda() = default;

double MarchingCubesCuda::uploadMs() const {
    return m_impl->uploadMs;
}
std::size_t MarchingCubesCuda::deviceBytes() const {
    return m_impl->deviceBytes();
}
DeviceMeshView MarchingCubesCuda::mesh() const {
    return m_impl->mesh;
}
const McCudaTimes& MarchingCubesCuda::times() const {
    return m_impl->times;
}
std::size_t MarchingCubesCuda::activeVoxelCount() const {
    return m_impl->activeCount;
}

template <typename T> CudaStatus MarchingCubesCuda::Impl::computeBrickMinMax() {
    const std::uint32_t count = bricksX * bricksY * bricksZ;
    mc::brickMinMax<T><<<count, tuning::kBrickReduceBlock, 0, stream.get()>>>(
        static_cast<const T*>(volume.voxels), std::uint32_t(volume.dims.x),
        std::uint32_t(volume.dims.y), std::uint32_t(volume.dims.z), bricksX, bricksY,
        brickMinMax.data());
    LW_CUDA_LAUNCHED("mc::brickMinMax");
    return CudaStatus::success();
}

namespace {

// Marching cubes needs at least one cell along each axis.
CudaStatus needsCells(glm::ivec3 dims, const char* where) {
    if (dims.x < 2 || dims.y < 2 || dims.z < 2)
        return CudaStatus::failure(CudaStatus::Code::TooLarge, where,
                                   "the volume needs at least 2 voxels along each axis");
    return CudaStatus::success();
}

} // namespace

CudaStatus MarchingCubesCuda::Impl::uploadGridTables(const VoxelGridSetup& setup) {
    const std::vector<double>& offsets = setup.sliceOffsets();
    const std::size_t slices = offsets.size();
    LW_RETURN_IF_FAILED(sliceOffset.reserve(slices, "cudaMalloc(sliceOffset)"));
    LW_RETURN_IF_FAILED(spanK.reserve(slices, "cudaMalloc(spanK)"));
    LW_RETURN_IF_FAILED(invSpanK.reserve(slices, "cudaMalloc(invSpanK)"));
    // On the kernels' stream (non-blocking, so not ordered after a plain cudaMemcpy, which may
    // return from pageable memory before its DMA lands).
    const cudaStream_t st = stream.get();
    LW_CUDA_TRY(cudaMemcpyAsync(sliceOffset.data(), offsets.data(), slices * sizeof(double),
                                cudaMemcpyHostToDevice, st),
                "cudaMemcpy(sliceOffset)");
    LW_CUDA_TRY(cudaMemcpyAsync(spanK.data(), setup.spans().spanK, slices * sizeof(float),
                                cudaMemcpyHostToDevice, st),
                "cudaMemcpy(spanK)");
    LW_CUDA_TRY(cudaMemcpyAsync(invSpanK.data(), setup.spans().invSpanK, slices * sizeof(float),
                                cudaMemcpyHostToDevice, st),
                "cudaMemcpy(invSpanK)");
    spans = setup.spans();
    spans.spanK = spanK.data();
    spans.invSpanK = invSpanK.data();
    frame = setup.frame();
    frame.sliceOffset = sliceOffset.data();

    return CudaStatus::success();
}

// What setVolume and setMappedVolume share before the voxels are placed.
CudaStatus MarchingCubesCuda::Impl::beginWholeVolume(const VolumeView& host) {
    mesh = DeviceMeshView();
    activeCount = 0;
    LW_RETURN_IF_FAILED(needsCells(host.dims, "marching cubes (CUDA)"));
    if (host.voxelCount() >= std::size_t(std::numeric_limits<std::uint32_t>::max()) - 1024)
        return CudaStatus::failure(CudaStatus::Code::TooLarge, "marching cubes (CUDA)",
                                   "more than 2^32 voxels: the kernels index voxels with 32 bits");
    LW_RETURN_IF_FAILED(mc::uploadTables());
    LW_RETURN_IF_FAILED(stream.create());
    unregisterHost();
    streamed = false;
    slabBox[0].release();
    slabBox[1].release();
    peakBytes = 0;
    volume = host;
    return CudaStatus::success();
}

CudaStatus MarchingCubesCuda::setVolume(const VolumeView& host, const VoxelGridSetup& setup) {
    return m_impl->copyWholeVolume(host, setup, cudaMemcpyHostToDevice);
}

CudaStatus MarchingCubesCuda::setDeviceVolume(const VolumeView& device,
                                              const VoxelGridSetup& setup) {
    return m_impl->copyWholeVolume(device, setup, cudaMemcpyDeviceToDevice);
}

// setVolume and setDeviceVolume: the voxels copied into the device buffer the kernels read.
CudaStatus MarchingCubesCuda::Impl::copyWholeVolume(const VolumeView& from,
                                                    const VoxelGridSetup& setup,
                                                    cudaMemcpyKind direction) {
    Impl& s = *this;
    LW_RETURN_IF_FAILED(s.beginWholeVolume(from));
    LW_RETURN_IF_FAILED(s.voxels.reserve(from.byteCount(), "cudaMalloc(volume)"));
    s.volume.voxels = s.voxels.data();

    dispatch::StageTimer upload;
    LW_RETURN_IF_FAILED(upload.start(s.stream.get()));
    LW_CUDA_TRY(
        cudaMemcpyAsync(s.voxels.data(), from.voxels, from.byteCount(), direction, s.stream.get()),
        "cudaMemcpy(volume)");
    LW_RETURN_IF_FAILED(upload.stop(s.stream.get()));
    LW_RETURN_IF_FAILED(s.finishWholeVolume(setup));
    s.uploadMs = upload.ms();
    return CudaStatus::success();
}

CudaStatus MarchingCubesCuda::setMappedVolume(const VolumeView& host, const VoxelGridSetup& setup) {
    Impl& s = *m_impl;
    LW_RETURN_IF_FAILED(s.beginWholeVolume(host));
    s.voxels.release(); // the device copy of an earlier setVolume
    const cudaError_t registered =
        cudaHostRegister(const_cast<void*>(host.voxels), host.byteCount(),
                         cudaHostRegisterMapped | cudaHostRegisterReadOnly);
    if (registered != cudaSuccess) {
        cudaGetLastError(); // not sticky: the caller's next way (the CPU) must not see it
        // Another renderer of the same volume page-locked it already (a streamed frame of
        // method 1 or 3): with unified addressing it is mapped too, and the registration stays
        // that renderer's (it unregisters before the volume dies, releaseVolume).
        if (registered != cudaErrorHostMemoryAlreadyRegistered)
            return dispatch::statusOf(registered, "cudaHostRegister(mapped volume)");
    } else {
        s.hostRegistered = true;
        s.hostVoxels = host.voxels;
    }
    void* device = nullptr;
    const cudaError_t mapped = cudaHostGetDevicePointer(&device, const_cast<void*>(host.voxels), 0);
    if (mapped != cudaSuccess) {
        cudaGetLastError();
        return dispatch::statusOf(mapped, "cudaHostGetDevicePointer(volume)");
    }
    s.volume.voxels = device;
    LW_RETURN_IF_FAILED(s.finishWholeVolume(setup));
    s.uploadMs = 0.0;
    return CudaStatus::success();
}

// The grid tables and the brick min/max, once the voxels are where the kernels read them.
CudaStatus MarchingCubesCuda::Impl::finishWholeVolume(const VoxelGridSetup& setup) {
    Impl& s = *this;
    const glm::ivec3 d = volume.dims;
    LW_RETURN_IF_FAILED(s.uploadGridTables(setup));

    const auto bricks = [](int voxels) {
        return std::uint32_t((voxels - 1 + tuning::kSkipBrickCells - 1) / tuning::kSkipBrickCells);
    };
    s.bricksX = bricks(d.x);
    s.bricksY = bricks(d.y);
    s.bricksZ = bricks(d.z);
    const std::size_t brickCount = std::size_t(s.bricksX) * s.bricksY * s.bricksZ;
    LW_RETURN_IF_FAILED(s.brickMinMax.reserve(brickCount, "cudaMalloc(brickMinMax)"));
    LW_RETURN_IF_FAILED(s.brickActive.reserve(brickCount, "cudaMalloc(brickActive)"));
    LW_RETURN_IF_FAILED(s.flag.reserve(1, "cudaMalloc(flag)"));
    LW_RETURN_IF_FAILED(dispatchVoxelKind(
        volume.kind, [&](auto zero) { return s.computeBrickMinMax<decltype(zero)>(); }));
    LW_CUDA_TRY(cudaStreamSynchronize(s.stream.get()), "mc::brickMinMax");
    s.notePeak();
    return CudaStatus::success();
}

void MarchingCubesCuda::setGradientStencil(GradientStencil stencil) {
    m_impl->spans.stencil = stencil;
}

CudaStatus MarchingCubesCuda::extract(double storedIso) {
    Impl& s = *m_impl;
    if (!s.volume.voxels || s.streamed)
        return CudaStatus::failure(CudaStatus::Code::Failed, "marching cubes (CUDA)",
                                   "no volume: call setVolume first");
    s.mesh = DeviceMeshView();
    const CudaStatus status = dispatchVoxelKind(
        s.volume.kind, [&](auto zero) { return s.extractTyped<decltype(zero)>(storedIso); });
    s.notePeak();
    return status;
}

template <typename T> CudaStatus MarchingCubesCuda::Impl::markBricksTyped(const mc::Grid<T>& g) {
    cudaStream_t st = stream.get();
    const std::uint32_t brickCount = bricksX * bricksY * bricksZ;
    mc::markActiveBricks<<<blocksFor(brickCount, 256), 256, 0, st>>>(brickMinMax.data(), brickCount,
                                                                     g.iso, brickActive.data());
    LW_CUDA_LAUNCHED("mc::markActiveBricks");
    LW_CUDA_TRY(cudaMemsetAsync(flag.data(), 0, sizeof(int), st), "cudaMemset(flag)");
    mc::borderInside<T><<<dim3(64, 6), 256, 0, st>>>(
        g.box, std::uint32_t(volume.dims.x), std::uint32_t(volume.dims.y),
        std::uint32_t(volume.dims.z), g.threshold, flag.data());
    LW_CUDA_LAUNCHED("mc::borderInside");
    // Read after the classification's wait (classifyTyped).
    return queueCount(flag.data(), kBorderSlot, "mc::borderInside");
}

template <typename T>
CudaStatus MarchingCubesCuda::Impl::classifyGrid(const mc::Grid<T>& g, CountWait wait) {
    cudaStream_t st = stream.get();
    const std::uint32_t tilesPerRow =
        blocksFor(std::size_t(g.hi.x - g.lo.x + 1), tuning::kClassifyBlock);
    const std::uint32_t slices = std::uint32_t(g.hi.z - g.lo.z + 1);
    const std::uint32_t zGroups = (slices + tuning::kClassifyPlanes - 1) / tuning::kClassifyPlanes;
    const dim3 tileGrid(g.rowsY * zGroups, tilesPerRow); // see mc::TileWalk
    wordsPerRow = tilesPerRow * (tuning::kClassifyBlock / 32);
    wordCount = wordsPerRow * g.rowsY * slices;
    LW_RETURN_IF_FAILED(activeWords.reserve(std::size_t(wordCount) + 1, "cudaMalloc(activeWords)"));
    LW_RETURN_IF_FAILED(wordOffsets.reserve(std::size_t(wordCount) + 1, "cudaMalloc(wordOffsets)"));
    mc::classifyWords<T><<<tileGrid, tuning::kClassifyBlock, 0, st>>>(g, activeWords.data());
    LW_CUDA_LAUNCHED("mc::classifyWords");
    LW_CUDA_TRY(cudaMemsetAsync(activeWords.data() + wordCount, 0, sizeof(std::uint32_t), st),
                "cudaMemset(activeWords)");
    LW_RETURN_IF_FAILED(
        exclusiveSum(thrust::make_transform_iterator(activeWords.data(), BitCount()),
                     wordOffsets.data(), wordCount + 1, "cub::DeviceScan(words)"));
    if (wait == CountWait::Pending && listCapacity() > 0) {
        // generate() learns the count with the totals and writes the list again only if it did
        // not fit: one wait for the host instead of two.
        activePending = true;
        return writeActiveList(g, listCapacity());
    }
    activePending = false;
    LW_RETURN_IF_FAILED(queueCount(activeTotal(), kActiveSlot, "mc::classifyWords"));
    LW_RETURN_IF_FAILED(waitForCounts("mc::classifyWords"));
    activeCount = count(kActiveSlot);
    if (activeCount == 0)
        return CudaStatus::success();
    LW_RETURN_IF_FAILED(reserveActiveList(activeCount));
    return writeActiveList(g, activeCount);
}

CudaStatus MarchingCubesCuda::Impl::reserveActiveList(std::uint32_t active) {
    const std::size_t entries = std::size_t(active) + 1; // the counts' end entry
    LW_RETURN_IF_FAILED(activeVoxels.reserve(active, "cudaMalloc(activeVoxels)"));
    LW_RETURN_IF_FAILED(activeCodes.reserve(active, "cudaMalloc(activeCodes)"));
    LW_RETURN_IF_FAILED(vertexCounts.reserve(entries, "cudaMalloc(vertexCounts)"));
    return triangleCounts.reserve(entries, "cudaMalloc(triangleCounts)");
}

template <typename T>
CudaStatus MarchingCubesCuda::Impl::writeActiveList(const mc::Grid<T>& g, std::uint32_t capacity) {
    mc::writeActive<T>
        <<<blocksFor(wordCount, tuning::kActiveBlock), tuning::kActiveBlock, 0, stream.get()>>>(
            g, bitmap(), wordCount, capacity, activeVoxels.data(), activeCodes.data(),
            vertexCounts.data(), triangleCounts.data());
    LW_CUDA_LAUNCHED("mc::writeActive");
    return CudaStatus::success();
}

CudaStatus MarchingCubesCuda::Impl::scanGeometry(std::uint32_t capacity) {
    const std::uint32_t entries = capacity + 1;
    LW_RETURN_IF_FAILED(vertexOffsets.reserve(entries, "cudaMalloc(vertexOffsets)"));
    LW_RETURN_IF_FAILED(triangleOffsets.reserve(entries, "cudaMalloc(triangleOffsets)"));
    LW_RETURN_IF_FAILED(totals.reserve(3, "cudaMalloc(totals)"));
    LW_RETURN_IF_FAILED(exclusiveSum(vertexCounts.data(), vertexOffsets.data(), entries,
                                     "cub::DeviceScan(vertices)"));
    LW_RETURN_IF_FAILED(exclusiveSum(triangleCounts.data(), triangleOffsets.data(), entries,
                                     "cub::DeviceScan(triangles)"));
    mc::gatherTotals<<<1, 1, 0, stream.get()>>>(activeTotal(), vertexOffsets.data(),
                                                triangleOffsets.data(), capacity, totals.data());
    LW_CUDA_LAUNCHED("mc::gatherTotals");
    static_assert(kVertexSlot == kActiveSlot + 1 && kTriangleSlot == kActiveSlot + 2);
    LW_CUDA_TRY(cudaMemcpyAsync(hostCounts.data() + kActiveSlot, totals.data(),
                                3 * sizeof(std::uint32_t), cudaMemcpyDeviceToHost, stream.get()),
                "mc::gatherTotals");
    return waitForCounts("cub::DeviceScan(vertices, triangles)");
}

template <typename T>
CudaStatus MarchingCubesCuda::Impl::offsetsOfActiveList(const mc::Grid<T>& g) {
    if (!activePending)
        return scanGeometry(activeCount);
    activePending = false;
    const std::uint32_t capacity = listCapacity();
    LW_RETURN_IF_FAILED(scanGeometry(capacity));
    activeCount = count(kActiveSlot);
    if (activeCount <= capacity)
        return CudaStatus::success();
    // More active voxels than the list held: its writes stopped at the end, so write it again.
    LW_RETURN_IF_FAILED(reserveActiveList(activeCount));
    LW_RETURN_IF_FAILED(writeActiveList(g, activeCount));
    return scanGeometry(activeCount);
}

template <typename T> CudaStatus MarchingCubesCuda::Impl::generate(const mc::Grid<T>& g) {
    cudaStream_t st = stream.get();
    const bool touchesBorder = mesh.touchesBorder;
    mesh = DeviceMeshView();
    mesh.touchesBorder = touchesBorder;
    if (!activePending && activeCount == 0)
        return CudaStatus::success();

    // Vertex and triangle offsets.
    LW_RETURN_IF_FAILED(timers[2].start(st));
    LW_RETURN_IF_FAILED(hostCounts.reserve(kCountSlots, "cudaMallocHost(counts)"));
    LW_RETURN_IF_FAILED(offsetsOfActiveList(g));
    LW_RETURN_IF_FAILED(timers[2].stop(st));
    const std::uint32_t active = activeCount;
    if (active == 0)
        return CudaStatus::success();
    const std::uint32_t vertexTotal = count(kVertexSlot), triangleTotal = count(kTriangleSlot);
    // Each active voxel has at most 3 vertices and 5 triangles: with fewer than 2^32 / 16 active
    // voxels no 32-bit count can have wrapped.
    if (active >= std::numeric_limits<std::uint32_t>::max() / 16)
        return CudaStatus::failure(CudaStatus::Code::TooLarge, "marching cubes (CUDA)",
                                   "more than 2^32 / 3 triangle corners");

    LW_RETURN_IF_FAILED(timers[3].start(st));
    LW_RETURN_IF_FAILED(positions.reserve(vertexTotal, "cudaMalloc(positions)"));
    LW_RETURN_IF_FAILED(normals.reserve(vertexTotal, "cudaMalloc(normals)"));
    LW_RETURN_IF_FAILED(indices.reserve(std::size_t(triangleTotal) * 3, "cudaMalloc(indices)"));
    mc::generateVertices<T>
        <<<blocksFor(active, tuning::kActiveBlock), tuning::kActiveBlock, 0, st>>>(
            g, activeVoxels.data(), activeCodes.data(), vertexOffsets.data(), active,
            positions.data(), normals.data());
    LW_CUDA_LAUNCHED("mc::generateVertices");
    mc::generateTriangles<T>
        <<<blocksFor(active, tuning::kActiveBlock), tuning::kActiveBlock, 0, st>>>(
            g, bitmap(), activeVoxels.data(), activeCodes.data(), vertexOffsets.data(),
            triangleOffsets.data(), active, indices.data());
    LW_CUDA_LAUNCHED("mc::generateTriangles");
    LW_RETURN_IF_FAILED(timers[3].stop(st));
    LW_CUDA_TRY(cudaStreamSynchronize(st), "mc::generate");

    mesh.positions = positions.data();
    mesh.normals = normals.data();
    mesh.indices = indices.data();
    mesh.vertexCount = vertexTotal;
    mesh.triangleCount = triangleTotal;
    return CudaStatus::success();
}

template <typename T>
CudaStatus MarchingCubesCuda::Impl::classifyTyped(double iso, CountWait wait) {
    cudaStream_t st = stream.get();
    const mc::Grid<T> g = grid<T>(iso);
    LW_RETURN_IF_FAILED(timers[0].start(st));
    LW_RETURN_IF_FAILED(markBricksTyped<T>(g));
    LW_RETURN_IF_FAILED(timers[0].stop(st));
    mesh = DeviceMeshView();
    LW_RETURN_IF_FAILED(timers[1].start(st));
    LW_RETURN_IF_FAILED(classifyGrid<T>(g, wait));
    LW_RETURN_IF_FAILED(timers[1].stop(st));
    if (wait == CountWait::Now) // the wait has landed the border flag's copy too
        mesh.touchesBorder = count(kBorderSlot) != 0;
    return CudaStatus::success();
}

template <typename T> CudaStatus MarchingCubesCuda::Impl::extractTyped(double iso) {
    LW_RETURN_IF_FAILED(classifyTyped<T>(iso, CountWait::Pending));
    LW_RETURN_IF_FAILED(generate<T>(grid<T>(iso)));
    LW_CUDA_TRY(cudaStreamSynchronize(stream.get()), "mc::extract");
    mesh.touchesBorder = count(kBorderSlot) != 0;
    times = McCudaTimes{timers[0].ms(), timers[1].ms(), activeCount ? timers[2].ms() : 0.0,
                        activeCount ? timers[3].ms() : 0.0};
    return CudaStatus::success();
}

CudaStatus MarchingCubesCuda::setStreamedVolume(const VolumeView& host,
                                                const VoxelGridSetup& setup) {
    Impl& s = *m_impl;
    s.mesh = DeviceMeshView();
    s.activeCount = 0;
    const glm::ivec3 d = host.dims;
    LW_RETURN_IF_FAILED(needsCells(d, "marching cubes (CUDA, streamed)"));
    if (std::size_t(d.x) * std::size_t(d.y) * 4 >= std::numeric_limits<std::uint32_t>::max())
        return CudaStatus::failure(CudaStatus::Code::TooLarge, "marching cubes (CUDA, streamed)",
                                   "slices of more than 2^30 voxels");
    LW_RETURN_IF_FAILED(mc::uploadTables());
    LW_RETURN_IF_FAILED(s.stream.create());
    LW_RETURN_IF_FAILED(s.uploadStream.create());
    for (cudaEvent_t& e : s.uploaded)
        if (!e)
            LW_CUDA_TRY(cudaEventCreateWithFlags(&e, cudaEventDisableTiming), "cudaEventCreate");
    // The whole-volume buffers go: streaming exists to stay under a memory budget.
    s.voxels.release();
    s.brickMinMax.release();
    s.brickActive.release();
    s.releaseScratch();
    s.unregisterHost();
    s.volume = host;
    s.streamed = true;
    s.hostVoxels = host.voxels;
    // Page-locking the volume lets every slab go up with one asynchronous copy. Where the driver
    // refuses (limits on locked memory), slabs are staged through two pinned buffers instead.
    const cudaError_t registered = cudaHostRegister(const_cast<void*>(host.voxels),
                                                    host.byteCount(), cudaHostRegisterReadOnly);
    s.hostRegistered = registered == cudaSuccess;
    if (!s.hostRegistered)
        cudaGetLastError();
    LW_RETURN_IF_FAILED(s.uploadGridTables(setup));
    s.peakBytes = 0;
    s.notePeak();
    return CudaStatus::success();
}

MarchingCubesCuda::Impl::SlabBox MarchingCubesCuda::Impl::slabBoxOf(const CellSlab& slab) const {
    const glm::ivec3 d = volume.dims;
    const auto apron = [](glm::ivec2 cells, int voxels) {
        return glm::ivec2(cells.x > 0 ? cells.x - 1 : 0,
                          cells.y + 2 < voxels ? cells.y + 2 : voxels);
    };
    const glm::ivec2 y = apron(slab.rows, d.y), z = apron(slab.layers, d.z);
    return SlabBox{glm::ivec3(0, y.x, z.x), glm::ivec3(d.x, y.y, z.y)};
}

CudaStatus MarchingCubesCuda::Impl::uploadSlab(int slot, const SlabBox& box) {
    // Per slice of the box one contiguous run (rows box.begin.y .. box.end.y, whole x): a 2D copy
    // with the host's slice pitch; slices the crop leaves whole make it one contiguous copy.
    const std::size_t row = std::size_t(volume.dims.x) * voxelKindSize(volume.kind);
    const std::size_t slicePitch = row * std::size_t(volume.dims.y);
    const std::size_t run = row * std::size_t(box.end.y - box.begin.y);
    const std::size_t slices = std::size_t(box.end.z - box.begin.z);
    const std::size_t bytes = run * slices;
    const unsigned char* source = static_cast<const unsigned char*>(hostVoxels) +
                                  std::size_t(box.begin.z) * slicePitch +
                                  std::size_t(box.begin.y) * row;
    std::size_t sourcePitch = slicePitch;
    LW_RETURN_IF_FAILED(slabBox[slot].reserve(bytes, "cudaMalloc(slab)"));
    if (!hostRegistered) {
        // The staging buffer of this slot may still feed the upload of two slabs ago.
        LW_CUDA_TRY(cudaEventSynchronize(uploaded[slot]), "cudaEventSynchronize(upload)");
        LW_RETURN_IF_FAILED(staging[slot].reserve(bytes, "cudaMallocHost(staging)"));
        for (std::size_t k = 0; k < slices; ++k)
            std::memcpy(staging[slot].data() + k * run, source + k * slicePitch, run);
        source = staging[slot].data();
        sourcePitch = run;
    }
    LW_CUDA_TRY(cudaMemcpy2DAsync(slabBox[slot].data(), run, source, sourcePitch, run, slices,
                                  cudaMemcpyHostToDevice, uploadStream.get()),
                "cudaMemcpy(slab)");
    LW_CUDA_TRY(cudaEventRecord(uploaded[slot], uploadStream.get()), "cudaEventRecord(upload)");
    notePeak();
    return CudaStatus::success();
}

template <typename T>
CudaStatus
MarchingCubesCuda::Impl::extractSlabsTyped(double iso, const std::vector<CellSlab>& slabs,
                                           const MarchingCubesCuda::SlabCallback& onSlab) {
    if (!slabs.empty())
        LW_RETURN_IF_FAILED(uploadSlab(0, slabBoxOf(slabs[0])));
    for (std::size_t k = 0; k < slabs.size(); ++k) {
        const int slot = int(k % 2);
        if (k + 1 < slabs.size()) // slot (k + 1) % 2 held slab k - 1, whose extraction has finished
            LW_RETURN_IF_FAILED(uploadSlab(int((k + 1) % 2), slabBoxOf(slabs[k + 1])));
        LW_CUDA_TRY(cudaStreamWaitEvent(stream.get(), uploaded[slot], 0), "cudaStreamWaitEvent");
        const SlabBox box = slabBoxOf(slabs[k]);
        const CellSlab& cells = slabs[k];
        const mc::Grid<T> g =
            brickGrid<T>(iso, reinterpret_cast<const T*>(slabBox[slot].data()), box.begin, box.end,
                         glm::ivec3(0, cells.rows.x, cells.layers.x),
                         glm::ivec3(volume.dims.x - 1, cells.rows.y, cells.layers.y));
        mesh = DeviceMeshView();
        LW_RETURN_IF_FAILED(classifyGrid<T>(g, CountWait::Now));
        LW_RETURN_IF_FAILED(generate<T>(g));
        notePeak();
        if (mesh.triangleCount > 0)
            LW_RETURN_IF_FAILED(onSlab(k, mesh));
    }
    return CudaStatus::success();
}

CudaStatus MarchingCubesCuda::extractSlabs(double storedIso, const std::vector<CellSlab>& slabs,
                                           const SlabCallback& onSlab) {
    Impl& s = *m_impl;
    if (!s.streamed)
        return CudaStatus::failure(CudaStatus::Code::Failed, "marching cubes (CUDA, streamed)",
                                   "no volume: call setStreamedVolume first");
    const glm::ivec3 cells = s.volume.dims - 1;
    for (const CellSlab& slab : slabs)
        if (slab.layers.x < 0 || slab.layers.y <= slab.layers.x || slab.layers.y > cells.z ||
            slab.rows.x < 0 || slab.rows.y <= slab.rows.x || slab.rows.y > cells.y)
            return CudaStatus::failure(CudaStatus::Code::Failed, "marching cubes (CUDA, streamed)",
                                       "a slab's cell layers or rows are out of range");
    return dispatchVoxelKind(s.volume.kind, [&](auto zero) {
        return s.extractSlabsTyped<decltype(zero)>(storedIso, slabs, onSlab);
    });
}

std::size_t MarchingCubesCuda::peakDeviceBytes() const {
    return m_impl->peakBytes;
}

void MarchingCubesCuda::release() {
    // A fresh state: every DeviceBuffer, event and stream frees itself; the host registration is
    // undone by the destructor.
    m_impl = std::make_unique<Impl>();
}

CudaStatus MarchingCubesCuda::classify(double storedIso) {
    Impl& s = *m_impl;
    if (!s.volume.voxels)
        return CudaStatus::failure(CudaStatus::Code::Failed, "marching cubes (CUDA)",
                                   "no volume: call setVolume first");
    s.mesh = DeviceMeshView();
    return dispatchVoxelKind(s.volume.kind, [&](auto zero) -> CudaStatus {
        LW_RETURN_IF_FAILED(s.classifyTyped<decltype(zero)>(storedIso, Impl::CountWait::Now));
        LW_CUDA_TRY(cudaStreamSynchronize(s.stream.get()), "mc::classify");
        return CudaStatus::success();
    });
}

CudaStatus MarchingCubesCuda::download(std::vector<glm::vec3>& positions,
                                       std::vector<glm::vec3>& normals,
                                       std::vector<std::uint32_t>& indices) const {
    const DeviceMeshView& m = m_impl->mesh;
    positions.resize(m.vertexCount);
    normals.resize(m.vertexCount);
    indices.resize(m.triangleCount * 3);
    if (m.vertexCount > 0) {
        LW_CUDA_TRY(cudaMemcpy(positions.data(), m.positions, m.vertexCount * sizeof(glm::vec3),
                               cudaMemcpyDeviceToHost),
                    "cudaMemcpy(positions)");
        LW_CUDA_TRY(cudaMemcpy(normals.data(), m.normals, m.vertexCount * sizeof(glm::vec3),
                               cudaMemcpyDeviceToHost),
                    "cudaMemcpy(normals)");
    }
    if (m.triangleCount > 0)
        LW_CUDA_TRY(cudaMemcpy(indices.data(), m.indices,
                               m.triangleCount * 3 * sizeof(std::uint32_t), cudaMemcpyDeviceToHost),
                    "cudaMemcpy(indices)");
    return CudaStatus::success();
}

} // namespace lw::kernels::cuda
