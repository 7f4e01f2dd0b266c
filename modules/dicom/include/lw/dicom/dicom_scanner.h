#pragma once

#include "lw/core/limits.h"
#include "lw/core/progress.h"
#include "lw/dicom/dicom_types.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace lw::dicom {

// Patient -> study -> series -> instances found under one input, plus every file that could not
// be used (unreadable, not DICOM, missing although a DICOMDIR references it) with the reason.
struct DicomIndex {
    std::filesystem::path root;
    bool fromDicomdir = false;
    std::vector<PatientInfo> patients;
    std::vector<FileError> errors;
    std::vector<std::string> warnings;
    std::size_t filesExamined = 0;

    std::size_t seriesCount() const;
    std::size_t instanceCount() const;
    const SeriesInfo* findSeries(std::string_view seriesInstanceUid) const;
    std::vector<const SeriesInfo*> allSeries() const;
};

// `path` may be a folder (scanned recursively; headers read on all cores), a DICOMDIR file
// (records followed, nested DICOMDIRs too, referenced paths kept inside the file-set root) or a
// single DICOM file. Source files are opened read-only. Throws core::Error only when `path`
// itself cannot be used; per-file problems land in DicomIndex::errors, among them headers that
// declare more frames or pixel data than `limits` allow.
DicomIndex scanDicom(const std::filesystem::path& path, core::Progress* progress = nullptr,
                     const core::ImportLimits& limits = {});

// Reads the headers of exactly these files (on all cores), as a folder scan would: the study
// database reopens a series from its stored file list this way. A file that no longer exists or
// cannot be read lands in DicomIndex::errors with the reason ("file is missing" when gone).
DicomIndex scanDicomFiles(const std::vector<std::filesystem::path>& files,
                          core::Progress* progress = nullptr,
                          const core::ImportLimits& limits = {});

// True when `path` looks like DICOM input: a folder, a DICOMDIR or a file with the DICM magic.
bool looksLikeDicomInput(const std::filesystem::path& path);

} // namespace lw::dicom
