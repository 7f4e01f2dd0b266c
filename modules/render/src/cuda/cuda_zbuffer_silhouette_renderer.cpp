#include "cuda_zbuffer_silhouette_renderer.h"

#include "../view_transform.h"
#include "cuda_support.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cuda/cuda_device.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/cuda/zbuffer_cuda.h"
#include "lw/render/zbuffer_silhouette_renderer.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <string>

namespace lw::render {
namespace {

using kernels::cuda::CudaStatus;
constexpr core::LogCategory kLog("lw.render");

constexpr std::string_view kWhere = "method 3 (CUDA)";

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

} // namespace

struct CudaZBufferSilhouetteRenderer::State {
    const volume::Volume* volume = nullptr;
    // Where the voxels are now (Cpu: none on the device) and where frames must go at least
    // (raised by an out-of-memory fallback until the next setVolume).
    GpuResidency resident = GpuResidency::Cpu;
    GpuResidency floor = GpuResidency::WholeVolume;
    GpuResidency last = GpuResidency::WholeVolume;
    kernels::cuda::MarchingCubesCuda marchingCubes;
    kernels::cuda::ZBufferCuda zbuffer;
    bool meshValid = false; // whole volume: the device mesh is for meshIso
    double meshIso = std::numeric_limits<double>::quiet_NaN();
    double closedIso = std::numeric_limits<double>::quiet_NaN(); // slabs: meshClosed is for it
    bool meshClosed = false;
    mutable Mesh hostMesh;
    mutable bool hostMeshValid = false;
    double lastIso = std::numeric_limits<double>::quiet_NaN();
    std::unique_ptr<ZBufferSilhouetteRenderer> cpu; // the last fallback
    // Slabs: the voxel rows' value ranges (once per volume) and the last frame's cropped slabs,
    // reused while the iso-value and the layer plan stay (an orbit).
    std::unique_ptr<VoxelRowRanges> rowRanges;
    std::vector<glm::ivec2> plannedLayers;
    double croppedIso = std::numeric_limits<double>::quiet_NaN();
    std::vector<kernels::CellSlab> croppedSlabs;

    CudaStatus renderWhole(const Camera& camera, const SilhouetteSettings& settings,
                           SilhouetteFrame& frame);
    CudaStatus renderSlabs(const Camera& camera, const SilhouetteSettings& settings,
                           std::size_t budget, SilhouetteFrame& frame);
    CudaStatus draw(const Camera& camera, const SilhouetteSettings& settings, bool closed,
                    const kernels::cuda::DeviceMeshView* mesh,
                    const std::vector<kernels::CellSlab>* slabs, double storedIso,
                    SilhouetteFrame& frame);
    const std::vector<kernels::CellSlab>& slabsOf(const std::vector<glm::ivec2>& layers,
                                                  double storedIso);
    std::size_t imageBytes(const Camera& camera) const {
        // zbuffer1, zbuffer2 (4 bytes a pixel each) and the mask.
        return std::size_t(camera.width()) * std::size_t(camera.height()) * 9;
    }
};

CudaZBufferSilhouetteRenderer::CudaZBufferSilhouetteRenderer()
    : m_state(std::make_unique<State>()) {}
CudaZBufferSilhouetteRenderer::~CudaZBufferSilhouetteRenderer() = default;

std::string_view CudaZBufferSilhouetteRenderer::backendName() const {
    return m_state->last == GpuResidency::Cpu ? "cpu" : "cuda";
}

GpuResidency CudaZBufferSilhouetteRenderer::lastResidency() const {
    return m_state->last;
}

double CudaZBufferSilhouetteRenderer::uploadMs() const {
    return m_state->resident == GpuResidency::WholeVolume ? m_state->marchingCubes.uploadMs() : 0.0;
}

void CudaZBufferSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    State& s = *m_state;
    s.volume = &volume;
    s.resident = GpuResidency::Cpu;
    s.floor = GpuResidency::WholeVolume;
    s.meshValid = false;
    s.hostMeshValid = false;
    s.closedIso = std::numeric_limits<double>::quiet_NaN();
    s.rowRanges.reset();
    s.croppedIso = std::numeric_limits<double>::quiet_NaN();
    if (s.cpu)
        s.cpu->setVolume(volume);
}

void CudaZBufferSilhouetteRenderer::releaseVolume() {
    State& s = *m_state;
    s.marchingCubes.release(); // the device buffers and the host registration
    s.zbuffer.release();
    s.cpu.reset();
    s.rowRanges.reset();
    s.volume = nullptr;
    s.resident = GpuResidency::Cpu;
    s.floor = GpuResidency::WholeVolume;
    s.meshValid = false;
    s.hostMeshValid = false;
    s.closedIso = std::numeric_limits<double>::quiet_NaN();
    s.croppedIso = std::numeric_limits<double>::quiet_NaN();
    s.lastIso = std::numeric_limits<double>::quiet_NaN();
}

