#pragma once

// One way to open what a user points at, for the CLI and the GUI alike (issue 6): a DICOM
// folder, DICOMDIR or file (DICOM builds), a volume file (NRRD, NIfTI, PVM, raw by extension),
// or the benchmark phantom ("phantom:N", "phantom:NXxNYxNZ", optionally ":ct" or ":sphere").

#include "lw/core/progress.h"
#include "lw/volume/volume.h"

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lw::input {

struct OpenOptions {
    // DICOM: the series to open; default the one with the most slices (in a CT study the
    // diagnostic volume, not a scout or a dose report).
    std::optional<std::string> seriesUid;
    // What one volume may take (default: half the physical memory): every path below checks it
    // before it allocates the volume.
    core::ImportLimits limits;
};

// Whom and which study and series a DICOM volume shows, from the first instance of its series:
// what a derived object repeats (a report's header; a Secondary Capture joins the same study
// with the same patient module).
struct DicomIdentity {
    std::string patientName, patientId, patientBirthDate, patientSex;
    std::string studyInstanceUid, studyId, studyDate, studyTime, studyDescription, accessionNumber;
    std::string seriesInstanceUid, seriesDescription, modality;
    std::optional<int> seriesNumber;
};

struct OpenedVolume {
    volume::Volume volume;
    std::string source;                 // the path or phantom spec
    std::string seriesUid;              // DICOM only
    std::string description;            // one line for titles and logs
    std::vector<std::string> warnings;  // tilt, uneven gaps, missing slices, files that failed
    std::optional<DicomIdentity> dicom; // DICOM only
};

// Throws core::Error naming the path and the reason; core::Cancelled when `progress` is
// cancelled. Progress: DICOM scanning the first 20 %, decoding the rest.
OpenedVolume openInput(const std::string& path, const OpenOptions& options = {},
                       core::Progress* progress = nullptr);

// The files of one DICOM series as the study database stores them. Files that have gone missing
// make it fail with their count and the first few paths. Throws in a build without DICOM.
OpenedVolume openDicomFiles(const std::vector<std::filesystem::path>& files,
                            const OpenOptions& options = {}, core::Progress* progress = nullptr);

bool isDicomBuild();

// "N" or "NXxNYxNZ", each a whole number in [minimum, maximum]; nullopt otherwise (phantom specs
// here, sizes in the CLI's options).
std::optional<glm::ivec3> parseDims(std::string_view text, int minimum, int maximum = 1 << 30);
// "NXxNYxNZ".
std::string dimsText(glm::ivec3 dims);

} // namespace lw::input
