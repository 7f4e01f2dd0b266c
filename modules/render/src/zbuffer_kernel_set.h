#pragma once

// Method 3's seam between the frame logic every back-end shares (ZBufferSilhouetteRenderer: the
// mode a/b cache, whether the surface is closed, the depth tolerance, the fallback after running
// out of device memory, the host mesh for the shaded panel) and what a back-end does (this
// interface: extract, draw into the two z-buffers, resolve). One implementation per back-end:
// zbuffer_kernels_cpu.cpp, cuda/cuda_zbuffer_kernels.cpp. S is the one-piece case: a back-end
// that keeps the whole surface draws it as one piece; one that cannot (L, or a device budget too
// small for the volume) draws the pieces it streams, and both give the same image.
//
// A frame:  beginFrame -> [extractWhole when the cache is stale] -> drawWhole
//                       or drawPieces                              -> resolve

#include "lw/core/image.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/volume/volume.h"
#include "out_of_device_memory.h"

#include <cstddef>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

namespace lw::render {

class ZBufferKernelSet {
public:
    virtual ~ZBufferKernelSet() = default;
    virtual std::string_view backendName() const = 0;
    // Whether resolve() may draw into settings.frameTarget (the CUDA kernels, through CUDA-GL
    // interop); the others fill the host mask.
    virtual bool drawsToFrameTargets() const { return false; }
    // A new volume, or none: whatever was kept of the last one goes (device memory, host
    // registrations, the kept surface).
    virtual void bind(const volume::Volume* volume) = 0;
    // After bind: the bound voxels on the device already (SilhouetteRenderer::
    // setVolumeWithDeviceCopy), until the next bind. Only the CUDA kernels take it.
    virtual void useDeviceCopy(DeviceVoxelCopy /*copy*/) {}

    // Whether this frame can keep the whole surface (the CPU: always; CUDA: the volume and its
    // surface within settings.gpuMemoryBudget). When not, the frame draws pieces.
    virtual bool keepsWholeSurface(const Camera& camera, const SilhouetteSettings& settings) = 0;
    // Extracts the whole surface at `storedIso` and keeps it (closed at the border when
    // settings.closeAtBorder); returns whether it is open where the border cuts it (then back
    // faces stay). Never open when closed at the border.
    virtual bool extractWhole(double storedIso, const SilhouetteSettings& settings,
                              SilhouetteFrame& frame) = 0;
    // The kept surface on the host (downloaded on first use); null when none is kept.
    virtual const Mesh* keptMesh() = 0;
    // Only the kept surface's triangles that may hold `camera`'s contour (contour_triangles.h),
    // where it is on the device; nullopt where the host has it (keptMesh) or none is kept.
    virtual std::optional<Mesh> contourTriangles(const Camera& /*camera*/) { return std::nullopt; }

    // Clears both z-buffers at the camera's size.
    virtual void beginFrame(const Camera& camera, const SilhouetteSettings& settings,
                            SilhouetteFrame& frame) = 0;
    // The kept surface's silhouette segments and triangles into the z-buffers.
    virtual void drawWhole(const Camera& camera, const SilhouetteSettings& settings, bool closed,
                           SilhouetteFrame& frame) = 0;
    // Every piece of the surface (bricks, slabs; the border cap when settings.closeAtBorder)
    // extracted, drawn and dropped; nothing is kept but the cap.
    virtual void drawPieces(const Camera& camera, const SilhouetteSettings& settings,
                            double storedIso, bool closed, SilhouetteFrame& frame) = 0;
    // The colour pass: frame.lines from the two z-buffers.
    virtual void resolve(const SilhouetteSettings& settings, float epsilon,
                         SilhouetteFrame& frame) = 0;

    // The shaded iso panel of the kept whole surface (with its cap), drawn where the surface is:
    // only back-ends that keep it on a device do (shadesOnDevice); the others leave the panel to
    // the host mesh. `image` is sized to the camera; `depth` (optional) as shadeSurfaceCpu's.
    struct DeviceShading {
        std::size_t triangles = 0;
        double rasterMs = 0.0, shadeMs = 0.0;
    };
    virtual bool shadesOnDevice() const { return false; }
    virtual DeviceShading shadeWhole(const Camera& camera, const SurfaceShading& shading,
                                     core::ImageRgba8& image, std::vector<float>* depth);

    // After OutOfDeviceMemory: whether this back-end has a leaner way to try (CUDA: slabs after
    // the whole volume); false sends the frame to the CPU.
    virtual bool fallBack() { return false; }
};

std::unique_ptr<ZBufferKernelSet> makeCpuZBufferKernels();
// Null where this build has no CUDA back-end.
std::unique_ptr<ZBufferKernelSet> makeCudaZBufferKernels();

} // namespace lw::render
