#include "device_thick_slices.h"

#include "cuda_support.h"
#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/volume/slice_distance.h"

#include <cstring>
#include <string>

namespace lw::render {

volume::Volume DeviceThickSlices::make(const volume::Volume& source, const SamplingPlan& plan,
                                       double iso, double limitMm, unsigned threads) {
    const glm::ivec3 dims = volume::oversampledDims(source.dims(), plan.factors);
    volume::checkVolumeAllocation(dims, volume::VoxelType::Int16, {}, "shape-based interpolation",
                                  "the signed-distance copy");
    volume::Volume field(dims, volume::VoxelType::Int16,
                         source.geometry().refined(plan.factors, source.dims().z));
    field.setDescription(source.description());
    makeInto(field, source, plan, iso, limitMm, threads);
    return field;
}

void DeviceThickSlices::makeInto(volume::Volume& field, const volume::Volume& source,
                                 const SamplingPlan& plan, double iso, double limitMm,
                                 unsigned threads) {
    constexpr std::string_view kWhere = "thick slices (CUDA)";
    if (field.dims() != volume::oversampledDims(source.dims(), plan.factors) ||
        field.voxelType() != volume::VoxelType::Int16)
        throw core::Error(std::string(kWhere), "the copy to write is not of this source and plan");
    if (m_uploaded != &source) {
        m_uploaded = nullptr;
        throwIfCudaFailed(kWhere, m_field.setVolume(hostVolumeView(source)));
        m_uploaded = &source;
    }
    field.setValueMapping({1.0 / volume::kSliceDistanceStepsPerMm, iso});
    kernels::cuda::ThickSliceFieldSetup setup;
    setup.slope = source.valueMapping().slope;
    setup.intercept = source.valueMapping().intercept;
    setup.spacingI = source.geometry().spacingI();
    setup.spacingJ = source.geometry().spacingJ();
    setup.limitMm = limitMm;
    setup.stepsPerMm = volume::kSliceDistanceStepsPerMm;
    setup.factors = plan.factors;
    setup.monotoneAlongSlices = plan.alongSlices == volume::SliceInterpolation::MonotoneCubic;
    throwIfCudaFailed(kWhere, m_field.make(iso, setup));
    // From page-locked memory into the volume's, in parallel: the copy's first touch of fresh
    // pages is what costs (page faults), and threads take them side by side.
    const std::int16_t* from = m_field.field();
    std::int16_t* to = field.dataAs<std::int16_t>();
    constexpr std::size_t kRun = std::size_t(1) << 20; // voxels per task: 2 MiB
    core::parallelForRanges(
        field.voxelCount(), kRun,
        [&](std::size_t begin, std::size_t end) {
            std::memcpy(to + begin, from + begin, (end - begin) * sizeof(std::int16_t));
        },
        threads);
}

} // namespace lw::render