const Mesh* CudaZBufferSilhouetteRenderer::surfaceMesh() const {
    const State& s = *m_state;
    if (s.last == GpuResidency::Cpu && s.cpu)
        return s.cpu->surfaceMesh();
    if (!s.hostMeshValid && s.volume && !std::isnan(s.lastIso)) {
        if (s.last == GpuResidency::WholeVolume && s.meshValid)
            throwIfCudaFailed(kWhere,
                              s.marchingCubes.download(s.hostMesh.positions, s.hostMesh.normals,
                                                       s.hostMesh.indices));
        else // slab frames keep no whole mesh: the CPU extracts it for the caller that asks
            extractIsoSurface(*s.volume, s.lastIso, IsoSurfaceOptions{}, s.hostMesh);
        s.hostMeshValid = true;
    }
    return &s.hostMesh;
}

CudaStatus CudaZBufferSilhouetteRenderer::State::draw(const Camera& camera,
                                                      const SilhouetteSettings& settings,
                                                      bool closed,
                                                      const kernels::cuda::DeviceMeshView* mesh,
                                                      const std::vector<kernels::CellSlab>* slabs,
                                                      double storedIso, SilhouetteFrame& frame) {
    kernels::cuda::ZBufferCudaSettings zb;
    zb.visibility = settings.visibility;
    zb.cullBackFaces = closed;
    zb.epsilon =
        settings.visibility ? ZBufferSilhouetteRenderer::depthEpsilon(camera, *volume) : 0.0f;
    kernels::cuda::ZBufferCudaFrame timing;
    LW_RETURN_IF_FAILED(zbuffer.begin(toViewTransform(camera)));
    if (mesh) {
        LW_RETURN_IF_FAILED(zbuffer.draw(*mesh, zb, timing));
        frame.triangles = mesh->triangleCount;
    } else {
        const auto start = std::chrono::steady_clock::now();
        LW_RETURN_IF_FAILED(marchingCubes.extractSlabs(
            storedIso, *slabs, [&](const kernels::cuda::DeviceMeshView& slab) {
                frame.triangles += slab.triangleCount;
                return zbuffer.draw(slab, zb, timing);
            }));
        // The slabs' extraction and drawing interleave: extraction is the loop's wall time less
        // the drawing kernels' time.
        const double drawn = timing.projectMs + timing.silhouetteMs + timing.depthMs;
        frame.times.extractMs = std::max(0.0, msSince(start) - drawn);
    }
    frame.lines = PixelMask(camera.width(), camera.height());
    LW_RETURN_IF_FAILED(zbuffer.resolve(zb, frame.lines.pixels().data(), timing));
    frame.segments = timing.segments;
    frame.times.silhouetteMs = timing.projectMs + timing.silhouetteMs;
    frame.times.visibilityMs = timing.depthMs;
    frame.times.drawMs = timing.resolveMs;
    frame.deviceBytes = marchingCubes.peakDeviceBytes() + zbuffer.deviceBytes();
    return CudaStatus::success();
}

CudaStatus CudaZBufferSilhouetteRenderer::State::renderWhole(const Camera& camera,
                                                             const SilhouetteSettings& settings,
                                                             SilhouetteFrame& frame) {
    if (resident != GpuResidency::WholeVolume) {
        meshValid = false;
        resident = GpuResidency::Cpu;
        LW_RETURN_IF_FAILED(marchingCubes.setVolume(hostVolumeView(*volume),
                                                    kernels::cpu::voxelGridSetup(*volume)));
        resident = GpuResidency::WholeVolume;
    }
    const double storedIso = storedIsoValue(*volume, settings.isoReal);
    const bool reuse =
        settings.mode == ExtractionMode::CachedA && meshValid && meshIso == settings.isoReal;
    if (!reuse) {
        meshValid = false;
        hostMeshValid = false;
        LW_RETURN_IF_FAILED(marchingCubes.extract(storedIso));
        meshValid = true;
        meshIso = settings.isoReal;
        frame.times.extractMs = marchingCubes.times().totalMs();
    }
    const kernels::cuda::DeviceMeshView mesh = marchingCubes.mesh();
    const double extractMs = frame.times.extractMs;
    LW_RETURN_IF_FAILED(
        draw(camera, settings, !mesh.touchesBorder, &mesh, nullptr, storedIso, frame));
    frame.times.extractMs = extractMs;
    return CudaStatus::success();
}

