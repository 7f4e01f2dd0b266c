#pragma once

// Internal to lw::dicom: reading a DICOMDIR (and the DICOMDIRs it nests) into the list of files
// it references, the series it lists, and the errors met on the way.

#include "file_set_paths.h"
#include "lw/core/progress.h"
#include "lw/dicom/dicom_scanner.h"

#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lw::dicom::detail {

// What a SERIES record says, with the PATIENT and STUDY records before it, and how many of the
// files listed under it are referenced and missing.
struct ListedSeries {
    std::string patientId, patientName;
    std::string studyInstanceUid, studyId, studyDescription, studyDate, studyTime;
    std::string modality, description;
    std::optional<int> seriesNumber;
    std::size_t referenced = 0;
    std::size_t missing = 0;
};

// What following a DICOMDIR and the DICOMDIRs it nests collects.
struct DicomdirState {
    std::filesystem::path root; // the file-set root: the folder of the DICOMDIR the scan started at
    std::filesystem::path canonicalRoot; // for the containment check after symlinks are resolved
    std::set<std::filesystem::path> visitedDicomdirs;
    std::set<std::filesystem::path> seenFiles;
    std::vector<std::filesystem::path> files;
    std::vector<FileError> errors;
    std::vector<std::string> warnings;
    std::set<std::string> listedSeries;
    std::set<std::string> listedStudies;
    // What the SERIES records say, with the PATIENT and STUDY records before them, so series
    // whose files are all missing still appear in the index (a CD with a series held back).
    std::map<std::string, ListedSeries> listedSeriesRecords;
    bool recordsInOrder = true; // every file's records run PATIENT, STUDY, SERIES, IMAGE...
    CaseInsensitiveResolver resolver;
    core::Progress* progress = nullptr;
};

// Follows the records of `dicomdir` (and of nested DICOMDIRs) into `state`. Damage met there
// becomes the file's error; for the top-level DICOMDIR (topLevel) it fails the scan, see there.
void walkDicomdir(const std::filesystem::path& dicomdir, DicomdirState& state, int depth,
                  bool topLevel);

// Adds the series a DICOMDIR lists but whose files are all missing, as empty series under their
// study and patient, and records how many referenced files each listed series lacks.
void addListedSeries(DicomIndex& index, const DicomdirState& state);

} // namespace lw::dicom::detail
