// Method 2's CUDA kernel set (raycast_kernel_set.h, lw/kernels/cuda/raycast_silhouette_cuda.h):
// the volume uploaded on the first frame after bind, the active cells (and the macro occupancy
// the visibility rays skip with) found on the device, then per view the segments, one ray per
// endpoint (or per line step) and the lines.
//
// Its rays cross the whole volume, so it cannot stream slabs as methods 1 and 3 do. The chunked
// (L) variant, and a volume over the device memory budget, leave the voxels in host memory,
// page-locked and mapped into the device's address space: the same kernels read them over the
// bus, the device holds only the tables and the frame's buffers (MarchingCubesCuda::
// setMappedVolume). Out of device memory with a resident volume, the frame goes mapped before it
// goes to the CPU.
#include "../mesh_silhouette.h"
#include "../raycast_kernel_set.h"
#include "cuda_support.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cpu/voxel_ray.h"
#include "lw/kernels/cuda/cuda_device.h"
#include "lw/kernels/cuda/raycast_silhouette_cuda.h"
#include "lw/render/gpu_memory_plan.h"
#include "lw/render/iso_surface.h"

namespace lw::render {
namespace {

constexpr std::string_view kWhere = "method 2 (CUDA)";

void check(const kernels::cuda::CudaStatus& status) {
    if (status.code == kernels::cuda::CudaStatus::Code::OutOfMemory)
        throw OutOfDeviceMemory(status.describe());
    throwIfCudaFailed(kWhere, status);
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
    setup.neighbourReach = grid.neighbourReach();
    return setup;
}

class CudaRayCastKernels final : public RayCastKernelSet {
public:
    std::string_view backendName() const override { return "cuda"; }

    void bind(const volume::Volume* volume) override {
        // A new copy of the same grid (the thick-slice field at a new iso-value) keeps the device's
        // buffers, which fit it as they are (cuda_zbuffer_kernels.cpp says why); volumes read
        // from host memory are let go of before that memory goes.
        const bool sameGrid = volume && m_volume && m_uploaded && !m_kernels.readsHostMemory() &&
                              volume->dims() == m_volume->dims() &&
                              volume->voxelType() == m_volume->voxelType();
        if (!sameGrid)
            m_kernels.release();
        m_volume = volume;
        m_deviceCopy = {};
        m_uploaded = false;
        m_mappedFloor = false;
        m_cap.clear();
    }

    void useDeviceCopy(DeviceVoxelCopy copy) override {
        m_deviceCopy = copy;
        if (copy.faceMaxima && m_volume)
            m_cap.useFaceMaxima(*m_volume, *copy.faceMaxima);
    }

    bool fallBack() override {
        if (m_mappedFloor)
            return false;
        m_mappedFloor = true;
        m_kernels.release(); // frees what the failed attempt holds
        m_uploaded = false;
        return true;
    }

    bool drawsPieces() const override { return true; }

    void prepare(double storedIso, const SilhouetteSettings& settings,
                 SilhouetteFrame& frame) override {
        const bool mapped = m_mappedFloor || !fitsWhole(settings);
        if (!m_uploaded || mapped != m_mapped) {
            m_uploaded = false;
            check(m_kernels.setVolume(hostVolumeView(*m_volume),
                                      kernels::cpu::voxelGridSetup(*m_volume),
                                      rayGridSetup(*m_volume), mapped, m_deviceCopy.voxels));
            m_uploaded = true;
            m_mapped = mapped;
        }
        kernels::cuda::RayCastCudaFrame timing;
        m_kernels.setGradientStencil(settings.gradientStencil);
        check(m_kernels.prepare(storedIso, timing));
        frame.times.extractMs += timing.prepareMs;
        m_storedIso = storedIso;
    }

    void drawView(const Camera& camera, const SilhouetteSettings& settings,
                  SilhouetteFrame& frame) override {
        kernels::cuda::RayCastCudaSettings rc;
        rc.visibility = settings.visibility;
        rc.alongSegment = settings.testAlongSegment;
        rc.minStrokePixels = settings.minStrokePixels;
        rc.strokeGapPixels = kStrokeGapPixels;
        const bool orthographic = camera.isOrthographic();
        kernels::cuda::RayCastCudaFrame timing;
        frame.lines = PixelMask(camera.width(), camera.height());
        const glm::dvec3 eyeOrDirection = orthographic ? -camera.forward() : camera.eye();
        // The border cap's segments, found on the host (its mesh is small), tested on the device.
        m_capSegments.clear();
        std::size_t capTriangles = 0;
        if (settings.closeAtBorder) {
            const Mesh& cap = m_cap.cap(*m_volume, m_storedIso, settings.gradientStencil);
            appendMeshSilhouette(cap, glm::vec3(eyeOrDirection), orthographic, m_capSegments);
            capTriangles = cap.triangleCount();
        }
        check(m_kernels.render(pixelCamera(camera), eyeOrDirection, orthographic, rc,
                               frame.lines.pixels().data(), timing, m_capSegments.data(),
                               m_capSegments.size()));
        frame.strokesPruned = true; // on the device, before the mask left it
        frame.triangles = timing.triangles + capTriangles;
        frame.segments = timing.segments;
        // The kernels find the segments and test them in one go: their time is visibility.
        frame.times.visibilityMs += timing.renderMs;
    }

private:
    // Whether the whole volume may go to the device: not for L, nor over the budget.
    bool fitsWhole(const SilhouetteSettings& settings) const {
        std::size_t budget = settings.gpuMemoryBudget;
        if (budget == 0) // what is free plus what this back-end holds already
            budget = defaultGpuBudget(kernels::cuda::freeDeviceBytes() + m_kernels.deviceBytes());
        return chooseResidency(m_volume->dims(), volume::voxelSize(m_volume->voxelType()), budget,
                               0, settings.brickCells > 0) == GpuResidency::WholeVolume;
    }

    const volume::Volume* m_volume = nullptr;
    DeviceVoxelCopy m_deviceCopy; // the bound voxels on the device already, or null
    kernels::cuda::RayCastSilhouetteCuda m_kernels;
    bool m_uploaded = false;
    bool m_mapped = false;      // the voxels are read from host memory
    bool m_mappedFloor = false; // ran out of device memory resident: mapped until the next volume
    double m_storedIso = 0.0;
    BorderCapCache m_cap;
    std::vector<kernels::SegmentEndpoints> m_capSegments;
};

} // namespace

std::unique_ptr<RayCastKernelSet> makeCudaRayCastKernels() {
    return std::make_unique<CudaRayCastKernels>();
}

} // namespace lw::render
