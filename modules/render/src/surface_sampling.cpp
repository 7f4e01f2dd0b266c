#include "lw/render/surface_sampling.h"

#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/volume/oversampling.h"
#include "lw/volume/slice_bridging.h"
#include "lw/volume/slice_distance.h"

#if LINEWORK_CUDA
#include "cuda/device_thick_slices.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lw::render {
namespace {
constexpr core::LogCategory kLog("lw.render");

// A number as the log shows it (300.5, not 300.500000).
std::string shortNumber(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

// The shape-based field's limit: one slice step along the normal (volume/slice_distance.h).
double distanceLimit(const volume::Volume& volume) {
    return kThickSliceDistanceLimitSteps * std::abs(volume.geometry().sliceStepAlongNormal());
}

} // namespace

std::string_view oversamplingName(Oversampling oversampling) {
    return oversampling == Oversampling::Auto ? "auto" : "off";
}

std::optional<Oversampling> parseOversampling(std::string_view name) {
    if (name == "auto")
        return Oversampling::Auto;
    if (name == "off")
        return Oversampling::Off;
    return std::nullopt;
}

std::string_view thickSlicesName(ThickSlices thickSlices) {
    return thickSlices == ThickSlices::Smooth ? "smooth" : "linear";
}

std::optional<ThickSlices> parseThickSlices(std::string_view name) {
    if (name == "smooth")
        return ThickSlices::Smooth;
    if (name == "linear")
        return ThickSlices::Linear;
    return std::nullopt;
}

bool hasThickSlices(glm::ivec3 dims, const volume::VolumeGeometry& geometry) {
    const double pixel = std::min(geometry.spacingI(), geometry.spacingJ());
    return dims.z >= 3 && pixel > 0.0 &&
           std::abs(geometry.sliceStepAlongNormal()) >= kThickSliceOverPixel * pixel;
}

SamplingPlan samplingPlan(glm::ivec3 dims, const volume::VolumeGeometry& geometry,
                          VolumeSampling sampling) {
    SamplingPlan plan;
    plan.factors = oversamplingFactors(dims, geometry, sampling.oversampling);
    if (sampling.thickSlices == ThickSlices::Smooth && hasThickSlices(dims, geometry)) {
        plan.factors.z = std::max(plan.factors.z, kThickSliceFactor);
        plan.shapeBased = true;
        plan.alongSlices = volume::SliceInterpolation::MonotoneCubic;
        plan.thinWallMm = sampling.thinWallMm;
    }
    return plan;
}

glm::ivec3 oversamplingFactors(glm::ivec3 dims, const volume::VolumeGeometry& geometry,
                               Oversampling oversampling) {
    glm::ivec3 factors(1);
    if (oversampling == Oversampling::Off || dims.x < 1 || dims.y < 1 || dims.z < 1)
        return factors;
    const glm::dvec3 last(std::max(dims.x - 1, 0), std::max(dims.y - 1, 0),
                          std::max(dims.z - 1, 0));
    const double diagonal =
        glm::length(geometry.indexToPatient(last) - geometry.indexToPatient(glm::dvec3(0.0)));
    if (!(diagonal > 0.0))
        return factors;
    const double largestCell = diagonal / kOversamplingCellsPerDiagonal;
    const glm::dvec3 cell(geometry.spacingI(), geometry.spacingJ(), std::abs(geometry.sliceStep()));
    for (int axis = 0; axis < 3; ++axis) {
        if (dims[axis] < 2 || !(cell[axis] > largestCell))
            continue;
        const double needed = std::ceil(cell[axis] / largestCell);
        factors[axis] = int(std::min(needed, double(kMaxOversamplingFactor)));
    }
    return factors;
}

namespace {

void logResampled(const SamplingPlan& plan, double iso, glm::ivec3 dims, double ms,
                  const std::string& where) {
    const glm::ivec3 factors = plan.factors;
    kLog.info("oversampled " + std::to_string(factors.x) + "x" + std::to_string(factors.y) + "x" +
              std::to_string(factors.z) + " for rendering (cells at most 1/" +
              std::to_string(int(kOversamplingCellsPerDiagonal)) + " of the diagonal" +
              (plan.shapeBased
                   ? "; thick slices by shape-based interpolation at " + shortNumber(iso)
                   : std::string()) +
              "): " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
              std::to_string(dims.z) + " in " + std::to_string(int(ms)) + " ms" + where);
}

double msSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
        .count();
}

} // namespace

