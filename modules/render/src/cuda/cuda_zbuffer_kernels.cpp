// Method 3's CUDA kernel set (zbuffer_kernel_set.h): marching cubes and the z-buffer rasterizer
// as CUDA kernels (lw/kernels/cuda). The image equals the CPU's: both back-ends evaluate
// kernels/common's rules.
//
// Where the volume lives (gpu_memory_plan.h), decided per frame from settings.gpuMemoryBudget:
//   whole volume  uploaded once per volume; mode a keeps the surface on the device and only the
//                 view passes run per frame
//   slabs         the chunked (L) variant, and any volume too large for the budget: slabs of cell
//                 layers, cropped to the rows that can hold the surface, stream from host memory
//                 through two device slots, each slab's mesh drawn into the shared z-buffers and
//                 dropped, unless the budget holds it: the slabs' meshes are kept on the device
//                 while they fit in the half of the budget left to them, so a new view of the
//                 same surface draws the kept ones and streams only the rest (the CPU's L
//                 re-extracts every frame; the image is the same)
// A frame over the budget or out of device memory throws OutOfDeviceMemory: the renderer asks
// fallBack() (whole volume -> slabs) and then goes to the CPU.
//
// The shaded iso panel (shadeWhole) rasterizes the same kept surface at the panel's camera and
// lights it on the device; only the image and its depth come to the host.
//
// The colour pass writes the host mask, or, given a frame target (the GUI's silhouette panel),
// the GL texture straight through CUDA-GL interop. Where interop fails (no GL context current, a
// context on another device, a build without interop) the mask goes through host memory from
// then on, logged once.
#include "../view_transform.h"
#include "../zbuffer_kernel_set.h"
#include "cuda_support.h"
#include "device_surface_shader.h"
#include "lw/core/log.h"
#include "lw/kernels/cpu/border_cap_cpu.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cuda/cuda_device.h"
#include "lw/kernels/cuda/device_mesh_store.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/cuda/zbuffer_cuda.h"
#include "lw/render/gl_frame_target.h"
#include "lw/render/gpu_memory_plan.h"

#if LINEWORK_CUDA_GL_INTEROP
#include "lw/kernels/cuda/gl_texture_interop.h"
#endif

#include <algorithm>
#include <chrono>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace lw::render {
namespace {

using kernels::cuda::CudaStatus;
constexpr std::string_view kWhere = "method 3 (CUDA)";
constexpr core::LogCategory kLog("lw.render");

#if LINEWORK_CUDA_GL_INTEROP
// A frame target's CUDA registration, owned by the target so that it goes before the texture.
struct CudaTextureAttachment final : GlFrameTarget::Attachment {
    kernels::cuda::GlTextureInterop interop;
};
#endif

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

// A failed status: out of memory goes down a way, anything else is an error naming the kernel.
void check(const CudaStatus& status) {
    if (status.code == CudaStatus::Code::OutOfMemory)
        throw OutOfDeviceMemory(status.describe());
    throwIfCudaFailed(kWhere, status);
}

class CudaZBufferKernels final : public ZBufferKernelSet {
public:
    std::string_view backendName() const override { return "cuda"; }
    bool drawsToFrameTargets() const override { return true; }

    void bind(const volume::Volume* volume) override {
        if (keepsBuffersFor(volume)) {
            m_shading.forgetCap();
        } else {
            m_marchingCubes.release(); // device buffers and a streamed volume's host registration
            m_zbuffer.release();
            m_shading.release();
            m_contour.release();
        }
        m_volume = volume;
        m_deviceCopy = {};
        m_resident = GpuResidency::Cpu;
        m_floor = GpuResidency::WholeVolume;
        m_rowRanges.reset();
        m_croppedIso = std::numeric_limits<double>::quiet_NaN();
        m_hostMeshValid = false;
        m_cap.clear();
        m_capKept = nullptr;
        m_capKeptOnDevice = false;
        forgetKeptSlabs();
    }

    void useDeviceCopy(DeviceVoxelCopy copy) override {
        m_deviceCopy = copy;
        if (copy.faceMaxima && m_volume)
            m_cap.useFaceMaxima(*m_volume, *copy.faceMaxima);
    }

    // A new copy of the same grid (the thick-slice field at a new iso-value) after a resident
    // whole volume: the device's buffers fit it as they are, and freeing and allocating them
    // again (cudaFree waits for the device) cost more than its frame. The voxels go up again at
    // the next extraction; a streamed volume's host registration is released in any case.
    bool keepsBuffersFor(const volume::Volume* volume) const {
        return volume && m_volume && m_resident == GpuResidency::WholeVolume &&
               volume->dims() == m_volume->dims() && volume->voxelType() == m_volume->voxelType();
    }

