#pragma once

// The shape-based thick-slice copy made on the CUDA device (kernels::cuda::ThickSliceFieldCuda)
// as the render module's volume: the same geometry, value mapping and description that
// oversampledToRender gives the host's. Internal to the CUDA back-end's sources.

#include "lw/kernels/cuda/thick_slice_field_cuda.h"
#include "lw/render/surface_sampling.h"
#include "lw/volume/volume.h"

namespace lw::render {

class DeviceThickSlices {
public:
    // The copy of `plan` (shape-based) at `iso` of `source`, whose slices go to the device at the
    // first call for it (the caller keeps `source` alive and unchanged while it uses this).
    // Throws core::Error when the device fails. `threads`: for the copy from page-locked memory.
    volume::Volume make(const volume::Volume& source, const SamplingPlan& plan, double iso,
                        double limitMm, unsigned threads);
    // The same into `field`, a copy made earlier for the same source and plan (its dims and
    // type): its pages are written again instead of fresh ones faulted in.
    void makeInto(volume::Volume& field, const volume::Volume& source, const SamplingPlan& plan,
                  double iso, double limitMm, unsigned threads);
    const kernels::cuda::ThickSliceFieldTimes& times() const { return m_field.times(); }
    // The last copy in device memory, until the next make().
    const void* deviceVoxels() const { return m_field.deviceField(); }

private:
    kernels::cuda::ThickSliceFieldCuda m_field;
    const volume::Volume* m_uploaded = nullptr;
};

} // namespace lw::render