namespace {

// Whether the shape-based field can be written in one volume: refined along the slices only, as
// thick slices are (their pixels are fine already).
bool refinesAlongSlicesOnly(const SamplingPlan& plan) {
    return plan.shapeBased && plan.factors.x == 1 && plan.factors.y == 1;
}

// The shape-based field of `source` at `iso` into `field` (int16, of the plan's refined size):
// the distances into every factor-th slice, then the slices between refined in place -- what
// oversampled(signedSliceDistance(...)) makes, bit for bit, without a second volume written and
// read (volume/slice_distance.h, volume/oversampling.h).
void writeShapeBasedField(volume::Volume& field, const volume::Volume& source,
                          const SamplingPlan& plan, double iso, unsigned threads) {
    volume::writeSignedSliceDistance(source, iso, distanceLimit(source), plan.factors.z, field,
                                     threads);
    volume::refineBetweenSlices(field, plan.factors.z, threads, plan.alongSlices);
    volume::bridgeThinWalls(field, plan.factors.z, distanceLimit(source), plan.thinWallMm, threads);
    field.setValueMapping({1.0 / volume::kSliceDistanceStepsPerMm, iso});
    field.setDescription(source.description());
}

// A new volume for the shape-based field of `source` under `plan`.
volume::Volume shapeBasedFieldVolume(const volume::Volume& source, const SamplingPlan& plan) {
    const glm::ivec3 dims = volume::oversampledDims(source.dims(), plan.factors);
    volume::checkVolumeAllocation(dims, volume::VoxelType::Int16, {}, "shape-based interpolation",
                                  "the thick-slice field");
    return volume::Volume(dims, volume::VoxelType::Int16,
                          source.geometry().refined(plan.factors, source.dims().z));
}

} // namespace

std::optional<volume::Volume> oversampledToRender(const volume::Volume& volume,
                                                  VolumeSampling sampling, double iso,
                                                  unsigned threads) {
    const SamplingPlan plan = samplingPlan(volume.dims(), volume.geometry(), sampling);
    if (plan.asLoaded())
        return std::nullopt;
    const auto start = std::chrono::steady_clock::now();
    std::optional<volume::Volume> finer;
    if (refinesAlongSlicesOnly(plan)) {
        finer = shapeBasedFieldVolume(volume, plan);
        writeShapeBasedField(*finer, volume, plan, iso, threads);
    } else if (plan.shapeBased) {
        finer = volume::oversampled(
            volume::signedSliceDistance(volume, iso, distanceLimit(volume), threads), plan.factors,
            threads, plan.alongSlices);
        volume::bridgeThinWalls(*finer, plan.factors.z, distanceLimit(volume), plan.thinWallMm,
                                threads);
    } else {
        finer = volume::oversampled(volume, plan.factors, threads, plan.alongSlices);
    }
    logResampled(plan, iso, finer->dims(), msSince(start), "");
    return finer;
}

std::shared_ptr<const volume::Volume> volumeToRender(std::shared_ptr<const volume::Volume> volume,
                                                     VolumeSampling sampling, double iso,
                                                     unsigned threads) {
    if (!volume)
        return volume;
    std::optional<volume::Volume> finer = oversampledToRender(*volume, sampling, iso, threads);
    if (!finer)
        return volume;
    return std::make_shared<const volume::Volume>(std::move(*finer));
}

struct DrawnVolumeMaker::Impl {
    std::shared_ptr<const volume::Volume> source;
    bool onDevice = false; // the shape-based field is made on the CUDA device
    bool lastOnDevice = false;
    std::string note;
    // The shape-based copies made, kept to be written again once nobody else holds them: a 43 MB
    // copy into fresh pages costs its page faults at every iso-value, several ms. During a drag
    // the frame on screen and the one being drawn hold theirs; the one before is free. At most
    // kKeptCopies. The device path's are page-locked where the driver allows, so that its
    // download goes straight into them.
    struct KeptCopy {
        std::shared_ptr<volume::Volume> volume;
        bool pageLocked = false;
    };
    std::vector<KeptCopy> copies;
    static constexpr std::size_t kKeptCopies = 3;

    // A kept copy of `dims` nobody else holds (the others nobody holds go), or none.
    std::optional<KeptCopy> freeCopy(glm::ivec3 dims) {
        std::optional<KeptCopy> found;
        std::erase_if(copies, [&](const KeptCopy& copy) {
            if (copy.volume.use_count() != 1)
                return false;
            if (!found && copy.volume->dims() == dims) {
                found = copy;
                return false;
            }
            return true;
        });
        return found;
    }

    void keep(const KeptCopy& copy) {
        if (copies.size() >= kKeptCopies)
            copies.erase(copies.begin()); // the oldest: its holders keep it alive
        copies.push_back(copy);
    }

