// Host dispatch of method 2 on the GPU (kernels in raycast_kernels.cuh).

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

struct RayCastSilhouetteCuda::Impl {
    MarchingCubesCuda marchingCubes;
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
    DeviceBuffer<unsigned char> sortTemp;
    DeviceBuffer<std::uint8_t> visible; // phase 2's, a flag per representative endpoint
    // Phase 2's endpoint dedupe: the table, each endpoint's representative, the representatives'
    // list and count (and the flags the list is selected by, from the endpoints' numbers).
    DeviceBuffer<unsigned long long> endpointTable;
    DeviceBuffer<std::uint32_t> representative, representatives, representativeCount;
    // Phase 2c's: the points whose own ray was blocked close by.
    DeviceBuffer<std::uint32_t> neighbourList, neighbourCount;
    DeviceBuffer<std::uint8_t> isRepresentative;
    StrokePruning pruning;
    double iso = 0.0;
    bool prepared = false;
    bool keepMesh = true;  // setKeepCellMesh
    bool meshKept = false; // phase 1 reads the cells' mesh, not the voxels (findActiveCells)
    dispatch::StageTimer prepareTimer, renderTimer;

    MarchingCubesCuda::Impl& mc() { return marchingCubes.implementation(); }

    template <typename T> CudaStatus findMacroMaxima();
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
    return s.marchingCubes.deviceBytes() + s.rayOffsets.bytes() + s.macroMaxima.bytes() +
           s.macroOccupied.bytes() + s.coarseOccupied.bytes() + s.mask.bytes() +
           s.counters.bytes() + s.segments.bytes() + s.segmentCells.bytes() +
           s.sortedSegments.bytes() + s.sortedCells.bytes() + s.sortTemp.bytes() +
           s.visible.bytes() + s.pruning.deviceBytes() + s.endpointTable.bytes() +
           s.representative.bytes() + s.representatives.bytes() + s.representativeCount.bytes() +
           s.isRepresentative.bytes() + s.neighbourList.bytes() + s.neighbourCount.bytes();
}

CudaStatus RayCastSilhouetteCuda::setVolume(const VolumeView& hostVolume,
                                            const VoxelGridSetup& setup,
                                            const RayGridSetup& rayGrid, bool mapped) {
    Impl& s = *m_impl;
    s.prepared = false;
    // This translation unit's copy of the constant tables (see marching_cubes_kernels.cuh).
    LW_RETURN_IF_FAILED(mc::uploadTables());
    LW_RETURN_IF_FAILED(mapped ? s.marchingCubes.setMappedVolume(hostVolume, setup)
                               : s.marchingCubes.setVolume(hostVolume, setup));
    s.rayGrid = rayGrid;
    LW_RETURN_IF_FAILED(s.rayOffsets.reserve(rayGrid.offsets.size(), "cudaMalloc(rayOffsets)"));
    LW_CUDA_TRY(cudaMemcpy(s.rayOffsets.data(), rayGrid.offsets.data(),
                           rayGrid.offsets.size() * sizeof(double), cudaMemcpyHostToDevice),
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
    return dispatchVoxelKind(s.mc().volume.kind,
                             [&](auto zero) { return s.findMacroMaxima<decltype(zero)>(); });
}

template <typename T> CudaStatus RayCastSilhouetteCuda::Impl::findMacroMaxima() {
    MarchingCubesCuda::Impl& m = mc();
    const std::size_t macroCount =
        std::size_t(macroDims.x) * std::size_t(macroDims.y) * std::size_t(macroDims.z);
    rc::macroMaximum<T><<<blocksFor(macroCount, 128), 128, 0, m.stream.get()>>>(
        static_cast<const T*>(m.volume.voxels), m.spans.dims, macroDims, macroMaxima.data());
    LW_CUDA_LAUNCHED("rc::macroMaximum");
    LW_CUDA_TRY(cudaStreamSynchronize(m.stream.get()), "rc::macroMaximum");
    return CudaStatus::success();
}

// The active cells at a new iso-value, and their mesh where the device holds it: every view's
// segments then come from the mesh (rc::findMeshSegments), which on a volume mapped from host
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
    LW_RETURN_IF_FAILED(findActiveCells<T>(storedIso));
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
    if (!s.mc().volume.voxels)
        return CudaStatus::failure(CudaStatus::Code::Failed, "method 2 (CUDA)",
                                   "no volume: call setVolume first");
    return dispatchVoxelKind(s.mc().volume.kind, [&](auto zero) {
        return s.prepareTyped<decltype(zero)>(storedIso, frame);
    });
}

