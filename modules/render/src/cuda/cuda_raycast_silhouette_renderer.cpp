#include "cuda_raycast_silhouette_renderer.h"

#include "cuda_support.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cpu/voxel_ray.h"
#include "lw/kernels/cuda/raycast_silhouette_cuda.h"
#include "lw/render/iso_surface.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace lw::render {
namespace {

constexpr core::LogCategory kLog("lw.render");

struct OutOfDeviceMemory : std::runtime_error {
    using std::runtime_error::runtime_error;
};

void throwIfFailed(const kernels::cuda::CudaStatus& status) {
    if (status.code == kernels::cuda::CudaStatus::Code::OutOfMemory)
        throw OutOfDeviceMemory(status.describe());
    if (!status.ok())
        throw core::Error("method 2 (CUDA)", status.describe());
}

kernels::PixelCamera pixelCamera(const Camera& camera) {
    kernels::PixelCamera c;
    c.eye = camera.eye();
    c.right = camera.right();
    c.up = camera.up();
    c.forward = camera.forward();
    c.halfWidth = camera.halfWidth();
    c.halfHeight = camera.halfHeight();
    c.width = camera.width();
    c.height = camera.height();
    c.orthographic = camera.isOrthographic();
    return c;
}

// The walk's grid and its cell widths, from the CPU engine's VoxelRayGrid.
kernels::cuda::RayGridSetup rayGridSetup(const volume::Volume& volume) {
    const kernels::cpu::VoxelRayGrid grid(volume);
    kernels::cuda::RayGridSetup setup;
    setup.offsets = grid.offsets();
    setup.view = grid.view();
    setup.cellScale = grid.cellScale();
    return setup;
}

} // namespace

struct CudaRayCastSilhouetteRenderer::State {
    const volume::Volume* volume = nullptr;
    bool uploaded = false;
    kernels::cuda::RayCastSilhouetteCuda kernels;
    bool prepared = false;
    double preparedIso = std::numeric_limits<double>::quiet_NaN();
    ChunkedOnCpu<RayCastSilhouetteRenderer> chunked; // L frames (see the header)
    bool onCpu = false;                              // ran out of device memory with this volume
};

CudaRayCastSilhouetteRenderer::CudaRayCastSilhouetteRenderer()
    : m_state(std::make_unique<State>()) {}
CudaRayCastSilhouetteRenderer::~CudaRayCastSilhouetteRenderer() = default;

std::string_view CudaRayCastSilhouetteRenderer::backendName() const {
    return m_state->chunked.lastFrameWasChunked() || m_state->onCpu ? "cpu" : "cuda";
}

void CudaRayCastSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    State& s = *m_state;
    s.volume = &volume;
    s.uploaded = false;
    s.prepared = false;
    s.onCpu = false;
    s.chunked.setVolume(volume);
}

void CudaRayCastSilhouetteRenderer::releaseVolume() {
    State& s = *m_state;
    s.kernels.release();
    s.volume = nullptr;
    s.uploaded = false;
    s.prepared = false;
    s.onCpu = false;
}

SilhouetteFrame CudaRayCastSilhouetteRenderer::renderFrame(const Camera& camera,
                                                      const SilhouetteSettings& settings) {
    State& s = *m_state;
    if (s.onCpu) {
        SilhouetteFrame frame;
        s.chunked.renderAlways(camera, settings, frame);
        return frame;
    }
    try {
        return renderOnGpu(camera, settings);
    } catch (const OutOfDeviceMemory& error) {
        // Method 2 has no streamed variant: out of device memory, it goes to the CPU for this
        // volume (until the next setVolume).
        kLog.warning(std::string("method 2 (CUDA): ") + error.what() + "; rendering on the CPU");
        s.kernels.release();
        s.uploaded = false;
        s.onCpu = true;
        SilhouetteFrame frame;
        s.chunked.renderAlways(camera, settings, frame);
        return frame;
    }
}

SilhouetteFrame CudaRayCastSilhouetteRenderer::renderOnGpu(const Camera& camera,
                                                           const SilhouetteSettings& settings) {
    State& s = *m_state;
    if (!s.volume)
        throw core::Error("method 2 (CUDA)", "no volume bound (setVolume)");
    SilhouetteFrame frame;
    if (s.chunked.render(camera, settings, frame))
        return frame;
    if (settings.cancel && settings.cancel->isCancelled())
        throw core::Cancelled();
    if (!s.uploaded) {
        throwIfFailed(s.kernels.setVolume(hostVolumeView(*s.volume),
                                          kernels::cpu::voxelGridSetup(*s.volume),
                                          rayGridSetup(*s.volume)));
        s.uploaded = true;
        s.prepared = false;
    }
    kernels::cuda::RayCastCudaFrame timing;
    const double storedIso = storedIsoValue(*s.volume, settings.isoReal);
    if (!s.prepared || s.preparedIso != storedIso || settings.mode == ExtractionMode::EveryFrameB) {
        s.prepared = false;
        throwIfFailed(s.kernels.prepare(storedIso, timing));
        s.prepared = true;
        s.preparedIso = storedIso;
        frame.times.extractMs = timing.prepareMs;
    }
    kernels::cuda::RayCastCudaSettings rc;
    rc.visibility = settings.visibility;
    rc.alongSegment = settings.testAlongSegment;
    const bool orthographic = camera.isOrthographic();
    frame.lines = PixelMask(camera.width(), camera.height());
    throwIfFailed(s.kernels.render(pixelCamera(camera),
                                   orthographic ? -camera.forward() : camera.eye(), orthographic,
                                   rc, frame.lines.pixels().data(), timing));
    frame.triangles = timing.triangles;
    frame.segments = timing.segments;
    // One kernel finds the segments and tests them: its time is reported as visibility.
    frame.times.visibilityMs = timing.renderMs;
    return frame;
}

} // namespace lw::render
