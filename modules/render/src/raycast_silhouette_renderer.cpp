#include "lw/render/raycast_silhouette_renderer.h"

#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/iso_surface.h"
#include "raycast_kernels_cpu.h"

#include <limits>
#include <string>

namespace lw::render {
namespace {

constexpr core::LogCategory kLog("lw.render");

} // namespace

struct RayCastSilhouetteRenderer::State {
    const volume::Volume* volume = nullptr;
    std::unique_ptr<RayCastKernelSet> device; // null: the CPU is the back-end
    std::unique_ptr<CpuRayCastKernels> cpu;
    bool deviceFailed = false; // ran out of device memory with this volume: the CPU from now on
    RayCastKernelSet* last = nullptr;

    // The prepared cells are for this iso-value, brick size, mode and gradient stencil, on
    // `prepared` (null: none).
    RayCastKernelSet* prepared = nullptr;
    double preparedIso = std::numeric_limits<double>::quiet_NaN();
    int preparedBrickCells = -1;
    ExtractionMode preparedMode = ExtractionMode::CachedA;
    GradientStencil preparedStencil = GradientStencil::Central;

    CpuRayCastKernels& cpuSet() {
        if (!cpu) {
            cpu = makeCpuRayCastKernels();
            cpu->bind(volume);
        }
        return *cpu;
    }
    // Who draws this frame: the device unless it cannot (L) or failed.
    RayCastKernelSet& setFor(const SilhouetteSettings& settings) {
        if (device && !deviceFailed && (settings.brickCells == 0 || device->drawsPieces()))
            return *device;
        return cpuSet();
    }
    void frameOn(RayCastKernelSet& set, const Camera& camera, const SilhouetteSettings& settings,
                 SilhouetteFrame& frame);
    void fallBack(const OutOfDeviceMemory& error);
};

// Out of device memory: with the volume resident, again with it mapped from host memory; after
// that, the CPU for this volume (until the next setVolume).
void RayCastSilhouetteRenderer::State::fallBack(const OutOfDeviceMemory& error) {
    prepared = nullptr;
    const std::string what =
        "method 2 (" + std::string(device->backendName()) + "): " + error.what();
    if (device->fallBack()) {
        kLog.warning(what + "; reading the volume from host memory");
        return;
    }
    kLog.warning(what + "; rendering on the CPU");
    device->bind(nullptr);
    device->bind(volume); // frees what the failed attempt holds, uploads again later
    deviceFailed = true;
}

// Mode a keeps the active cells while the iso-value, brick size and mode stay; segments depend on
// the eye and are found anew for every view. Mode b finds the cells every frame.
void RayCastSilhouetteRenderer::State::frameOn(RayCastKernelSet& set, const Camera& camera,
                                               const SilhouetteSettings& settings,
                                               SilhouetteFrame& frame) {
    const double storedIso = storedIsoValue(*volume, settings.isoReal);
    const bool stale = prepared != &set || !(preparedIso == storedIso) ||
                       preparedBrickCells != settings.brickCells || preparedMode != settings.mode ||
                       preparedStencil != settings.gradientStencil ||
                       settings.mode == ExtractionMode::EveryFrameB;
    if (stale) {
        prepared = nullptr; // until a prepare completes
        set.prepare(storedIso, settings, frame);
        prepared = &set;
        preparedIso = storedIso;
        preparedBrickCells = settings.brickCells;
        preparedMode = settings.mode;
        preparedStencil = settings.gradientStencil;
    }
    if (settings.cancel && settings.cancel->isCancelled())
        throw core::Cancelled();
    set.drawView(camera, settings, frame);
    last = &set;
}

RayCastSilhouetteRenderer::RayCastSilhouetteRenderer(Backend backend)
    : m_state(std::make_unique<State>()) {
    if (backend == Backend::Cuda) {
        m_state->device = makeCudaRayCastKernels();
        if (!m_state->device)
            throw core::Error("method 2", "this build has no CUDA back-end");
    }
}

RayCastSilhouetteRenderer::~RayCastSilhouetteRenderer() = default;

std::string_view RayCastSilhouetteRenderer::backendName() const {
    const State& s = *m_state;
    if (s.last)
        return s.last->backendName();
    return s.device ? s.device->backendName() : "cpu";
}

void RayCastSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    State& s = *m_state;
    s.volume = &volume;
    if (s.device)
        s.device->bind(&volume);
    if (s.cpu)
        s.cpu->bind(&volume);
    s.deviceFailed = false;
    s.prepared = nullptr;
    s.last = nullptr;
}

void RayCastSilhouetteRenderer::setVolumeWithDeviceCopy(const volume::Volume& volume,
                                                        DeviceVoxelCopy copy) {
    setVolume(volume);
    if (m_state->device)
        m_state->device->useDeviceCopy(copy);
}

void RayCastSilhouetteRenderer::releaseVolume() {
    State& s = *m_state;
    if (s.device)
        s.device->bind(nullptr);
    if (s.cpu)
        s.cpu->bind(nullptr);
    s.volume = nullptr;
    s.prepared = nullptr;
    s.last = nullptr;
}

SilhouetteFrame RayCastSilhouetteRenderer::renderFrame(const Camera& camera,
                                                       const SilhouetteSettings& settings) {
    State& s = *m_state;
    if (!s.volume)
        throw core::Error(s.device ? "method 2 (CUDA)" : "method 2", "no volume bound (setVolume)");
    if (settings.cancel && settings.cancel->isCancelled())
        throw core::Cancelled();
    for (;;) {
        SilhouetteFrame frame;
        try {
            s.frameOn(s.setFor(settings), camera, settings, frame);
            return frame;
        } catch (const OutOfDeviceMemory& error) {
            s.fallBack(error); // the device's leaner way, or the CPU (which never runs out)
        }
    }
}

static const CpuRayCastKernels& cpuFrameOf(const RayCastKernelSet* last,
                                           const CpuRayCastKernels* cpu) {
    if (!cpu || last != cpu)
        throw core::Error("method 2", "the last frame was not drawn on the CPU");
    return *cpu;
}

std::size_t RayCastSilhouetteRenderer::activeCellCount() const {
    const State& s = *m_state;
    return s.cpu && s.last == s.cpu.get() ? s.cpu->kernel().activeCellCount() : 0;
}

std::vector<RayCastSilhouetteRenderer::Segment> RayCastSilhouetteRenderer::lastSegments() const {
    const CpuRayCastKernels& set = cpuFrameOf(m_state->last, m_state->cpu.get());
    const auto& kernel = set.kernel();
    std::vector<Segment> out;
    out.reserve(kernel.segmentCount() + set.capSegments().size());
    for (std::size_t c = 0; c < kernel.segmentChunkCount(); ++c)
        for (const auto& s : kernel.segmentChunk(c))
            out.push_back({s.a, s.b});
    for (const auto& s : set.capSegments())
        out.push_back({s.a, s.b});
    return out;
}

bool RayCastSilhouetteRenderer::isPointVisible(const Camera& camera, glm::dvec3 point) const {
    if (!m_state->cpu)
        throw core::Error("method 2", "isPointVisible() needs a render() first");
    return m_state->cpu->isPointVisible(camera, point);
}

} // namespace lw::render