    // The shape-based field made on the host into a kept copy (or a new one, then kept).
    std::shared_ptr<const volume::Volume> onTheHost(const SamplingPlan& plan, double iso,
                                                    unsigned threads) {
        const auto start = std::chrono::steady_clock::now();
        std::optional<KeptCopy> copy =
            freeCopy(volume::oversampledDims(source->dims(), plan.factors));
        if (!copy) {
            copy = KeptCopy{std::make_shared<volume::Volume>(shapeBasedFieldVolume(*source, plan))};
            keep(*copy);
        }
        writeShapeBasedField(*copy->volume, *source, plan, iso, threads);
        logResampled(plan, iso, copy->volume->dims(), msSince(start), "");
        return copy->volume;
    }

#if LINEWORK_CUDA
    DeviceThickSlices device;

    std::shared_ptr<volume::Volume> deviceCopy(const SamplingPlan& plan, double iso,
                                               unsigned threads) {
        std::optional<KeptCopy> copy =
            freeCopy(volume::oversampledDims(source->dims(), plan.factors));
        if (!copy) {
            copy.emplace();
            copy->volume = pageLockedVolume(shapeBasedFieldVolume(*source, plan), copy->pageLocked);
            keep(*copy);
        }
        device.makeInto(*copy->volume, *source, plan, iso, distanceLimit(*source), threads,
                        copy->pageLocked);
        return copy->volume;
    }
#endif

    // The shape-based copy made on the device, or null (the device failed: from now on the
    // host makes it).
    std::shared_ptr<const volume::Volume> onTheDevice(const SamplingPlan& plan, double iso,
                                                      unsigned threads) {
#if LINEWORK_CUDA
        try {
            const auto start = std::chrono::steady_clock::now();
            std::shared_ptr<const volume::Volume> field = deviceCopy(plan, iso, threads);
            const kernels::cuda::ThickSliceFieldTimes& t = device.times();
            logResampled(plan, iso, field->dims(), msSince(start),
                         " on the CUDA device (distances " + shortNumber(t.distanceMs) +
                             " ms, refinement " + shortNumber(t.refineMs) + " ms, download " +
                             shortNumber(t.downloadMs) + " ms)");
            return field;
        } catch (const core::Error& error) {
            onDevice = false;
            note = std::string("thick slices on the host: ") + error.what();
            kLog.warning(note);
        }
#else
        (void)plan;
        (void)iso;
        (void)threads;
#endif
        return nullptr;
    }
};

DrawnVolumeMaker::DrawnVolumeMaker(std::shared_ptr<const volume::Volume> source, Backend backend)
    : m_impl(std::make_unique<Impl>()) {
    m_impl->source = std::move(source);
    // Not for the CPU back-end; where Cuda is asked for and no device is there, the renderers
    // say so themselves, and the host makes the field.
    m_impl->onDevice = backend != Backend::Cpu && cudaAvailability().available;
}

DrawnVolumeMaker::~DrawnVolumeMaker() = default;

std::shared_ptr<const volume::Volume> DrawnVolumeMaker::make(VolumeSampling sampling, double iso,
                                                             unsigned threads) {
    Impl& d = *m_impl;
    d.lastOnDevice = false;
    if (!d.source)
        return d.source;
    const SamplingPlan plan = samplingPlan(d.source->dims(), d.source->geometry(), sampling);
    if (plan.shapeBased && d.onDevice) {
        if (std::shared_ptr<const volume::Volume> field = d.onTheDevice(plan, iso, threads)) {
            d.lastOnDevice = true;
            return field;
        }
    }
    if (refinesAlongSlicesOnly(plan))
        return d.onTheHost(plan, iso, threads);
    return volumeToRender(d.source, sampling, iso, threads);
}

bool DrawnVolumeMaker::lastMadeOnDevice() const {
    return m_impl->lastOnDevice;
}

DeviceVoxelCopy DrawnVolumeMaker::deviceCopy() const {
#if LINEWORK_CUDA
    if (m_impl->lastOnDevice)
        return {m_impl->device.deviceVoxels(), m_impl->device.faceMaxima()};
#endif
    return {};
}

DeviceCopyTimes DrawnVolumeMaker::lastDeviceTimes() const {
#if LINEWORK_CUDA
    if (m_impl->lastOnDevice) {
        const kernels::cuda::ThickSliceFieldTimes& t = m_impl->device.times();
        return {t.distanceMs, t.refineMs, t.downloadMs};
    }
#endif
    return {};
}

std::string DrawnVolumeMaker::takeNote() {
    return std::exchange(m_impl->note, std::string());
}

} // namespace lw::render