    bool keepsWholeSurface(const Camera& camera, const SilhouetteSettings& settings) override {
        const GpuResidency where =
            chooseResidency(m_volume->dims(), volume::voxelSize(m_volume->voxelType()), m_budget,
                            imageBytes(camera, settings), false);
        return where == GpuResidency::WholeVolume && m_floor == GpuResidency::WholeVolume;
    }

    bool extractWhole(double storedIso, const SilhouetteSettings& settings,
                      SilhouetteFrame& frame) override {
        m_hostMeshValid = false;
        if (m_resident != GpuResidency::WholeVolume) {
            m_resident = GpuResidency::Cpu;
            check(placeWholeVolume(m_marchingCubes, *m_volume, m_deviceCopy));
            m_resident = GpuResidency::WholeVolume;
        }
        m_capKept = nullptr;
        m_capKeptOnDevice = false;
        m_shading.forgetCap();
        forgetKeptSlabs(); // the cap on the device is the whole surface's from now on
        m_marchingCubes.setGradientStencil(settings.gradientStencil);
        check(m_marchingCubes.extract(storedIso));
        frame.times.extractMs += m_marchingCubes.times().totalMs();
        if (settings.closeAtBorder) {
            m_capKept = &m_cap.cap(*m_volume, storedIso, settings.gradientStencil);
            return false;
        }
        return m_marchingCubes.mesh().touchesBorder;
    }

    const Mesh* keptMesh() override {
        if (m_resident != GpuResidency::WholeVolume)
            return nullptr;
        if (!m_hostMeshValid) {
            downloadSurface(kWhere, m_marchingCubes, m_capKept, m_hostMesh);
            m_hostMeshValid = true;
        }
        return &m_hostMesh;
    }

    std::optional<Mesh> contourTriangles(const Camera& camera) override {
        if (m_resident != GpuResidency::WholeVolume)
            return std::nullopt;
        Mesh part;
        check(downloadContourTriangles(m_contour, m_marchingCubes, m_capKept, camera, part));
        return part;
    }

    void beginFrame(const Camera& camera, const SilhouetteSettings& settings,
                    SilhouetteFrame&) override {
        m_budget = settings.gpuMemoryBudget;
        if (m_budget == 0) // what is free plus what this back-end holds already
            m_budget = defaultGpuBudget(kernels::cuda::freeDeviceBytes() +
                                        m_marchingCubes.deviceBytes() + m_zbuffer.deviceBytes());
        m_timing = kernels::cuda::ZBufferCudaFrame();
        m_draw = kernels::cuda::ZBufferCudaSettings();
        m_draw.visibility = settings.visibility;
        m_draw.minStrokePixels = settings.minStrokePixels;
        m_draw.strokeGapPixels = kStrokeGapPixels;
        m_width = camera.width();
        m_height = camera.height();
        check(m_zbuffer.begin(toViewTransform(camera)));
    }

    void drawWhole(const Camera&, const SilhouetteSettings&, bool closed,
                   SilhouetteFrame& frame) override {
        const kernels::cuda::DeviceMeshView mesh = m_marchingCubes.mesh();
        m_draw.cullBackFaces = closed;
        check(m_zbuffer.draw(mesh, m_draw, m_timing));
        frame.triangles = mesh.triangleCount;
        if (m_capKept) {
            if (!m_capKeptOnDevice) // once per kept surface: mode a only turns the camera
                check(m_zbuffer.keepHostMesh(*m_capKept));
            m_capKeptOnDevice = true;
            check(m_zbuffer.drawKeptHostMesh(m_draw, m_timing));
            frame.triangles += m_capKept->triangleCount();
        }
    }

    void drawPieces(const Camera& camera, const SilhouetteSettings& settings, double storedIso,
                    bool closed, SilhouetteFrame& frame) override;

