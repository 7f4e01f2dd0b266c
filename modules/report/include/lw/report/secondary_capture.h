#pragma once

// DICOM Secondary Capture (SC Image Storage, RGB, explicit VR little endian) of the exported
// pictures: a new series in the source's study (same StudyInstanceUID and patient module, new
// series and instance UIDs), so it can be sent back to the PACS next to the CT it was made from.
// DCMTK stays inside this module (PRIVATE).

#include "lw/core/file_util.h"
#include "lw/input/open_input.h"

#include <QImage>
#include <filesystem>
#include <string>
#include <vector>

namespace lw::report {

struct SecondaryCaptureSeries {
    input::DicomIdentity source;       // patient and study repeated, series replaced
    std::string derivationDescription; // how the pictures were made: method and iso-value
    std::string seriesDescription = "Linework silhouette review";
    std::string softwareVersion;
};

// The file name of the n-th picture (1-based): LWSC0001.dcm, ...
std::string secondaryCaptureFileName(int number);

// Writes each picture as one instance of one new series into `folder` (created when missing;
// its parent must exist) and returns the files. Each file is written atomically; an existing
// file is an error unless `overwrite` allows it; on any failure the files written so far (and
// a folder created here) are removed. Throws core::Error naming the file and the reason, or the
// source when it has no StudyInstanceUID.
// Before rendering: throws core::Error naming the file or folder when writing a series into
// `folder` is bound to be refused (its first file exists and `overwrite` is Refuse, or the folder
// or its parent cannot be written), so a refused export stops before any work.
void checkSecondaryCaptureTarget(const std::filesystem::path& folder, core::Overwrite overwrite);

std::vector<std::filesystem::path> writeSecondaryCapture(const std::filesystem::path& folder,
                                                         const std::vector<QImage>& pictures,
                                                         const SecondaryCaptureSeries& series,
                                                         core::Overwrite overwrite);

} // namespace lw::report
