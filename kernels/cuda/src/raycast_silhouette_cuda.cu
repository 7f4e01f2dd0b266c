// Host dispatch of method 2 on the GPU (kernels in raycast_kernels.cuh).

#include "lw/kernels/cuda/device_mesh_store.h"
#include "lw/kernels/cuda/raycast_silhouette_cuda.h"
#include "marching_cubes_impl.cuh"
#include "raycast_kernels.cuh"
#include "stroke_pruning.h"

#include <algorithm>
#include <cub/device/device_radix_sort.cuh>
#include <cub/device/device_select.cuh>
#include <limits>
#include <thrust/iterator/counting_iterator.h>
#include <utility>

namespace lw::kernels::cuda {

namespace {

// Marching cubes over the whole volume indexes voxels with 32 bits; a larger volume (2048^3:
// 8.6 G voxels) goes through it in slabs instead (see RayCastSilhouetteCuda::Impl::slabbed).
constexpr std::size_t kWholeVolumeVoxelLimit = std::numeric_limits<std::uint32_t>::max() - 1024;
// A slab's box on the device, at most (two of them: one extracting, one uploading).
constexpr std::size_t kSlabBoxBytes = std::size_t(512) << 20;

} // namespace

struct RayCastSilhouetteCuda::Impl {
    MarchingCubesCuda marchingCubes;
    // What the rays read: the voxels (on the device, or host memory mapped into its address
    // space) and their grid; the whole volume in every mode.
    const void* rayVoxels = nullptr;
    GridDims rayDims;
    VoxelKind kind = VoxelKind::Int16;
    // Slabbed: a volume of more voxels than whole-volume marching cubes indexes. Its slabs are
    // extracted one by one from host memory (MarchingCubesCuda::extractSlabs) and their meshes
    // kept here; each view takes its segments from every triangle of them, keyed by the
    // triangle's number over all slabs (cell order, as the cells' keys are). The rays read the
    // volume mapped from host memory.
    bool slabbed = false;
    bool raysReadHostMemory = false; // mapped, or slabbed
    int slabLayers = 0;              // setSlabLayers: cell layers per slab (0: from kSlabBoxBytes)
    DeviceMeshStore slabMeshes;
    std::vector<std::size_t> slabFirstTriangle;
    std::size_t slabTriangles = 0;
    RayGridSetup rayGrid;
    DeviceBuffer<double> rayOffsets;
    DeviceBuffer<float> macroMaxima; // per macro cell, per volume (rc::macroMaximum)
    DeviceBuffer<std::uint8_t> macroOccupied, coarseOccupied;
    glm::ivec3 macroDims{0}, coarseDims{0};
    DeviceBuffer<std::uint8_t> mask;
    MaskDownload download;
    DeviceBuffer<rc::Counters> counters;
    DeviceBuffer<SegmentEndpoints> segments;  // phase 1's output, grown on demand
    DeviceBuffer<std::uint32_t> segmentCells; // each segment's cell (voxel index): the sort key
    DeviceBuffer<SegmentEndpoints> sortedSegments;
    DeviceBuffer<std::uint32_t> sortedCells;
    DeviceBuffer<float> vertexDistance; // per vertex of the kept mesh, per view
    DeviceBuffer<unsigned char> sortTemp;
    DeviceBuffer<std::uint8_t> visible; // phase 2's, a flag per representative endpoint
    // Phase 2's endpoint dedupe: the table, each endpoint's representative, the representatives'
    // list and count (and the flags the list is selected by, from the endpoints' numbers).
    DeviceBuffer<unsigned long long> endpointTable;
    DeviceBuffer<std::uint32_t> representative, representatives, representativeCount;
    // Phase 2b's: the next representative a lane takes (rc::testRepresentatives).
    DeviceBuffer<std::uint32_t> nextRay;
    unsigned rayBlocks = 0; // the ray launch's blocks: as many as are resident on the device
    DeviceBuffer<std::uint8_t> isRepresentative;
    StrokePruning pruning;
    double iso = 0.0;
    bool prepared = false;
    bool keepMesh = true;  // setKeepCellMesh
    bool meshKept = false; // phase 1 reads the cells' mesh, not the voxels (findActiveCells)
    dispatch::StageTimer prepareTimer, renderTimer;