    void resolve(const SilhouetteSettings& settings, float epsilon,
                 SilhouetteFrame& frame) override {
        m_draw.epsilon = epsilon;
        frame.drewToTarget = resolveIntoTarget(settings);
        if (!frame.drewToTarget) {
            frame.lines = PixelMask(m_width, m_height);
            check(m_zbuffer.resolve(m_draw, frame.lines.pixels().data(), m_timing));
        }
        frame.strokesPruned = true; // on the device, before the mask left it
        frame.segments = m_timing.segments;
        // The silhouette and the surface's depth are one pass on the device (visibilityMs 0).
        frame.times.silhouetteMs += m_timing.projectMs + m_timing.drawMs;
        frame.times.drawMs += m_timing.resolveMs;
        frame.deviceBytes = m_marchingCubes.peakDeviceBytes() + m_zbuffer.deviceBytes() +
                            m_keptSlabs.deviceBytes() + m_shading.deviceBytes();
        // The budget is a limit, not a hint: a frame that held more (the whole volume's overhead
        // is an estimate) counts as out of memory, and the frame goes the next way down.
        if (frame.deviceBytes > m_budget)
            throw OutOfDeviceMemory("the frame held " + std::to_string(frame.deviceBytes >> 20) +
                                    " MiB, over the budget of " + std::to_string(m_budget >> 20) +
                                    " MiB");
    }

    bool shadesOnDevice() const override { return true; }
    DeviceShading shadeWhole(const Camera& camera, const SurfaceShading& shading,
                             core::ImageRgba8& image, std::vector<float>* depth) override;

    bool fallBack() override {
        if (m_floor != GpuResidency::WholeVolume)
            return false;
        m_floor = afterOutOfMemory(m_floor);
        m_marchingCubes.release(); // free what the failed attempt holds before slabs allocate
        m_zbuffer.release();
        m_shading.release();
        m_contour.release();
        m_capKeptOnDevice = false;
        forgetKeptSlabs();
        m_resident = GpuResidency::Cpu;
        return true;
    }

private:
    bool resolveIntoTarget(const SilhouetteSettings& settings);
    // zbuffer1, zbuffer2 (4 bytes a pixel each) and the mask; stroke pruning's labels and group
    // sizes (4 bytes a pixel each) when it runs.
    static std::size_t imageBytes(const Camera& camera, const SilhouetteSettings& settings) {
        const std::size_t perPixel = settings.minStrokePixels > 1 ? 17 : 9;
        return std::size_t(camera.width()) * std::size_t(camera.height()) * perPixel;
    }
    const std::vector<kernels::CellSlab>& slabsOf(const std::vector<glm::ivec2>& layers,
                                                  double storedIso);
    void forgetKeptSlabs() {
        m_keptSlabs.clear();
        m_keptSlabEnd = 0;
        m_keptFor = KeptSlabsKey();
    }
    CudaStatus keepSlab(std::size_t slab, const kernels::cuda::DeviceMeshView& mesh,
                        std::size_t streamingReserve);
    void drawKeptSlabs(SilhouetteFrame& frame);

    const volume::Volume* m_volume = nullptr;
    DeviceVoxelCopy m_deviceCopy; // the bound voxels on the device already, or null
    kernels::cuda::MarchingCubesCuda m_marchingCubes;
    kernels::cuda::ZBufferCuda m_zbuffer;
    DeviceSurfaceShader m_shading;                    // the iso panel's rasterizer
    kernels::cuda::ContourTrianglesCuda m_contour;    // the exports' lines' triangles
    GpuResidency m_resident = GpuResidency::Cpu;      // where the voxels are now
    GpuResidency m_floor = GpuResidency::WholeVolume; // raised by fallBack until the next volume
    std::size_t m_budget = 0;
    Mesh m_hostMesh;
    bool m_hostMeshValid = false;
    // The border cap (settings.closeAtBorder): drawn after the kept mesh or the last slab.
    BorderCapCache m_cap;
    const Mesh* m_capKept = nullptr; // with the kept whole mesh, if closed
    bool m_capKeptOnDevice = false;  // m_zbuffer holds m_capKept's copy