CudaStatus CudaZBufferSilhouetteRenderer::State::renderSlabs(const Camera& camera,
                                                             const SilhouetteSettings& settings,
                                                             std::size_t budget,
                                                             SilhouetteFrame& frame) {
    if (resident != GpuResidency::Slabs) {
        meshValid = false;
        resident = GpuResidency::Cpu;
        LW_RETURN_IF_FAILED(marchingCubes.setStreamedVolume(hostVolumeView(*volume),
                                                            kernels::cpu::voxelGridSetup(*volume)));
        resident = GpuResidency::Slabs;
    }
    hostMeshValid = false;
    const double storedIso = storedIsoValue(*volume, settings.isoReal);
    if (!(closedIso == settings.isoReal)) {
        meshClosed = !surfaceTouchesBorder(*volume, storedIso);
        closedIso = settings.isoReal;
    }
    const std::vector<glm::ivec2> layers =
        planSlabs(volume->dims(), volume::voxelSize(volume->voxelType()), budget,
                  imageBytes(camera), settings.gpuSlabLayers);
    return draw(camera, settings, meshClosed, nullptr, &slabsOf(layers, storedIso), storedIso,
                frame);
}

const std::vector<kernels::CellSlab>&
CudaZBufferSilhouetteRenderer::State::slabsOf(const std::vector<glm::ivec2>& layers,
                                              double storedIso) {
    if (!rowRanges)
        rowRanges = std::make_unique<VoxelRowRanges>(*volume);
    if (!(croppedIso == storedIso) || layers != plannedLayers) {
        croppedSlabs = cropSlabsToSurface(layers, *rowRanges, storedIso);
        plannedLayers = layers;
        croppedIso = storedIso;
    }
    return croppedSlabs;
}

SilhouetteFrame CudaZBufferSilhouetteRenderer::renderFrame(const Camera& camera,
                                                      const SilhouetteSettings& settings) {
    State& s = *m_state;
    if (!s.volume)
        throw core::Error(std::string(kWhere), "no volume bound: call setVolume first");
    if (settings.brickCells < 0)
        throw core::Error(std::string(kWhere), "brickCells must be 0 (whole volume) or positive");
    if (settings.cancel && settings.cancel->isCancelled())
        throw core::Cancelled();
    s.lastIso = settings.isoReal;
    std::size_t budget = settings.gpuMemoryBudget;
    if (budget == 0) // what is free plus what this renderer holds already
        budget = defaultGpuBudget(kernels::cuda::freeDeviceBytes() + s.marchingCubes.deviceBytes() +
                                  s.zbuffer.deviceBytes());
    GpuResidency where = chooseResidency(s.volume->dims(), volume::voxelSize(s.volume->voxelType()),
                                         budget, s.imageBytes(camera), settings.brickCells > 0);
    if (int(where) < int(s.floor))
        where = s.floor;
    for (;;) {
        s.last = where;
        if (where == GpuResidency::Cpu) {
            if (!s.cpu) {
                s.cpu = std::make_unique<ZBufferSilhouetteRenderer>();
                s.cpu->setVolume(*s.volume);
            }
            return s.cpu->render(camera, settings);
        }
        SilhouetteFrame frame;
        CudaStatus status = where == GpuResidency::WholeVolume
                                ? s.renderWhole(camera, settings, frame)
                                : s.renderSlabs(camera, settings, budget, frame);
        // The budget is a limit, not a hint: a frame that held more than it (the whole volume's
        // overhead is an estimate) counts as out of memory, and later frames take the next way.
        if (status.ok() && frame.deviceBytes > budget)
            status = CudaStatus::failure(
                CudaStatus::Code::OutOfMemory, "method 3 (CUDA)",
                "the frame held " + std::to_string(frame.deviceBytes >> 20) +
                    " MiB, over the budget of " + std::to_string(budget >> 20) + " MiB");
        if (status.ok())
            return frame;
        if (status.code != CudaStatus::Code::OutOfMemory)
            throwIfCudaFailed(kWhere, status);
        const GpuResidency next = afterOutOfMemory(where);
        kLog.warning("method 3 (CUDA): out of device memory with the " +
                     std::string(residencyName(where)) + " (" + status.describe() +
                     "); trying the " + std::string(residencyName(next)));
        // Free what the failed attempt holds before the next one allocates.
        s.marchingCubes.release();
        s.zbuffer.release();
        s.resident = GpuResidency::Cpu;
        s.meshValid = false;
        s.floor = next;
        where = next;
    }
}

} // namespace lw::render