    MarchingCubesCuda::Impl& mc() { return marchingCubes.implementation(); }

    template <typename T> CudaStatus findMacroMaxima();
    CudaStatus placeVolume(const VolumeView& host, const VoxelGridSetup& setup, bool mapped,
                           const void* deviceVoxels);
    std::vector<CellSlab> slabPlan() const;
    CudaStatus extractSlabs(double storedIso);
    CudaStatus findSlabSegments(const rc::View& view, std::uint32_t capacity);
    CudaStatus findMeshSegments(const DeviceMeshView& mesh, std::uint32_t firstTriangle,
                                const rc::View& view, std::uint32_t capacity);
    bool hasSurface() { return slabbed ? slabTriangles > 0 : mc().activeCount > 0; }
    template <typename T> CudaStatus findActiveCells(double storedIso);
    template <typename T> CudaStatus prepareTyped(double storedIso, RayCastCudaFrame& frame);
    template <typename T>
    CudaStatus renderTyped(const rc::View& view, const RayCastCudaSettings& settings,
                           std::uint8_t* hostMask, RayCastCudaFrame& frame,
                           const SegmentEndpoints* extra, std::size_t extraCount);
    template <typename T> CudaStatus findSegments(const rc::View& view, rc::Counters& counts);
    template <typename T> CudaStatus testAndDraw(const rc::View& view, std::uint32_t count);
    template <typename T>
    CudaStatus testRepresentativeEndpoints(const RayVisibility<T>& rule, const rc::View& view,
                                           std::uint32_t count);
};

RayCastSilhouetteCuda::RayCastSilhouetteCuda() : m_impl(std::make_unique<Impl>()) {}
RayCastSilhouetteCuda::~RayCastSilhouetteCuda() = default;

void RayCastSilhouetteCuda::release() {
    m_impl = std::make_unique<Impl>();
}

void RayCastSilhouetteCuda::setGradientStencil(GradientStencil stencil) {
    m_impl->marchingCubes.setGradientStencil(stencil);
}

void RayCastSilhouetteCuda::setKeepCellMesh(bool keep) {
    m_impl->keepMesh = keep;
    m_impl->prepared = false;
}

double RayCastSilhouetteCuda::uploadMs() const {
    return m_impl->marchingCubes.uploadMs();
}

std::size_t RayCastSilhouetteCuda::deviceBytes() const {
    const Impl& s = *m_impl;
    return s.marchingCubes.deviceBytes() + s.slabMeshes.deviceBytes() + s.rayOffsets.bytes() +
           s.macroMaxima.bytes() + s.macroOccupied.bytes() + s.coarseOccupied.bytes() +
           s.mask.bytes() + s.counters.bytes() + s.segments.bytes() + s.segmentCells.bytes() +
           s.sortedSegments.bytes() + s.sortedCells.bytes() + s.vertexDistance.bytes() +
           s.sortTemp.bytes() + s.visible.bytes() + s.pruning.deviceBytes() +
           s.endpointTable.bytes() + s.representative.bytes() + s.representatives.bytes() +
           s.representativeCount.bytes() + s.isRepresentative.bytes() + s.nextRay.bytes();
}

bool RayCastSilhouetteCuda::readsHostMemory() const {
    return m_impl->raysReadHostMemory;
}

CudaStatus RayCastSilhouetteCuda::setVolume(const VolumeView& hostVolume,
                                            const VoxelGridSetup& setup,
                                            const RayGridSetup& rayGrid, bool mapped,
                                            const void* deviceVoxels) {
    Impl& s = *m_impl;
    s.prepared = false;
    // This translation unit's copy of the constant tables (see marching_cubes_kernels.cuh).
    LW_RETURN_IF_FAILED(mc::uploadTables());
    LW_RETURN_IF_FAILED(s.placeVolume(hostVolume, setup, mapped, deviceVoxels));
    s.rayGrid = rayGrid;
    LW_RETURN_IF_FAILED(s.rayOffsets.reserve(rayGrid.offsets.size(), "cudaMalloc(rayOffsets)"));
    // On the rays' stream, as marching cubes' grid tables (see uploadGridTables).
    LW_CUDA_TRY(cudaMemcpyAsync(s.rayOffsets.data(), rayGrid.offsets.data(),
                                rayGrid.offsets.size() * sizeof(double), cudaMemcpyHostToDevice,
                                s.mc().stream.get()),
                "cudaMemcpy(rayOffsets)");
    s.rayGrid.view.offsets = s.rayOffsets.data();
    s.rayGrid.view.offsetCount = int(rayGrid.offsets.size());
    const glm::ivec3 cells = glm::max(hostVolume.dims - 1, glm::ivec3(0));
    const int n = RayVisibilityRule::kMacroCells;
    s.macroDims = (cells + n - 1) / n;
    const std::size_t macroCount =
        std::size_t(s.macroDims.x) * std::size_t(s.macroDims.y) * std::size_t(s.macroDims.z);
    LW_RETURN_IF_FAILED(s.macroMaxima.reserve(macroCount, "cudaMalloc(macroMaxima)"));
    LW_RETURN_IF_FAILED(s.macroOccupied.reserve(macroCount, "cudaMalloc(macroOccupied)"));
    s.coarseDims = coarseDimsOf(s.macroDims);
    const std::size_t coarseCount =
        std::size_t(s.coarseDims.x) * std::size_t(s.coarseDims.y) * std::size_t(s.coarseDims.z);
    LW_RETURN_IF_FAILED(s.coarseOccupied.reserve(coarseCount, "cudaMalloc(coarseOccupied)"));
    LW_RETURN_IF_FAILED(s.counters.reserve(1, "cudaMalloc(counters)"));
    return dispatchVoxelKind(s.kind,
                             [&](auto zero) { return s.findMacroMaxima<decltype(zero)>(); });
}

// The voxels where marching cubes and the rays read them: on the device, mapped from host
// memory, or (slabbed) streamed to marching cubes by slab and mapped for the rays.
CudaStatus RayCastSilhouetteCuda::Impl::placeVolume(const VolumeView& host,
                                                    const VoxelGridSetup& setup, bool mapped,
                                                    const void* deviceVoxels) {
    slabMeshes.clear();
    slabFirstTriangle.clear();
    slabTriangles = 0;
    kind = host.kind;
    rayDims = makeGridDims(host.dims);
    slabbed = slabLayers > 0 || host.voxelCount() >= kWholeVolumeVoxelLimit;
    raysReadHostMemory = mapped || slabbed;
    if (!slabbed) {
        VolumeView onDevice = host;
        onDevice.voxels = deviceVoxels;
        LW_RETURN_IF_FAILED(mapped         ? marchingCubes.setMappedVolume(host, setup)
                            : deviceVoxels ? marchingCubes.setDeviceVolume(onDevice, setup)
                                           : marchingCubes.setVolume(host, setup));
        rayVoxels = mc().volume.voxels;
        return CudaStatus::success();
    }
    LW_RETURN_IF_FAILED(marchingCubes.setStreamedVolume(host, setup));
    // setStreamedVolume page-locked the volume; with unified addressing that maps it too.
    void* device = nullptr;
    const cudaError_t found = cudaHostGetDevicePointer(&device, const_cast<void*>(host.voxels), 0);
    if (found != cudaSuccess) {
        cudaGetLastError();
        return CudaStatus::failure(CudaStatus::Code::Failed, "method 2 (CUDA)",
                                   "a volume of more than 2^32 voxels is read from host memory, "
                                   "and this device cannot map it: " +
                                       std::string(cudaGetErrorString(found)));
    }
    rayVoxels = device;
    return CudaStatus::success();
}

template <typename T> CudaStatus RayCastSilhouetteCuda::Impl::findMacroMaxima() {
    MarchingCubesCuda::Impl& m = mc();
    const std::size_t macroCount =
        std::size_t(macroDims.x) * std::size_t(macroDims.y) * std::size_t(macroDims.z);
    rc::macroMaximum<T><<<blocksFor(macroCount, 128), 128, 0, m.stream.get()>>>(
        static_cast<const T*>(rayVoxels), rayDims, macroDims, macroMaxima.data());
    LW_CUDA_LAUNCHED("rc::macroMaximum");
    LW_CUDA_TRY(cudaStreamSynchronize(m.stream.get()), "rc::macroMaximum");
    return CudaStatus::success();
}

// The active cells at a new iso-value, and their mesh where the device holds it: every view's
// segments then come from the mesh (rc::findTriangleSegments), which on a volume mapped from host
// memory saves reading the active cells' voxels over the bus at every view (73 of 109 ms at
// 1024x1024x2048 on the H200) and on a resident one most of phase 1. Without room for the mesh
// the segments come from the voxels as before.
template <typename T> CudaStatus RayCastSilhouetteCuda::Impl::findActiveCells(double storedIso) {
    MarchingCubesCuda::Impl& m = mc();
    meshKept = false;
    if (!keepMesh)
        return m.classifyTyped<T>(storedIso, MarchingCubesCuda::Impl::CountWait::Now);
    const CudaStatus extracted = m.extractTyped<T>(storedIso);
    if (extracted.ok()) {
        meshKept = true;
        return extracted;
    }
    if (extracted.code != CudaStatus::Code::OutOfMemory)
        return extracted;
    cudaGetLastError(); // an allocation's failure, not sticky: the voxel path needs no mesh
    m.positions.release();
    m.normals.release();
    m.indices.release();
    return m.classifyTyped<T>(storedIso, MarchingCubesCuda::Impl::CountWait::Now);
}

template <typename T>
CudaStatus RayCastSilhouetteCuda::Impl::prepareTyped(double storedIso, RayCastCudaFrame& frame) {
    MarchingCubesCuda::Impl& m = mc();
    cudaStream_t st = m.stream.get();
    LW_RETURN_IF_FAILED(prepareTimer.start(st));
    LW_RETURN_IF_FAILED(slabbed ? extractSlabs(storedIso) : findActiveCells<T>(storedIso));
    const std::size_t macroCount =
        std::size_t(macroDims.x) * std::size_t(macroDims.y) * std::size_t(macroDims.z);
    rc::macroOccupancy<<<blocksFor(macroCount, 128), 128, 0, st>>>(
        macroMaxima.data(), std::uint32_t(macroCount), insideThreshold(storedIso),
        macroOccupied.data());
    LW_CUDA_LAUNCHED("rc::macroOccupancy");
    const std::size_t coarseCount =
        std::size_t(coarseDims.x) * std::size_t(coarseDims.y) * std::size_t(coarseDims.z);
    rc::coarseOccupancyOf<<<blocksFor(coarseCount, 128), 128, 0, st>>>(
        macroOccupied.data(), macroDims, coarseDims, coarseOccupied.data());
    LW_CUDA_LAUNCHED("rc::coarseOccupancyOf");
    LW_RETURN_IF_FAILED(prepareTimer.stop(st));
    LW_CUDA_TRY(cudaStreamSynchronize(st), "rc::prepare");
    frame.prepareMs = prepareTimer.ms();
    iso = storedIso;
    prepared = true;
    return CudaStatus::success();
}

CudaStatus RayCastSilhouetteCuda::prepare(double storedIso, RayCastCudaFrame& frame) {
    Impl& s = *m_impl;
    s.prepared = false;
    if (!s.rayVoxels)
        return CudaStatus::failure(CudaStatus::Code::Failed, "method 2 (CUDA)",
                                   "no volume: call setVolume first");
    return dispatchVoxelKind(
        s.kind, [&](auto zero) { return s.prepareTyped<decltype(zero)>(storedIso, frame); });
}

// Phase 1: the segments of the active cells into `segments` (sorted by cell for the rays).
template <typename T>
CudaStatus RayCastSilhouetteCuda::Impl::findSegments(const rc::View& view, rc::Counters& counts) {
    MarchingCubesCuda::Impl& m = mc();
    cudaStream_t st = m.stream.get();
    // Run again with a larger buffer when the segments did not fit.
    for (int attempt = 0; attempt < 2; ++attempt) {
        LW_CUDA_TRY(cudaMemsetAsync(counters.data(), 0, sizeof(rc::Counters), st),
                    "cudaMemset(counters)");
        const std::uint32_t capacity =
            std::uint32_t(std::min(segments.capacity(), segmentCells.capacity()));
        const std::uint32_t blocks = blocksFor(m.activeCount, tuning::kRayCastBlock);
        if (slabbed) {
            LW_RETURN_IF_FAILED(findSlabSegments(view, capacity));
        } else if (meshKept) {
            LW_RETURN_IF_FAILED(findMeshSegments(m.mesh, 0, view, capacity));
        } else {
            rc::findSegments<T><<<blocks, tuning::kRayCastBlock, 0, st>>>(
                m.grid<T>(iso), m.activeVoxels.data(), m.activeCodes.data(), m.activeCount, view,
                segments.data(), segmentCells.data(), capacity, counters.data());
            LW_CUDA_LAUNCHED("rc::findSegments");
        }
        LW_CUDA_TRY(
            cudaMemcpyAsync(&counts, counters.data(), sizeof counts, cudaMemcpyDeviceToHost, st),
            "cudaMemcpy(counters)");
        LW_CUDA_TRY(cudaStreamSynchronize(st), "rc::findSegments");
        if (counts.segments <= std::min(segments.capacity(), segmentCells.capacity()))
            break;
        LW_RETURN_IF_FAILED(segments.reserve(std::size_t(counts.segments), "cudaMalloc(segments)"));
        LW_RETURN_IF_FAILED(
            segmentCells.reserve(std::size_t(counts.segments), "cudaMalloc(segmentCells)"));
    }
    const std::uint32_t found = std::uint32_t(counts.segments);
    // The segments were appended in whatever order the cells' threads finished: sorted by cell,
    // neighbouring rays (similar paths through the grid toward the eye) share warps.
    if (found > 1 && view.visibility) {
        LW_RETURN_IF_FAILED(sortedSegments.reserve(found, "cudaMalloc(sortedSegments)"));
        LW_RETURN_IF_FAILED(sortedCells.reserve(found, "cudaMalloc(sortedCells)"));
        std::size_t bytes = 0;
        // The key: the triangle's number on a kept mesh (whose triangles are in cell order),
        // else the cell's voxel index.
        const std::uint32_t keyLimit = slabbed    ? std::uint32_t(slabTriangles)
                                       : meshKept ? std::uint32_t(m.mesh.triangleCount)
                                                  : m.activeVoxelLimit();
        const int keyBits = 32 - __builtin_clz(std::max(keyLimit, 1u));
        LW_CUDA_TRY(cub::DeviceRadixSort::SortPairs(nullptr, bytes, segmentCells.data(),
                                                    sortedCells.data(), segments.data(),
                                                    sortedSegments.data(), found, 0, keyBits, st),
                    "cub::DeviceRadixSort(segments)");
        LW_RETURN_IF_FAILED(sortTemp.reserve(bytes, "cudaMalloc(sortTemp)"));
        LW_CUDA_TRY(cub::DeviceRadixSort::SortPairs(sortTemp.data(), bytes, segmentCells.data(),
                                                    sortedCells.data(), segments.data(),
                                                    sortedSegments.data(), found, 0, keyBits, st),
                    "cub::DeviceRadixSort(segments)");
        swap(segments, sortedSegments); // dispatch::swap (ADL): the buffers trade places
    }
    return CudaStatus::success();
}

// Phase 2: the first `count` segments tested (per endpoint or along the segment) and drawn.
template <typename T>
CudaStatus RayCastSilhouetteCuda::Impl::testAndDraw(const rc::View& view, std::uint32_t count) {
    cudaStream_t st = mc().stream.get();
    RayVisibility<T> rule;
    rule.voxels = static_cast<const T*>(rayVoxels);
    rule.dims = rayDims;
    rule.grid = rayGrid.view;
    rule.macroOccupied = macroOccupied.data();
    rule.macroDims = macroDims;
    rule.coarseOccupied = coarseOccupied.data();
    rule.coarseDims = coarseDims;
    rule.cellScale = rayGrid.cellScale;
    rule.neighbourReach = rayGrid.neighbourReach;
    rule.iso = iso;
    rule.pixelSpan = view.pixelSpan;
    if (view.visibility && view.alongSegment) {
        rc::drawAlongSegments<T><<<blocksFor(count, tuning::kRayBlock), tuning::kRayBlock, 0, st>>>(
            rule, view, segments.data(), count, mask.data());
        LW_CUDA_LAUNCHED("rc::drawAlongSegments");
        return CudaStatus::success();
    }
    const std::uint8_t* visibleFlags = nullptr;
    if (view.visibility) {
        LW_RETURN_IF_FAILED(testRepresentativeEndpoints<T>(rule, view, count));
        visibleFlags = visible.data();
    }
    rc::drawSegments<<<blocksFor(count, tuning::kVertexBlock), tuning::kVertexBlock, 0, st>>>(
        view, segments.data(), count, visibleFlags, representative.data(), mask.data());
    LW_CUDA_LAUNCHED("rc::drawSegments");
    return CudaStatus::success();
}

// Phase 2: the visibility of the first `count` segments' endpoints, one ray per point and the
// neighbour rays apart (phases 2a-2c in raycast_kernels.cuh) into `visible`, each endpoint's
// representative into `representative`.
template <typename T>
CudaStatus RayCastSilhouetteCuda::Impl::testRepresentativeEndpoints(const RayVisibility<T>& rule,
                                                                    const rc::View& view,
                                                                    std::uint32_t count) {
    cudaStream_t st = mc().stream.get();
    const std::size_t endpoints = 2 * std::size_t(count);
    // CUB's item counts are int: at most INT_MAX endpoints (the table's mask then fits 32 bits).
    if (endpoints > std::size_t(std::numeric_limits<int>::max()))
        return CudaStatus::failure(CudaStatus::Code::Failed, "rc::findRepresentatives",
                                   "more segment endpoints than CUB's int item count can hold");
    std::size_t slots = 1024;
    while (slots < 2 * endpoints)
        slots *= 2;
    LW_RETURN_IF_FAILED(endpointTable.reserve(slots, "cudaMalloc(endpointTable)"));
    LW_RETURN_IF_FAILED(representative.reserve(endpoints, "cudaMalloc(representative)"));
    LW_RETURN_IF_FAILED(representatives.reserve(endpoints, "cudaMalloc(representatives)"));
    LW_RETURN_IF_FAILED(isRepresentative.reserve(endpoints, "cudaMalloc(isRepresentative)"));
    LW_RETURN_IF_FAILED(visible.reserve(endpoints, "cudaMalloc(visible)"));
    LW_RETURN_IF_FAILED(representativeCount.reserve(1, "cudaMalloc(representativeCount)"));
    LW_RETURN_IF_FAILED(nextRay.reserve(1, "cudaMalloc(nextRay)"));
    LW_CUDA_TRY(cudaMemsetAsync(endpointTable.data(), 0xff, slots * sizeof(unsigned long long), st),
                "cudaMemset(endpointTable)");
    const unsigned blocks = blocksFor(endpoints, tuning::kRayBlock);
    rc::findRepresentatives<<<blocks, tuning::kRayBlock, 0, st>>>(
        segments.data(), std::uint32_t(endpoints), endpointTable.data(), std::uint32_t(slots - 1),
        representative.data(), isRepresentative.data());
    LW_CUDA_LAUNCHED("rc::findRepresentatives");
    // The representatives' list, in endpoint order: the endpoints' numbers (counted, not
    // stored) selected by their flags.
    const thrust::counting_iterator<std::uint32_t> endpointNumbers(0);
    std::size_t bytes = 0;
    LW_CUDA_TRY(cub::DeviceSelect::Flagged(nullptr, bytes, endpointNumbers, isRepresentative.data(),
                                           representatives.data(), representativeCount.data(),
                                           endpoints, st),
                "cub::DeviceSelect(representatives)");
    LW_RETURN_IF_FAILED(sortTemp.reserve(bytes, "cudaMalloc(selectTemp)"));
    LW_CUDA_TRY(cub::DeviceSelect::Flagged(sortTemp.data(), bytes, endpointNumbers,
                                           isRepresentative.data(), representatives.data(),
                                           representativeCount.data(), endpoints, st),
                "cub::DeviceSelect(representatives)");
    LW_CUDA_TRY(cudaMemsetAsync(nextRay.data(), 0, sizeof(std::uint32_t), st),
                "cudaMemset(nextRay)");
    if (rayBlocks == 0)
        LW_RETURN_IF_FAILED(
            dispatch::residentBlocks(rc::testRepresentatives<T>, tuning::kRayBlock, rayBlocks));
    // Rays through device memory: as many lanes as the device holds, each taking ray after ray.
    // Rays through host memory (mapped): a thread per ray, neighbours in one warp from start to
    // end -- their reads over the bus share cache lines, which lanes taking scattered rays do not
    // (1024x1024x2048 mapped on the H200: 27.5 ms a view against 55-58).
    const bool takeMore = !raysReadHostMemory;
    const unsigned grid = takeMore ? std::min(rayBlocks, blocks) : blocks;
    // The block size is a multiple of the warp: every lane of a warp reaches the ballots.
    static_assert(tuning::kRayBlock % 32 == 0);
    rc::testRepresentatives<T><<<grid, tuning::kRayBlock, 0, st>>>(
        rule, view, segments.data(), representatives.data(), representativeCount.data(),
        nextRay.data(), takeMore, visible.data());
    LW_CUDA_LAUNCHED("rc::testRepresentatives");
    return CudaStatus::success();
}

template <typename T>
CudaStatus
RayCastSilhouetteCuda::Impl::renderTyped(const rc::View& view, const RayCastCudaSettings& settings,
                                         std::uint8_t* hostMask, RayCastCudaFrame& frame,
                                         const SegmentEndpoints* extra, std::size_t extraCount) {
    MarchingCubesCuda::Impl& m = mc();
    cudaStream_t st = m.stream.get();
    const std::size_t pixels = std::size_t(view.camera.width > 0 ? view.camera.width : 0) *
                               std::size_t(view.camera.height > 0 ? view.camera.height : 0);
    LW_RETURN_IF_FAILED(mask.reserve(pixels > 0 ? pixels : 1, "cudaMalloc(mask)"));
    LW_RETURN_IF_FAILED(renderTimer.start(st));
    LW_CUDA_TRY(cudaMemsetAsync(mask.data(), 0, pixels, st), "cudaMemset(mask)");
    rc::Counters counts{};
    if (hasSurface())
        LW_RETURN_IF_FAILED(findSegments<T>(view, counts));
    const std::size_t found = std::size_t(counts.segments);
    if (extra && extraCount > 0) {
        // After the sort: the extra segments keep their order behind the cells' ones.
        if (segments.capacity() < found + extraCount) {
            LW_RETURN_IF_FAILED(sortedSegments.reserve(found + extraCount, "cudaMalloc(segments)"));
            LW_CUDA_TRY(cudaMemcpyAsync(sortedSegments.data(), segments.data(),
                                        found * sizeof(SegmentEndpoints), cudaMemcpyDeviceToDevice,
                                        st),
                        "cudaMemcpy(segments)");
            swap(segments, sortedSegments);
        }
        LW_CUDA_TRY(cudaMemcpyAsync(segments.data() + found, extra,
                                    extraCount * sizeof(SegmentEndpoints), cudaMemcpyHostToDevice,
                                    st),
                    "cudaMemcpy(extraSegments)");
    }
    const std::size_t total = found + (extra ? extraCount : 0);
    if (total > 0)
        LW_RETURN_IF_FAILED(testAndDraw<T>(view, std::uint32_t(total)));
    LW_RETURN_IF_FAILED(pruning.run(mask.data(), view.camera.width, view.camera.height,
                                    settings.minStrokePixels, settings.strokeGapPixels, st));
    LW_RETURN_IF_FAILED(renderTimer.stop(st));
    LW_RETURN_IF_FAILED(download.queue(mask.data(), pixels, st));
    LW_CUDA_TRY(cudaStreamSynchronize(st), "rc::render");
    download.deliver(hostMask);
    frame.renderMs = renderTimer.ms();
    frame.triangles = std::size_t(counts.triangles);
    frame.segments = total;
    return CudaStatus::success();
}

CudaStatus RayCastSilhouetteCuda::render(const PixelCamera& camera, glm::dvec3 eyeOrDirection,
                                         bool orthographic, const RayCastCudaSettings& settings,
                                         std::uint8_t* hostMask, RayCastCudaFrame& frame,
                                         const SegmentEndpoints* extraSegments,
                                         std::size_t extraCount) {
    Impl& s = *m_impl;
    if (!s.prepared)
        return CudaStatus::failure(CudaStatus::Code::Failed, "method 2 (CUDA)",
                                   "render() needs a prepare() first");
    rc::View view;
    view.camera = camera;
    view.eyeOrDirection = eyeOrDirection;
    view.eyeOrDirectionF = glm::vec3(eyeOrDirection);
    view.orthographic = orthographic;
    view.visibility = settings.visibility;
    view.alongSegment = settings.alongSegment;
    view.pixelSpan = rayPixelSpan(camera.halfHeight, camera.height);
    return dispatchVoxelKind(s.kind, [&](auto zero) {
        return s.renderTyped<decltype(zero)>(view, settings, hostMask, frame, extraSegments,
                                             extraCount);
    });
}

// Slabs of whole cell layers whose box (layers plus the gradient apron) stays under
// kSlabBoxBytes, or setSlabLayers' count.
std::vector<CellSlab> RayCastSilhouetteCuda::Impl::slabPlan() const {
    const int cellsZ = rayDims.cz, cellsY = rayDims.cy;
    const std::size_t sliceBytes = rayDims.sz * voxelKindSize(kind);
    int layers = slabLayers;
    if (layers <= 0)
        layers =
            int(std::max<std::size_t>(kSlabBoxBytes / std::max<std::size_t>(sliceBytes, 1), 4) - 3);
    std::vector<CellSlab> slabs;
    for (int first = 0; first < cellsZ; first += layers)
        slabs.push_back(
            CellSlab{glm::ivec2(first, std::min(first + layers, cellsZ)), glm::ivec2(0, cellsY)});
    return slabs;
}

CudaStatus RayCastSilhouetteCuda::Impl::extractSlabs(double storedIso) {
    slabMeshes.clear();
    slabFirstTriangle.clear();
    slabTriangles = 0;
    if (rayDims.cx < 1 || rayDims.cy < 1 || rayDims.cz < 1)
        return CudaStatus::success();
    return marchingCubes.extractSlabs(
        storedIso, slabPlan(), [&](std::size_t, const DeviceMeshView& mesh) {
            if (slabTriangles + mesh.triangleCount >= std::numeric_limits<std::uint32_t>::max())
                return CudaStatus::failure(CudaStatus::Code::TooLarge, "method 2 (CUDA)",
                                           "more than 2^32 triangles");
            LW_RETURN_IF_FAILED(slabMeshes.keep(mesh));
            slabFirstTriangle.push_back(slabTriangles);
            slabTriangles += mesh.triangleCount;
            return CudaStatus::success();
        });
}

// Phase 1 on a kept mesh: its vertices' distances for `view`, then its triangles' segments
// (keyed from `firstTriangle`) into the shared counters.
CudaStatus RayCastSilhouetteCuda::Impl::findMeshSegments(const DeviceMeshView& mesh,
                                                         std::uint32_t firstTriangle,
                                                         const rc::View& view,
                                                         std::uint32_t capacity) {
    cudaStream_t st = mc().stream.get();
    LW_RETURN_IF_FAILED(vertexDistance.reserve(std::max<std::size_t>(mesh.vertexCount, 1),
                                               "cudaMalloc(vertexDistance)"));
    rc::vertexSilhouetteDistances<<<blocksFor(mesh.vertexCount, tuning::kVertexBlock),
                                    tuning::kVertexBlock, 0, st>>>(mesh, view,
                                                                   vertexDistance.data());
    LW_CUDA_LAUNCHED("rc::vertexSilhouetteDistances");
    rc::findTriangleSegments<tuning::kSegmentTriangleBlock>
        <<<blocksFor(mesh.triangleCount, tuning::kSegmentTriangleBlock),
           tuning::kSegmentTriangleBlock, 0, st>>>(mesh, firstTriangle, vertexDistance.data(),
                                                   segments.data(), segmentCells.data(), capacity,
                                                   counters.data());
    LW_CUDA_LAUNCHED("rc::findTriangleSegments");
    return CudaStatus::success();
}

// Phase 1 of a slabbed volume: every kept slab's triangles, into the shared counters.
CudaStatus RayCastSilhouetteCuda::Impl::findSlabSegments(const rc::View& view,
                                                         std::uint32_t capacity) {
    for (std::size_t k = 0; k < slabMeshes.count(); ++k)
        LW_RETURN_IF_FAILED(findMeshSegments(slabMeshes.mesh(k),
                                             std::uint32_t(slabFirstTriangle[k]), view, capacity));
    return CudaStatus::success();
}

void RayCastSilhouetteCuda::setSlabLayers(int layers) {
    m_impl->slabLayers = layers > 0 ? layers : 0;
    m_impl->prepared = false;
}

} // namespace lw::kernels::cuda
