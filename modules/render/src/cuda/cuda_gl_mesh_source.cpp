#include "../gl/gl_mesh_source.h"

#if LINEWORK_CUDA_GL_INTEROP
#include "cuda_support.h"
#include "device_surface_shader.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/kernels/cpu/border_cap_cpu.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cuda/cuda_device.h"
#include "lw/kernels/cuda/gl_mesh_interop.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/cuda/stroke_pruning_cuda.h"
#include "lw/render/gpu_memory_plan.h"
#endif

namespace lw::render {

#if LINEWORK_CUDA_GL_INTEROP
namespace {

constexpr core::LogCategory kLog("lw.render");

constexpr std::string_view kWhere = "method 1 (CUDA)";

class CudaGlMeshSource final : public GlMeshSource {
public:
    std::string_view backendName() const override { return "cuda+gl"; }

    void setVolume(const volume::Volume& volume) override {
        m_wholeCurrent = false;
        m_volume = &volume;
        m_deviceCopy = {};
        m_uploaded = false;
        m_streamed = false;
        m_rowRanges.reset();
        m_cap.clear();
        m_capInMesh = nullptr;
    }

    void useDeviceCopy(DeviceVoxelCopy copy) override {
        m_deviceCopy = copy;
        if (copy.faceMaxima && m_volume)
            m_cap.useFaceMaxima(*m_volume, *copy.faceMaxima);
    }

    void releaseVolume() override {
        m_wholeCurrent = false;
        m_shading.release();
        m_contour.release();
        m_marchingCubes.release(); // the device copy and a streamed volume's host registration
        m_volume = nullptr;
        m_deviceCopy = {};
        m_uploaded = false;
        m_streamed = false;
        m_rowRanges.reset();
        m_cap.clear();
        m_capInMesh = nullptr;
    }

    bool extractPiecesInto(SilhouetteGlRenderer& gl, const SilhouetteSettings& settings,
                           const PieceDrawer& drawPiece) override {
        if (!m_volume)
            throw core::Error("method 1 (CUDA)", "no volume bound");
        m_wholeCurrent = false; // the device's buffers hold one slab after another from here
        if (!m_streamed) {
            m_uploaded = false; // the streamed state replaces a resident volume
            throwIfCudaFailed(
                kWhere, m_marchingCubes.setStreamedVolume(hostVolumeView(*m_volume),
                                                          kernels::cpu::voxelGridSetup(*m_volume)));
            m_streamed = true;
            m_rowRanges = std::make_unique<VoxelRowRanges>(*m_volume);
        }
        m_marchingCubes.setGradientStencil(settings.gradientStencil);
        const double storedIso = storedIsoValue(*m_volume, settings.isoReal);
        std::size_t budget = settings.gpuMemoryBudget;
        if (budget == 0)
            budget =
                defaultGpuBudget(kernels::cuda::freeDeviceBytes() + m_marchingCubes.deviceBytes());
        const std::vector<glm::ivec2> layers =
            planSlabs(m_volume->dims(), volume::voxelSize(m_volume->voxelType()), budget, 0,
                      settings.gpuSlabLayers);
        const std::vector<kernels::CellSlab> slabs =
            cropSlabsToSurface(layers, *m_rowRanges, storedIso);
        throwIfCudaFailed(kWhere, m_marchingCubes.extractSlabs(
                                      storedIso, slabs,
                                      [&](std::size_t, const kernels::cuda::DeviceMeshView& mesh) {
                                          writeIntoGl(gl, mesh, nullptr);
                                          drawPiece(mesh.triangleCount);
                                          return kernels::cuda::CudaStatus::success();
                                      }));
        return true;
    }

    void extractInto(SilhouetteGlRenderer& gl, const SilhouetteSettings& settings) override {
        if (!m_volume)
            throw core::Error("method 1 (CUDA)", "no volume bound");
        if (!m_uploaded) {
            m_streamed = false; // a resident volume replaces the streamed state
            throwIfCudaFailed(kWhere, placeWholeVolume(m_marchingCubes, *m_volume, m_deviceCopy));
            m_uploaded = true;
        }
        const double storedIso = storedIsoValue(*m_volume, settings.isoReal);
        m_capInMesh = nullptr; // until the new mesh is written
        m_wholeCurrent = false;
        m_shading.forgetCap(); // the cache may hold the new cap where the old one was
        m_marchingCubes.setGradientStencil(settings.gradientStencil);
        throwIfCudaFailed(kWhere, m_marchingCubes.extract(storedIso));
        const Mesh* cap = settings.closeAtBorder
                              ? &m_cap.cap(*m_volume, storedIso, settings.gradientStencil)
                              : nullptr;
        writeIntoGl(gl, m_marchingCubes.mesh(), cap);
        m_capInMesh = cap;
        m_wholeCurrent = true;
    }