    // This frame's draw settings, timings and size.
    kernels::cuda::ZBufferCudaSettings m_draw;
    kernels::cuda::ZBufferCudaFrame m_timing;
    int m_width = 0, m_height = 0;
    // Set when writing a frame target failed: from then on the mask goes through host memory.
    bool m_targetUnavailable = false;
    // Slabs: the voxel rows' value ranges (once per volume) and the last cropped slabs, reused
    // while the iso-value and the layer plan stay (an orbit).
    std::unique_ptr<VoxelRowRanges> m_rowRanges;
    std::vector<glm::ivec2> m_plannedLayers;
    double m_croppedIso = std::numeric_limits<double>::quiet_NaN();
    std::vector<kernels::CellSlab> m_croppedSlabs;
    // Slab meshes kept on the device for the next view: those of m_croppedSlabs[0, m_keptSlabEnd)
    // (in order; slabs without triangles have none), made for m_keptFor.
    struct KeptSlabsKey {
        double storedIso = std::numeric_limits<double>::quiet_NaN();
        std::vector<glm::ivec2> layers;
        kernels::GradientStencil stencil = kernels::GradientStencil::Central;
        bool operator==(const KeptSlabsKey& o) const {
            return storedIso == o.storedIso && layers == o.layers && stencil == o.stencil;
        }
    };
    kernels::cuda::DeviceMeshStore m_keptSlabs;
    std::size_t m_keptSlabEnd = 0;
    bool m_keeping = false; // this frame still keeps the slabs it extracts
    KeptSlabsKey m_keptFor;
};

// The colour pass into settings.frameTarget where it applies; false: the caller resolves into
// host memory (the z-buffers are untouched by a failed attempt).
bool CudaZBufferKernels::resolveIntoTarget(const SilhouetteSettings& settings) {
    GlFrameTarget* target = settings.frameTarget;
    if (m_targetUnavailable || !target ||
        frameTargetUse({target->width(), target->height()}, {m_width, m_height}) !=
            FrameTargetUse::Texture)
        return false;
#if LINEWORK_CUDA_GL_INTEROP
    auto* attachment = dynamic_cast<CudaTextureAttachment*>(target->attachment());
    if (!attachment) {
        auto made = std::make_unique<CudaTextureAttachment>();
        attachment = made.get();
        target->setAttachment(std::move(made));
    }
    CudaStatus status =
        attachment->interop.attach(target->texture(), target->width(), target->height());
    if (status.ok())
        status = m_zbuffer.resolveInto(m_draw, attachment->interop, m_timing);
    if (status.ok())
        return true;
    // Out of memory (pruning's buffers are allocated in the compose) is no interop failure: the
    // frame goes the next way down like any other, and the texture stays usable.
    if (status.code == CudaStatus::Code::OutOfMemory)
        check(status);
    target->setAttachment(nullptr);
    const std::string reason = status.describe();
#else
    const std::string reason = "this build has no CUDA-GL interop";
#endif
    m_targetUnavailable = true;
    kLog.warning("method 3 (CUDA): the silhouette cannot be written into the GL texture (" +
                 reason + "); it goes through host memory");
    return false;
}

ZBufferKernelSet::DeviceShading CudaZBufferKernels::shadeWhole(const Camera& camera,
                                                               const SurfaceShading& shading,
                                                               core::ImageRgba8& image,
                                                               std::vector<float>* depth) {
    if (m_resident != GpuResidency::WholeVolume)
        throw core::Error(std::string(kWhere), "no whole surface is kept on the device to shade");
    DeviceSurfaceShader::Shaded shaded;
    check(
        m_shading.shade(camera, shading, m_marchingCubes.mesh(), m_capKept, image, depth, shaded));
    return {shaded.triangles, shaded.rasterMs, shaded.shadeMs};
}

const std::vector<kernels::CellSlab>&
CudaZBufferKernels::slabsOf(const std::vector<glm::ivec2>& layers, double storedIso) {
    if (!m_rowRanges)
        m_rowRanges = std::make_unique<VoxelRowRanges>(*m_volume);
    if (!(m_croppedIso == storedIso) || layers != m_plannedLayers) {
        m_croppedSlabs = cropSlabsToSurface(layers, *m_rowRanges, storedIso);
        m_plannedLayers = layers;
        m_croppedIso = storedIso;
    }
    return m_croppedSlabs;
}

// Keeps slab `slab`'s mesh when it extends the kept run and fits: the kept meshes, the z-buffers
// and the streaming's working set (the larger of what it held and what the plan allows it) stay
// within the budget.
CudaStatus CudaZBufferKernels::keepSlab(std::size_t slab, const kernels::cuda::DeviceMeshView& mesh,
                                        std::size_t streamingReserve) {
    if (!m_keeping)
        return CudaStatus::success();
    const std::size_t held = m_keptSlabs.deviceBytes() + m_zbuffer.deviceBytes() +
                             std::max(streamingReserve, m_marchingCubes.peakDeviceBytes());
    if (held + kernels::cuda::DeviceMeshStore::bytesOf(mesh) > m_budget) {
        m_keeping = false; // the kept run ends here: later slabs stream every frame
        return CudaStatus::success();
    }
    const CudaStatus kept = m_keptSlabs.keep(mesh);
    if (kept.code == CudaStatus::Code::OutOfMemory) { // the device has less than the budget says
        m_keeping = false;
        return CudaStatus::success();
    }
    if (kept.ok())
        m_keptSlabEnd = slab + 1;
    return kept;
}

void CudaZBufferKernels::drawKeptSlabs(SilhouetteFrame& frame) {
    for (std::size_t i = 0; i < m_keptSlabs.count(); ++i) {
        const kernels::cuda::DeviceMeshView& mesh = m_keptSlabs.mesh(i);
        frame.triangles += mesh.triangleCount;
        check(m_zbuffer.draw(mesh, m_draw, m_timing));
    }
}

void CudaZBufferKernels::drawPieces(const Camera& camera, const SilhouetteSettings& settings,
                                    double storedIso, bool closed, SilhouetteFrame& frame) {
    m_hostMeshValid = false;
    if (m_resident != GpuResidency::Slabs) {
        forgetKeptSlabs();
        m_resident = GpuResidency::Cpu;
        check(m_marchingCubes.setStreamedVolume(hostVolumeView(*m_volume),
                                                kernels::cpu::voxelGridSetup(*m_volume)));
        m_resident = GpuResidency::Slabs;
    }
    // Half of the budget beyond the images goes to streaming, half to the kept slab meshes.
    const std::size_t images = imageBytes(camera, settings);
    const std::size_t keptShare = m_budget > images ? (m_budget - images) / 2 : 0;
    const std::size_t voxelBytes = volume::voxelSize(m_volume->voxelType());
    const std::vector<glm::ivec2> layers = planSlabs(m_volume->dims(), voxelBytes, m_budget,
                                                     images + keptShare, settings.gpuSlabLayers);
    const KeptSlabsKey key{storedIso, layers, settings.gradientStencil};
    const bool everyFrame = settings.mode == ExtractionMode::EveryFrameB;
    if (everyFrame || !(key == m_keptFor)) {
        // Mode b extracts every frame as a new iso-value would, and keeps nothing.
        forgetKeptSlabs();
        if (!everyFrame)
            m_keptFor = key;
        m_capKeptOnDevice = false;
        m_keeping = !everyFrame;
    }
    int thickest = 0;
    for (const glm::ivec2& range : layers)
        thickest = std::max(thickest, range.y - range.x);
    const std::size_t streamingReserve =
        std::size_t(kSlabOverhead * double(thickest + 3) * double(m_volume->dims().x) *
                    double(m_volume->dims().y) * double(voxelBytes));
    m_draw.cullBackFaces = closed;
    m_marchingCubes.setGradientStencil(settings.gradientStencil);
    const auto start = std::chrono::steady_clock::now();
    drawKeptSlabs(frame);
    const std::vector<kernels::CellSlab>& slabs = slabsOf(layers, storedIso);
    const std::vector<kernels::CellSlab> streamed(slabs.begin() + std::ptrdiff_t(m_keptSlabEnd),
                                                  slabs.end());
    const std::size_t first = m_keptSlabEnd;
    check(m_marchingCubes.extractSlabs(
        storedIso, streamed, [&](std::size_t k, const kernels::cuda::DeviceMeshView& slab) {
            frame.triangles += slab.triangleCount;
            LW_RETURN_IF_FAILED(m_zbuffer.draw(slab, m_draw, m_timing));
            // The slab's buffers are the next slab's: the draw must be done with them.
            LW_RETURN_IF_FAILED(m_zbuffer.waitForDraws(m_timing));
            return keepSlab(first + k, slab, streamingReserve);
        }));
    if (m_keeping) // every slab is kept, the empty ones too: a new view streams nothing
        m_keptSlabEnd = slabs.size();
    m_keeping = false;
    if (settings.closeAtBorder) {
        const Mesh& cap = m_cap.cap(*m_volume, storedIso, settings.gradientStencil);
        if (!m_capKeptOnDevice) // once per kept surface, like the slabs
            check(m_zbuffer.keepHostMesh(cap));
        m_capKeptOnDevice = true;
        check(m_zbuffer.drawKeptHostMesh(m_draw, m_timing));
        frame.triangles += cap.triangleCount();
    }
    check(m_zbuffer.waitForDraws(m_timing));
    // The slabs' extraction and drawing interleave: extraction is the loop's wall time less the
    // drawing kernels' time.
    const double drawn = m_timing.projectMs + m_timing.drawMs;
    frame.times.extractMs += std::max(0.0, msSince(start) - drawn);
}

} // namespace

std::unique_ptr<ZBufferKernelSet> makeCudaZBufferKernels() {
    return std::make_unique<CudaZBufferKernels>();
}

} // namespace lw::render
