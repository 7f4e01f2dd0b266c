#include "cuda_zbuffer_silhouette_renderer.h"

#include "../view_transform.h"
#include "cuda_support.h"
#include "lw/core/error.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/cuda/zbuffer_cuda.h"

#include <limits>
#include <string>

namespace lw::render {
namespace {

void throwIfFailed(const kernels::cuda::CudaStatus& status) {
    if (!status.ok())
        throw core::Error("method 3 (CUDA)", status.describe());
}

} // namespace

struct CudaZBufferSilhouetteRenderer::State {
    const volume::Volume* volume = nullptr;
    bool uploaded = false;
    kernels::cuda::MarchingCubesCuda marchingCubes;
    kernels::cuda::ZBufferCuda zbuffer;
    bool meshValid = false;
    double meshIso = std::numeric_limits<double>::quiet_NaN();
    mutable Mesh hostMesh;
    mutable bool hostMeshValid = false;
    ChunkedOnCpu<ZBufferSilhouetteRenderer> chunked; // L frames (see the header)

    void upload() {
        if (uploaded)
            return;
        const kernels::VoxelGridSetup setup = kernels::cpu::voxelGridSetup(*volume);
        throwIfFailed(marchingCubes.setVolume(hostVolumeView(*volume), setup));
        uploaded = true;
    }
};

CudaZBufferSilhouetteRenderer::CudaZBufferSilhouetteRenderer()
    : m_state(std::make_unique<State>()) {}
CudaZBufferSilhouetteRenderer::~CudaZBufferSilhouetteRenderer() = default;

std::string_view CudaZBufferSilhouetteRenderer::backendName() const {
    return m_state->chunked.lastFrameWasChunked() ? "cpu" : "cuda";
}

double CudaZBufferSilhouetteRenderer::uploadMs() const {
    return m_state->uploaded ? m_state->marchingCubes.uploadMs() : 0.0;
}

void CudaZBufferSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    State& s = *m_state;
    s.volume = &volume;
    s.uploaded = false;
    s.meshValid = false;
    s.hostMeshValid = false;
    s.chunked.setVolume(volume);
}

const Mesh* CudaZBufferSilhouetteRenderer::surfaceMesh() const {
    const State& s = *m_state;
    if (s.chunked.lastFrameWasChunked())
        return s.chunked.renderer()->surfaceMesh();
    if (!s.hostMeshValid && s.meshValid) {
        throwIfFailed(s.marchingCubes.download(s.hostMesh.positions, s.hostMesh.normals,
                                               s.hostMesh.indices));
        s.hostMeshValid = true;
    }
    return &s.hostMesh;
}

SilhouetteFrame CudaZBufferSilhouetteRenderer::render(const Camera& camera,
                                                       const SilhouetteSettings& settings) {
    State& s = *m_state;
    if (!s.volume)
        throw core::Error("method 3 (CUDA)", "no volume bound: call setVolume first");
    if (settings.brickCells < 0)
        throw core::Error("method 3 (CUDA)", "brickCells must be 0 (whole volume) or positive");
    SilhouetteFrame frame;
    if (s.chunked.render(camera, settings, frame))
        return frame;
    if (settings.cancel && settings.cancel->isCancelled())
        throw core::Cancelled();
    s.upload();
    const bool reuse = settings.mode == ExtractionMode::CachedA && s.meshValid &&
                       s.meshIso == settings.isoReal;
    if (!reuse) {
        s.meshValid = false;
        s.hostMeshValid = false;
        throwIfFailed(s.marchingCubes.extract(storedIsoValue(*s.volume, settings.isoReal)));
        s.meshValid = true;
        s.meshIso = settings.isoReal;
        frame.times.extractMs = s.marchingCubes.times().totalMs();
    }
    const kernels::cuda::DeviceMeshView mesh = s.marchingCubes.mesh();
    frame.triangles = mesh.triangleCount;

    kernels::cuda::ZBufferCudaSettings zb;
    zb.visibility = settings.visibility;
    zb.cullBackFaces = !mesh.touchesBorder;
    zb.epsilon =
        settings.visibility ? ZBufferSilhouetteRenderer::depthEpsilon(camera, *s.volume) : 0.0f;
    kernels::cuda::ZBufferCudaFrame timing;
    throwIfFailed(s.zbuffer.begin(toViewTransform(camera)));
    throwIfFailed(s.zbuffer.draw(mesh, zb, timing));
    frame.lines = PixelMask(camera.width(), camera.height());
    throwIfFailed(s.zbuffer.resolve(zb, frame.lines.pixels().data(), timing));
    frame.segments = timing.segments;
    frame.times.silhouetteMs = timing.projectMs + timing.silhouetteMs;
    frame.times.visibilityMs = timing.depthMs;
    frame.times.drawMs = timing.resolveMs;
    return frame;
}

} // namespace lw::render
