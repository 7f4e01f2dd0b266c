#include "lw/render/cuda_iso_surface.h"

#include "lw/core/error.h"
#include "lw/render/renderer_factory.h"

#if LINEWORK_CUDA
#include "cuda/cuda_support.h"
#include "lw/kernels/cpu/border_cap_cpu.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#endif

namespace lw::render {

#if LINEWORK_CUDA
namespace {
constexpr std::string_view kWhere = "marching cubes (CUDA)";
} // namespace

struct CudaIsoSurfaceExtractor::Impl {
    const volume::Volume& volume;
    kernels::cuda::MarchingCubesCuda marchingCubes;
    BorderCapCache cap;
    const Mesh* capInMesh = nullptr;
};

CudaIsoSurfaceExtractor::CudaIsoSurfaceExtractor(const volume::Volume& volume) {
    const CudaAvailability cuda = cudaAvailability();
    if (!cuda.available)
        throw core::Error("marching cubes (CUDA)", cuda.reason);
    m_impl.reset(new Impl{volume});
    throwIfCudaFailed(kWhere, m_impl->marchingCubes.setVolume(
                                  hostVolumeView(volume), kernels::cpu::voxelGridSetup(volume)));
}

CudaIsoSurfaceExtractor::~CudaIsoSurfaceExtractor() = default;

double CudaIsoSurfaceExtractor::uploadMs() const {
    return m_impl->marchingCubes.uploadMs();
}

CudaExtraction CudaIsoSurfaceExtractor::extract(double isoReal, bool closeAtBorder,
                                                GradientStencil stencil) {
    const double storedIso = storedIsoValue(m_impl->volume, isoReal);
    m_impl->capInMesh = nullptr;
    m_impl->marchingCubes.setGradientStencil(stencil);
    throwIfCudaFailed(kWhere, m_impl->marchingCubes.extract(storedIso));
    if (closeAtBorder)
        m_impl->capInMesh = &m_impl->cap.cap(m_impl->volume, storedIso, stencil);
    const kernels::cuda::DeviceMeshView mesh = m_impl->marchingCubes.mesh();
    const kernels::cuda::McCudaTimes& t = m_impl->marchingCubes.times();
    const Mesh* cap = m_impl->capInMesh;
    return {mesh.triangleCount + (cap ? cap->triangleCount() : 0),
            mesh.vertexCount + (cap ? cap->vertexCount() : 0),
            t.totalMs(),
            t.bricksMs,
            t.classifyMs,
            t.countMs,
            t.generateMs};
}

void CudaIsoSurfaceExtractor::download(Mesh& mesh) const {
    downloadSurface(kWhere, m_impl->marchingCubes, m_impl->capInMesh, mesh);
}
#else
struct CudaIsoSurfaceExtractor::Impl {};

CudaIsoSurfaceExtractor::CudaIsoSurfaceExtractor(const volume::Volume&) {
    throw core::Error("marching cubes (CUDA)", cudaAvailability().reason);
}
CudaIsoSurfaceExtractor::~CudaIsoSurfaceExtractor() = default;
double CudaIsoSurfaceExtractor::uploadMs() const {
    return 0.0;
}
CudaExtraction CudaIsoSurfaceExtractor::extract(double, bool, GradientStencil) {
    return {};
}
void CudaIsoSurfaceExtractor::download(Mesh&) const {}
#endif

} // namespace lw::render
