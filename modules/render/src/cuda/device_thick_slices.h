#pragma once

// The shape-based thick-slice copy made on the CUDA device (kernels::cuda::ThickSliceFieldCuda)
// as the render module's volume: the same geometry, value mapping and description that
// oversampledToRender gives the host's. Internal to the CUDA back-end's sources.

#include "lw/kernels/cuda/thick_slice_field_cuda.h"
#include "lw/render/surface_sampling.h"
#include "lw/volume/volume.h"

#include <array>
#include <memory>

namespace lw::render {

// `volume` moved into shared ownership with its memory page-locked for as long as it lives, where
// the driver allows (`locked` says whether it did): a copy written again and again then takes
// the device's download straight in, without a staging buffer and a copy on the host.
std::shared_ptr<volume::Volume> pageLockedVolume(volume::Volume volume, bool& locked);

class DeviceThickSlices {
public:
    // The copy of `plan` (shape-based) at `iso` of `source` into `field`, a volume of the plan's
    // refined dims, int16, and of its geometry (the geometry is not checked). The slices go to
    // the device at the first call for `source` (the caller keeps it alive and unchanged while
    // it uses this). `fieldIsPageLocked`: the download goes straight into it (pageLockedVolume),
    // else through page-locked memory and a copy on `threads` threads. Throws core::Error when
    // the device fails.
    void makeInto(volume::Volume& field, const volume::Volume& source, const SamplingPlan& plan,
                  double iso, double limitMm, unsigned threads, bool fieldIsPageLocked);
    const kernels::cuda::ThickSliceFieldTimes& times() const { return m_field.times(); }
    // The last copy in device memory, until the next makeInto().
    const void* deviceVoxels() const { return m_field.deviceField(); }
    // The last copy's largest value per face (kernels::cpu::BorderFaceMaxima's order).
    const std::array<double, 6>& faceMaxima() const { return m_field.faceMaxima(); }

private:
    kernels::cuda::ThickSliceFieldCuda m_field;
    const volume::Volume* m_uploaded = nullptr;
};

} // namespace lw::render
