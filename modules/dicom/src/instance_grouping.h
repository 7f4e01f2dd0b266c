#pragma once

// Internal to lw::dicom: reading the headers of the files a scan found and grouping the
// instances into patients, studies and series (the same for a folder, a DICOMDIR or a list).

#include "lw/core/limits.h"
#include "lw/core/progress.h"
#include "lw/dicom/dicom_scanner.h"

#include <filesystem>
#include <optional>
#include <string>
#include <tuple>
#include <vector>

namespace lw::dicom::detail {

// Optional numbers sort before "missing" so that numbered series come first.
template <typename T> std::tuple<bool, T> optionalKey(const std::optional<T>& value) {
    return {!value.has_value(), value.value_or(T{})};
}

struct HeaderResults {
    std::vector<InstanceInfo> instances;
    std::vector<FileError> errors;
    std::vector<std::string> skippedDicomdirs;
};

// Reads every file's header in parallel; DICOMDIRs met on the way are set aside, unreadable
// files become errors with the reason.
HeaderResults readHeaders(const std::vector<std::filesystem::path>& files, core::Progress* progress,
                          const core::ImportLimits& limits);

// Patients, studies and series from the instances, in a deterministic order; duplicate
// SOPInstanceUIDs and instances without a SeriesInstanceUID are reported in `warnings`.
std::vector<PatientInfo> groupInstances(std::vector<InstanceInfo> instances,
                                        std::vector<std::string>& warnings);

// Reads `files` and fills `index` (patients, errors sorted by file, skipped DICOMDIRs).
void finishIndex(DicomIndex& index, const std::vector<std::filesystem::path>& files,
                 core::Progress* progress, const core::ImportLimits& limits);

} // namespace lw::dicom::detail