// Phase 1: the segments of the active cells into `segments` (sorted by cell for the rays).
template <typename T>
CudaStatus RayCastSilhouetteCuda::Impl::findSegments(const rc::View& view, rc::Counters& counts) {
    MarchingCubesCuda::Impl& m = mc();
    cudaStream_t st = m.stream.get();
    const mc::Grid<T> g = m.grid<T>(iso);
    // Run again with a larger buffer when the segments did not fit.
    for (int attempt = 0; attempt < 2; ++attempt) {
        LW_CUDA_TRY(cudaMemsetAsync(counters.data(), 0, sizeof(rc::Counters), st),
                    "cudaMemset(counters)");
        const std::uint32_t capacity =
            std::uint32_t(std::min(segments.capacity(), segmentCells.capacity()));
        const std::uint32_t blocks = blocksFor(m.activeCount, tuning::kRayCastBlock);
        if (meshKept) {
            rc::findMeshSegments<<<blocks, tuning::kRayCastBlock, 0, st>>>(
                m.activeVoxels.data(), m.activeCodes.data(), m.triangleOffsets.data(),
                m.activeCount, m.mesh, view, segments.data(), segmentCells.data(), capacity,
                counters.data());
            LW_CUDA_LAUNCHED("rc::findMeshSegments");
        } else {
            rc::findSegments<T><<<blocks, tuning::kRayCastBlock, 0, st>>>(
                g, m.activeVoxels.data(), m.activeCodes.data(), m.activeCount, view,
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
        const int keyBits = 32 - __builtin_clz(std::max(m.activeVoxelLimit(), 1u));
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
    MarchingCubesCuda::Impl& m = mc();
    cudaStream_t st = m.stream.get();
    const mc::Grid<T> g = m.grid<T>(iso);
    RayVisibility<T> rule;
    rule.voxels = g.box;
    rule.dims = m.spans.dims;
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
    LW_RETURN_IF_FAILED(neighbourList.reserve(endpoints, "cudaMalloc(neighbourList)"));
    LW_RETURN_IF_FAILED(neighbourCount.reserve(1, "cudaMalloc(neighbourCount)"));
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
    LW_CUDA_TRY(cudaMemsetAsync(neighbourCount.data(), 0, sizeof(std::uint32_t), st),
                "cudaMemset(neighbourCount)");
    // The block size is a multiple of the warp: every lane of a warp reaches the ballot.
    static_assert(tuning::kRayBlock % 32 == 0);
    rc::testRepresentatives<T><<<blocks, tuning::kRayBlock, 0, st>>>(
        rule, view, segments.data(), representatives.data(), representativeCount.data(),
        visible.data(), neighbourList.data(), neighbourCount.data());
    LW_CUDA_LAUNCHED("rc::testRepresentatives");
    rc::testNeighbourRays<T><<<blocks, tuning::kRayBlock, 0, st>>>(
        rule, view, segments.data(), neighbourList.data(), neighbourCount.data(), visible.data());
    LW_CUDA_LAUNCHED("rc::testNeighbourRays");
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
    if (m.activeCount > 0)
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
    return dispatchVoxelKind(s.mc().volume.kind, [&](auto zero) {
        return s.renderTyped<decltype(zero)>(view, settings, hostMask, frame, extraSegments,
                                             extraCount);
    });
}

} // namespace lw::kernels::cuda
