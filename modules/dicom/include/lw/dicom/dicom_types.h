#pragma once

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

// Plain descriptions of DICOM objects, filled from file headers. No DCMTK type appears in any
// public header of lw::dicom: DCMTK stays private to this module.
namespace lw::dicom {

// A file that could not be used, and why. Import goes on with the other files.
struct FileError {
    std::string file;
    std::string reason;
};

// One frame of an instance: a classic single-frame image has one, an enhanced multi-frame
// object one per frame (filled from the shared and per-frame functional groups).
struct FrameInfo {
    int frameIndex = 0;                               // 0-based within the file
    std::optional<glm::dvec3> position;               // ImagePositionPatient (mm, LPS)
    std::optional<std::array<double, 6>> orientation; // ImageOrientationPatient: row, column
    std::optional<glm::dvec2> pixelSpacing;           // PixelSpacing as stored: (row spacing, column spacing)
    std::optional<double> sliceThickness;
    double rescaleSlope = 1.0;
    double rescaleIntercept = 0.0;
    std::string frameType; // FrameType (enhanced) or ImageType (classic), values joined with '\\'
    std::optional<int> stackPosition;                 // InStackPositionNumber (enhanced)
    std::optional<int> temporalPosition;              // TemporalPositionIndex (enhanced)
};

struct InstanceInfo {
    std::string path; // as found on disk
    std::string sopInstanceUid;
    std::string sopClassUid;
    std::string transferSyntaxUid;
    std::string patientId, patientName, patientBirthDate, patientSex;
    std::string studyInstanceUid, studyId, studyDescription, studyDate, studyTime, accessionNumber;
    std::string seriesInstanceUid, seriesDescription, modality;
    std::optional<int> seriesNumber;
    std::optional<int> instanceNumber;
    std::optional<int> acquisitionNumber;

    int rows = 0;
    int columns = 0;
    int bitsAllocated = 0;
    int bitsStored = 0;
    int highBit = 0;
    int pixelRepresentation = 0; // 0 unsigned, 1 two's complement
    int samplesPerPixel = 1;
    std::string photometricInterpretation;
    bool hasPixelData = false;
    // Length of native (not encapsulated) pixel data as its element declares it; empty when
    // encapsulated or undefined. Checked against rows x columns x frames before loading.
    std::optional<std::uint64_t> nativePixelDataBytes;
    int numberOfFrames = 1;
    bool isEnhanced = false; // per-frame functional groups present
    bool isGzipWrapped = false; // the file on disk is a gzip of a DICOM file (.dcm.gz)

    std::optional<double> gantryTilt;           // (0018,1120); informative only: not reliable
    std::optional<double> spacingBetweenSlices; // (0018,0088)
    std::vector<FrameInfo> frames;              // never empty when hasPixelData
};

struct SeriesInfo {
    std::string seriesInstanceUid;
    std::string modality;
    std::string description;
    std::optional<int> seriesNumber;
    std::vector<InstanceInfo> instances;
    // From a DICOMDIR only: image files its records reference, and how many of them are missing.
    // A series whose files are all missing is listed with no instances.
    std::size_t referencedFiles = 0;
    std::size_t missingFiles = 0;
};

struct StudyInfo {
    std::string studyInstanceUid;
    std::string studyId;
    std::string description;
    std::string date;
    std::string time;
    std::string accessionNumber;
    std::vector<SeriesInfo> series;
};

struct PatientInfo {
    std::string patientId;
    std::string name;
    std::string birthDate;
    std::string sex;
    std::vector<StudyInfo> studies;
};

} // namespace lw::dicom
