#pragma once

// Method 2's seam between the frame logic every back-end shares (RayCastSilhouetteRenderer: when
// the active cells must be found again, which back-end draws an L frame, the fall back after
// running out of device memory) and what a back-end does (this interface). One implementation
// per back-end: raycast_kernels_cpu.cpp, cuda/cuda_raycast_kernels.cpp.
//
// A frame:  [prepare when the cells are stale: the active cells at the iso-value, view
//            independent] -> drawView (segments for the eye, the ray visibility test, the lines)

#include "lw/render/camera.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/volume/volume.h"
#include "out_of_device_memory.h"

#include <memory>
#include <string_view>

namespace lw::render {

class RayCastKernelSet {
public:
    virtual ~RayCastKernelSet() = default;
    virtual std::string_view backendName() const = 0;
    // A new volume, or none: whatever was kept of the last one goes.
    virtual void bind(const volume::Volume* volume) = 0;
    // After bind: the bound voxels on the device already (SilhouetteRenderer::
    // setVolumeWithDeviceCopy), until the next bind. Only the CUDA kernels take it.
    virtual void useDeviceCopy(DeviceVoxelCopy /*copy*/) {}
    // Whether it can draw the chunked (L) variant itself (the CPU: brick by brick; CUDA: with the
    // volume left in host memory, mapped).
    virtual bool drawsPieces() const = 0;
    // After OutOfDeviceMemory: whether this back-end has a leaner way to try (CUDA: the volume
    // mapped from host memory); false sends the frame to the CPU.
    virtual bool fallBack() { return false; }
    // The active cells at `storedIso` (settings.brickCells: the brick schedule; mode a: with the
    // normal cones that let later views skip cells).
    virtual void prepare(double storedIso, const SilhouetteSettings& settings,
                         SilhouetteFrame& frame) = 0;
    // The prepared cells' segments for the camera, their visibility and the lines, into frame.
    virtual void drawView(const Camera& camera, const SilhouetteSettings& settings,
                          SilhouetteFrame& frame) = 0;
};

// The CPU's kernel set also answers the questions the tests and tools ask of the last frame.
class CpuRayCastKernels;
std::unique_ptr<CpuRayCastKernels> makeCpuRayCastKernels();
// Null where this build has no CUDA back-end. Its failures: core::Error, or OutOfDeviceMemory
// when the device ran out of memory.
std::unique_ptr<RayCastKernelSet> makeCudaRayCastKernels();

} // namespace lw::render
