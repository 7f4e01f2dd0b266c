#pragma once

#include "lw/core/limits.h"
#include "lw/core/progress.h"
#include "lw/dicom/dicom_types.h"
#include "lw/volume/volume.h"

#include <string>
#include <vector>

namespace lw::dicom {

// One frame of the series placed in a volume.
struct SliceRef {
    std::size_t instance = 0; // index into SeriesInfo::instances
    int frame = 0;            // frame within that instance
    glm::dvec3 position{0.0}; // ImagePositionPatient of the frame
};

// A volume that can be assembled from (part of) a series: geometry known, pixels not read yet.
// Series are split the way dcm2niix and 3D Slicer do it: by orientation, image size, frame
// type and rescale; slices are sorted along the slice normal by position.
struct VolumePlan {
    std::string seriesInstanceUid;
    std::string label; // why this volume is separate from its siblings, empty when it is alone
    std::vector<SliceRef> slices;
    glm::ivec3 dims{0};
    volume::VoxelType voxelType = volume::VoxelType::Int16;
    volume::ValueMapping valueMapping;
    volume::VolumeGeometry geometry;
    double tiltDegrees = 0.0;     // angle between stacking direction and slice normal
    bool unevenGaps = false;      // gaps along the stack differ by more than 1%
    double minGap = 0.0;          // mm, along the stacking direction
    double maxGap = 0.0;
    int missingSlices = 0;        // estimated from gaps that are multiples of the common gap
    std::vector<std::string> transferSyntaxes; // UIDs, each once
    std::vector<std::string> warnings;
};

struct SeriesAssembly {
    std::vector<VolumePlan> volumes;
    std::vector<std::string> warnings; // e.g. "3 instances have no pixel data"
    std::vector<FileError> errors;
};

// Groups and sorts the frames of a series into volume plans (headers only, fast).
SeriesAssembly planVolumes(const SeriesInfo& series);

// Decodes the pixels of a plan into a Volume (both cores). Throws core::Error naming the file and
// the reason when a frame cannot be decoded; core::Cancelled when cancelled through `progress`.
// Before anything is allocated, the volume is checked against `limits` and every file's native
// pixel data against what its header declares (a truncated file fails first, not last).
volume::Volume loadVolume(const SeriesInfo& series, const VolumePlan& plan,
                          core::Progress* progress = nullptr,
                          const core::ImportLimits& limits = {});

// Decodes one slice of a plan (0-based along the stack) into a volume of dims (x, y, 1) with the
// plan's value mapping and that slice's geometry: thumbnails and previews without decoding the
// series. Throws core::Error naming the file, or the series for an index out of range.
volume::Volume loadSlice(const SeriesInfo& series, const VolumePlan& plan, std::size_t sliceIndex,
                         core::Progress* progress = nullptr, const core::ImportLimits& limits = {});

} // namespace lw::dicom
