#include "device_thick_slices.h"

#include "cuda_support.h"
#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/cuda/page_locked_host.h"
#include "lw/volume/slice_distance.h"

#include <cstring>
#include <string>
#include <utility>

namespace lw::render {

namespace {

// The lock is destroyed first (members in reverse order): the pages are unlocked before the
// volume frees them.
struct LockedVolume {
    volume::Volume volume;
    kernels::cuda::PageLockedHostRange lock;
};

} // namespace

std::shared_ptr<volume::Volume> pageLockedVolume(volume::Volume volume, bool& locked) {
    auto holder = std::make_shared<LockedVolume>(LockedVolume{std::move(volume), {}});
    locked = holder->volume.byteSize() > 0 &&
             holder->lock.lock(holder->volume.data(), holder->volume.byteSize()).ok();
    return std::shared_ptr<volume::Volume>(holder, &holder->volume);
}

void DeviceThickSlices::makeInto(volume::Volume& field, const volume::Volume& source,
                                 const SamplingPlan& plan, double iso, double limitMm,
                                 unsigned threads, bool fieldIsPageLocked) {
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
    field.setDescription(source.description());
    kernels::cuda::ThickSliceFieldSetup setup;
    setup.slope = source.valueMapping().slope;
    setup.intercept = source.valueMapping().intercept;
    setup.spacingI = source.geometry().spacingI();
    setup.spacingJ = source.geometry().spacingJ();
    setup.limitMm = limitMm;
    setup.stepsPerMm = volume::kSliceDistanceStepsPerMm;
    setup.factors = plan.factors;
    setup.monotoneAlongSlices = plan.alongSlices == volume::SliceInterpolation::MonotoneCubic;
    setup.thinWallMm = plan.thinWallMm;
    std::int16_t* to = field.dataAs<std::int16_t>();
    throwIfCudaFailed(kWhere, m_field.make(iso, setup, fieldIsPageLocked ? to : nullptr));
    if (fieldIsPageLocked)
        return;
    // From page-locked memory into the volume's, in parallel: the copy's first touch of fresh
    // pages is what costs (page faults), and threads take them side by side.
    const std::int16_t* from = m_field.field();
    constexpr std::size_t kRun = std::size_t(1) << 20; // voxels per task: 2 MiB
    core::parallelForRanges(
        field.voxelCount(), kRun,
        [&](std::size_t begin, std::size_t end) {
            std::memcpy(to + begin, from + begin, (end - begin) * sizeof(std::int16_t));
        },
        threads);
}

} // namespace lw::render