    bool shadeWhole(const Camera& camera, const SurfaceShading& shading, core::ImageRgba8& image,
                    std::vector<float>* depth, std::size_t& triangles) override {
        if (!m_wholeCurrent || !m_shadingWorks)
            return false;
        DeviceSurfaceShader::Shaded shaded;
        const kernels::cuda::CudaStatus status = m_shading.shade(
            camera, shading, m_marchingCubes.mesh(), m_capInMesh, image, depth, shaded);
        if (!status.ok()) {
            kLog.warning("method 1: the iso panel cannot be shaded on the device (" +
                         status.describe() + "); GL shades it");
            m_shading.release();
            m_shadingWorks = false;
            return false;
        }
        triangles = shaded.triangles;
        return true;
    }

    // The device mesh (and the border cap after it, from the host: it is small) into gl's
    // buffers: device to device through interop, or through host memory where interop fails
    // (a GL context on another device).
    void writeIntoGl(SilhouetteGlRenderer& gl, const kernels::cuda::DeviceMeshView& mesh,
                     const Mesh* cap) {
        const std::size_t capVertices = cap ? cap->vertexCount() : 0;
        const std::size_t capTriangles = cap ? cap->triangleCount() : 0;
        gl.reserveMesh(mesh.vertexCount + capVertices, mesh.triangleCount + capTriangles);
        if (m_interopWorks) {
            const kernels::cuda::CudaStatus copied =
                m_interop.copy(mesh, {gl.positionBuffer(), gl.normalBuffer(), gl.indexBuffer(),
                                      gl.storageGeneration()});
            if (copied.ok()) {
                if (cap)
                    gl.writeMeshTail(mesh.vertexCount, mesh.triangleCount, *cap);
                return;
            }
            // E.g. the GL context runs on another device (Mesa) than CUDA: the host round trip
            // still works.
            kLog.warning("method 1: CUDA-GL interop unavailable (" + copied.describe() +
                         "); copying the mesh through host memory");
            m_interop.unregister();
            m_interopWorks = false;
        }
        Mesh host;
        downloadSurface(kWhere, m_marchingCubes, cap, host);
        gl.uploadMesh(host);
    }

    void download(Mesh& mesh) override {
        downloadSurface(kWhere, m_marchingCubes, m_capInMesh, mesh);
    }

    std::optional<Mesh> contourTriangles(const Camera& camera) override {
        if (!m_wholeCurrent)
            return std::nullopt;
        Mesh part;
        throwIfCudaFailed(kWhere, downloadContourTriangles(m_contour, m_marchingCubes, m_capInMesh,
                                                           camera, part));
        return part;
    }

    bool pruneStrokes(PixelMask& lines, int minPixels, int gapPixels) override {
        if (!m_pruneWorks)
            return false;
        const kernels::cuda::CudaStatus status = m_pruner.prune(
            lines.pixels().data(), lines.width(), lines.height(), minPixels, gapPixels);
        if (status.ok())
            return true;
        // The pruned mask replaces the read-back one only when everything succeeded: on failure
        // `lines` is as read back, and the host prunes it.
        kLog.warning("method 1: strokes not pruned on the device (" + status.describe() +
                     "); the host prunes them");
        m_pruneWorks = false;
        return false;
    }

    void releaseGl() override { m_interop.unregister(); }

private:
    const volume::Volume* m_volume = nullptr;
    DeviceVoxelCopy m_deviceCopy; // the bound voxels on the device already, or null
    bool m_uploaded = false;
    bool m_streamed = false; // setStreamedVolume done (L frames); exclusive with m_uploaded
    std::unique_ptr<VoxelRowRanges> m_rowRanges; // L frames: which rows of a slab can matter
    bool m_interopWorks = true;
    kernels::cuda::MarchingCubesCuda m_marchingCubes;
    kernels::cuda::GlMeshInterop m_interop;
    kernels::cuda::HostMaskPruner m_pruner;
    bool m_pruneWorks = true;
    BorderCapCache m_cap;
    const Mesh* m_capInMesh = nullptr; // the cap written after the last whole mesh, if any
    // m_marchingCubes holds the whole surface of the last extractInto (not a slab's).
    bool m_wholeCurrent = false;
    DeviceSurfaceShader m_shading;                 // the iso panel from that surface
    kernels::cuda::ContourTrianglesCuda m_contour; // the exports' lines' triangles
    bool m_shadingWorks = true;
};

} // namespace

std::unique_ptr<GlMeshSource> makeCudaGlMeshSource() {
    return std::make_unique<CudaGlMeshSource>();
}
#else
std::unique_ptr<GlMeshSource> makeCudaGlMeshSource() {
    return nullptr;
}
#endif

} // namespace lw::render
