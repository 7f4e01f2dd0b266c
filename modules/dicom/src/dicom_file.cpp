#include "dicom_file.h"

#include "deflated_dataset.h"
#include "dicom_dcmtk.h"
#include "lw/core/error.h"
#include "lw/core/file_util.h"

#include <algorithm>
#include <cmath>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcistrmb.h>
#include <dcmtk/dcmdata/dcitem.h>
#include <dcmtk/dcmdata/dcsequen.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmdata/dcxfer.h>
#include <dcmtk/oflog/oflog.h>
#include <fstream>

namespace lw::dicom {

namespace {

// Elements longer than this are skipped while parsing and only loaded on demand: reading a
// header must not pull 500 KB of pixel data (or a 200 MB multi-frame) into memory.
constexpr Uint32 kHeaderMaxReadLength = 4096;

std::string joinValues(DcmItem& item, const DcmTagKey& key) {
    DcmElement* element = nullptr;
    if (item.findAndGetElement(key, element, OFFalse).bad() || !element)
        return {};
    OFString all;
    if (element->getOFStringArray(all).bad())
        return {};
    return trim(std::string(all.c_str()));
}

// Applies one functional-group item (shared or per-frame) to a frame. Per-frame items are
// applied after the shared one, so whatever they carry overrides the shared values.
void applyFunctionalGroups(DcmItem& groups, FrameInfo& frame) {
    if (DcmItem* measures = firstItem(groups, DCM_PixelMeasuresSequence)) {
        if (auto spacing = getDoubles(*measures, DCM_PixelSpacing, 2))
            frame.pixelSpacing = glm::dvec2((*spacing)[0], (*spacing)[1]);
        if (auto thickness = getDouble(*measures, DCM_SliceThickness))
            frame.sliceThickness = *thickness;
    }
    if (DcmItem* position = firstItem(groups, DCM_PlanePositionSequence)) {
        if (auto ipp = getDoubles(*position, DCM_ImagePositionPatient, 3))
            frame.position = glm::dvec3((*ipp)[0], (*ipp)[1], (*ipp)[2]);
    }
    if (DcmItem* orientation = firstItem(groups, DCM_PlaneOrientationSequence)) {
        if (auto iop = getDoubles(*orientation, DCM_ImageOrientationPatient, 6))
            frame.orientation = toOrientation(*iop);
    }
    if (DcmItem* transform = firstItem(groups, DCM_PixelValueTransformationSequence)) {
        if (auto slope = getDouble(*transform, DCM_RescaleSlope); slope && *slope != 0.0)
            frame.rescaleSlope = *slope;
        if (auto intercept = getDouble(*transform, DCM_RescaleIntercept))
            frame.rescaleIntercept = *intercept;
    }
    if (DcmItem* content = firstItem(groups, DCM_FrameContentSequence)) {
        if (auto stack = getInt(*content, DCM_InStackPositionNumber))
            frame.stackPosition = *stack;
        if (auto temporal = getInt(*content, DCM_TemporalPositionIndex))
            frame.temporalPosition = *temporal;
    }
    for (const DcmTagKey& key : {DCM_CTImageFrameTypeSequence, DCM_MRImageFrameTypeSequence,
                                 DCM_XAXRFFrameCharacteristicsSequence, DCM_PETFrameTypeSequence}) {
        if (DcmItem* type = firstItem(groups, key)) {
            std::string value = joinValues(*type, DCM_FrameType);
            if (!value.empty())
                frame.frameType = value;
        }
    }
}

// The size of the pixel data a header declares, checked against the import limits before a
// single frame is described: a 600-byte header claiming 2^31-1 frames used to cost 13 GB of
// frame descriptions and a minute before anything failed.
void checkDeclaredPixels(const InstanceInfo& info, const core::ImportLimits& limits) {
    limits.checkFrames(info.numberOfFrames, info.path);
    if (info.rows <= 0 || info.columns <= 0)
        return; // no image: storedVoxelType says so when a volume is planned
    limits.checkDimension(info.rows, info.path, "Rows");
    limits.checkDimension(info.columns, info.path, "Columns");
    const std::size_t sampleBytes = std::size_t(std::max(1, (info.bitsAllocated + 7) / 8));
    limits.checkedBytes({std::size_t(info.rows), std::size_t(info.columns),
                         std::size_t(info.numberOfFrames),
                         std::size_t(std::max(1, info.samplesPerPixel)), sampleBytes},
                        info.path, "the pixel data the header declares");
}

// The declared length of native pixel data, without loading it (header reads skip long values).
std::optional<std::uint64_t> nativePixelDataLength(DcmDataset& ds) {
    DcmElement* element = nullptr;
    if (ds.findAndGetElement(DCM_PixelData, element, OFFalse).bad() || !element)
        return std::nullopt;
    if (DcmXfer(ds.getOriginalXfer()).isEncapsulated())
        return std::nullopt;
    const Uint32 length = element->getLength();
    if (length == DCM_UndefinedLength)
        return std::nullopt;
    return length;
}

// SOP identity and the transfer syntax as parsed (and as written, where the meta says so).
void fillSopAndSyntax(DcmFileFormat& file, InstanceInfo& info) {
    DcmDataset& ds = *file.getDataset();
    DcmMetaInfo* meta = file.getMetaInfo();
    info.sopInstanceUid = getString(ds, DCM_SOPInstanceUID);
    info.sopClassUid = getString(ds, DCM_SOPClassUID);
    if (info.sopClassUid.empty() && meta)
        info.sopClassUid = getString(*meta, DCM_MediaStorageSOPClassUID);
    // The dataset's original transfer syntax is what was actually parsed: the meta element
    // may be missing (meta_missing_tsyntax.dcm) or absent altogether (ACR-NEMA).
    const E_TransferSyntax xfer = ds.getOriginalXfer();
    if (xfer != EXS_Unknown)
        info.transferSyntaxUid = DcmXfer(xfer).getXferID();
    // The meta element, when present, names the syntax as written (e.g. deflate) even where
    // DCMTK reports the decoded form.
    if (meta) {
        std::string metaSyntax = getString(*meta, DCM_TransferSyntaxUID);
        if (!metaSyntax.empty())
            info.transferSyntaxUid = metaSyntax;
    }
}

// Patient, study and series attributes: the browser's tree and the series grouping.
void fillNames(DcmDataset& ds, InstanceInfo& info) {
    info.patientId = getString(ds, DCM_PatientID);
    info.patientName = getString(ds, DCM_PatientName);
    info.patientBirthDate = getString(ds, DCM_PatientBirthDate);
    info.patientSex = getString(ds, DCM_PatientSex);
    info.studyInstanceUid = getString(ds, DCM_StudyInstanceUID);
    info.studyId = getString(ds, DCM_StudyID);
    info.studyDescription = getString(ds, DCM_StudyDescription);
    info.studyDate = getString(ds, DCM_StudyDate);
    info.studyTime = getString(ds, DCM_StudyTime);
    info.accessionNumber = getString(ds, DCM_AccessionNumber);
    info.seriesInstanceUid = getString(ds, DCM_SeriesInstanceUID);
    info.seriesDescription = getString(ds, DCM_SeriesDescription);
    info.modality = getString(ds, DCM_Modality);
    info.seriesNumber = getInt(ds, DCM_SeriesNumber);
    info.instanceNumber = getInt(ds, DCM_InstanceNumber);
    info.acquisitionNumber = getInt(ds, DCM_AcquisitionNumber);
}

// The pixel module, checked against the import limits before any pixel is read.
void fillPixelDescription(DcmDataset& ds, const LoadedDicom& loaded, InstanceInfo& info,
                          const core::ImportLimits& limits) {
    info.rows = getUnsigned(ds, DCM_Rows).value_or(0);
    info.columns = getUnsigned(ds, DCM_Columns).value_or(0);
    info.bitsAllocated = getUnsigned(ds, DCM_BitsAllocated).value_or(0);
    info.bitsStored = getUnsigned(ds, DCM_BitsStored).value_or(info.bitsAllocated);
    info.highBit =
        getUnsigned(ds, DCM_HighBit).value_or(info.bitsStored > 0 ? info.bitsStored - 1 : 0);
    info.pixelRepresentation = getUnsigned(ds, DCM_PixelRepresentation).value_or(0);
    info.samplesPerPixel = getUnsigned(ds, DCM_SamplesPerPixel).value_or(1);
    info.photometricInterpretation = getString(ds, DCM_PhotometricInterpretation);
    info.hasPixelData = ds.tagExists(DCM_PixelData, OFFalse) || loaded.pixelDataSkipped;
    // badVR.dcm carries NumberOfFrames "1A": treat what cannot be parsed as one frame.
    info.numberOfFrames = std::max(1, getInt(ds, DCM_NumberOfFrames).value_or(1));
    if (info.hasPixelData) {
        info.nativePixelDataBytes =
            loaded.pixelDataSkipped ? loaded.skippedPixelDataLength : nativePixelDataLength(ds);
        checkDeclaredPixels(info, limits);
    }
}

// The frame defaults from the classic top-level attributes.
FrameInfo classicFrameDefaults(DcmDataset& ds) {
    FrameInfo base;
    if (auto ipp = getDoubles(ds, DCM_ImagePositionPatient, 3))
        base.position = glm::dvec3((*ipp)[0], (*ipp)[1], (*ipp)[2]);
    if (auto iop = getDoubles(ds, DCM_ImageOrientationPatient, 6))
        base.orientation = toOrientation(*iop);
    if (auto spacing = getDoubles(ds, DCM_PixelSpacing, 2))
        base.pixelSpacing = glm::dvec2((*spacing)[0], (*spacing)[1]);
    else if (auto imager = getDoubles(ds, DCM_ImagerPixelSpacing, 2))
        base.pixelSpacing = glm::dvec2((*imager)[0], (*imager)[1]);
    base.sliceThickness = getDouble(ds, DCM_SliceThickness);
    if (auto slope = getDouble(ds, DCM_RescaleSlope); slope && *slope != 0.0)
        base.rescaleSlope = *slope;
    if (auto intercept = getDouble(ds, DCM_RescaleIntercept))
        base.rescaleIntercept = *intercept;
    base.frameType = joinValues(ds, DCM_FrameType);
    if (base.frameType.empty())
        base.frameType = joinValues(ds, DCM_ImageType);
    return base;
}

// One FrameInfo per frame: an enhanced object's functional groups override the defaults.
void fillFrames(DcmDataset& ds, const FrameInfo& base, InstanceInfo& info) {
    DcmSequenceOfItems* perFrame = nullptr;
    if (ds.findAndGetSequence(DCM_PerFrameFunctionalGroupsSequence, perFrame, OFFalse).bad())
        perFrame = nullptr;
    DcmItem* shared = firstItem(ds, DCM_SharedFunctionalGroupsSequence);
    info.isEnhanced = perFrame != nullptr || shared != nullptr;

    info.frames.clear();
    if (!info.hasPixelData)
        return;
    if (info.isEnhanced) {
        FrameInfo common = base;
        if (shared)
            applyFunctionalGroups(*shared, common);
        for (int i = 0; i < info.numberOfFrames; ++i) {
            FrameInfo frame = common;
            frame.frameIndex = i;
            if (perFrame && unsigned(i) < perFrame->card()) {
                if (DcmItem* item = perFrame->getItem(unsigned(i)))
                    applyFunctionalGroups(*item, frame);
            }
            info.frames.push_back(std::move(frame));
        }
        return;
    }
    for (int i = 0; i < info.numberOfFrames; ++i) {
        FrameInfo frame = base;
        frame.frameIndex = i;
        // A classic multi-frame object (US, NM, old XA) has one position for the whole object
        // at best: the frames' own positions are unknown, and guessing them would be fake.
        if (info.numberOfFrames > 1)
            frame.position.reset();
        info.frames.push_back(std::move(frame));
    }
}

void fillInstance(DcmFileFormat& file, const LoadedDicom& loaded, InstanceInfo& info,
                  const core::ImportLimits& limits) {
    DcmDataset& ds = *file.getDataset();
    fillSopAndSyntax(file, info);
    fillNames(ds, info);
    fillPixelDescription(ds, loaded, info, limits);
    info.gantryTilt = getDouble(ds, DCM_GantryDetectorTilt);
    info.spacingBetweenSlices = getDouble(ds, DCM_SpacingBetweenSlices);
    // The functional groups of an enhanced object override the classic attributes' defaults.
    fillFrames(ds, classicFrameDefaults(ds), info);
}

// Reads the raw bytes of a gzip-wrapped file and inflates them; empty when the file is not gzip.
std::vector<std::byte> gunzippedContents(const std::filesystem::path& path,
                                         const core::ImportLimits& limits) {
    std::ifstream in(path, std::ios::binary);
    char magic[2] = {};
    if (!in.read(magic, 2))
        return {};
    const std::byte header[2] = {std::byte(magic[0]), std::byte(magic[1])};
    if (!core::looksGzipped(header, 2))
        return {};
    const std::vector<std::byte> raw = core::readFileBytes(path);
    return core::gunzip(raw.data(), raw.size(), path.string(), limits.maxBytes);
}

// Without file meta DCMTK guesses the encoding and will "parse" arbitrary bytes into
// nonsense tags; accept a result only when it carries attributes every DICOM object has.
bool looksLikeDicom(DcmFileFormat& file) {
    DcmDataset& ds = *file.getDataset();
    return ds.tagExists(DCM_SOPClassUID) || ds.tagExists(DCM_Rows) ||
           ds.tagExists(DCM_SOPInstanceUID) || ds.tagExists(DCM_DirectoryRecordSequence);
}

// Process-wide DCMTK settings, made once. VR UN elements (explicit_VR-UN.dcm: a TCIA export
// with almost every tag UN) are read with their dictionary VR, otherwise Modality reads as hex.
void configureDcmtk() {
    static const bool configured = [] {
        dcmEnableUnknownVRConversion.set(OFTrue);
        // Problems are reported through core::Error with the file name; DCMTK's own stderr
        // chatter about every odd element would only bury them.
        OFLog::configure(OFLogger::FATAL_LOG_LEVEL);
        return true;
    }();
    (void)configured;
}

// Deflated files are read by deflated_dataset.cpp (bounded inflation) instead of DCMTK's own
// stream filter; a plain file is read into memory for it only when its meta names deflate.
std::optional<DeflatedRead> readDeflated(const std::filesystem::path& path,
                                         const std::vector<std::byte>& gunzipped,
                                         DcmFileFormat& file, bool headerOnly,
                                         std::optional<std::size_t> expectedPixelBytes,
                                         const core::ImportLimits& limits) {
    if (!gunzipped.empty())
        return readIfDeflated(gunzipped, file, headerOnly, expectedPixelBytes, path.string(),
                              limits);
    if (!isDeflatedFile(path.string()))
        return std::nullopt;
    return readIfDeflated(core::readFileBytes(path), file, headerOnly, expectedPixelBytes,
                          path.string(), limits);
}

} // namespace

LoadedDicom loadDicomFile(const std::filesystem::path& path, DcmFileFormat& file, bool headerOnly,
                          std::vector<std::byte>* inflated, const core::ImportLimits& limits,
                          std::optional<std::size_t> expectedPixelBytes) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw core::Error(path.string(), "not a readable file");
    // Anything shorter than one element header cannot be DICOM; DCMTK would call it an empty
    // dataset.
    if (std::filesystem::file_size(path, ec) < 8)
        throw core::Error(path.string(), "not a DICOM file (too short)");

    LoadedDicom loaded;
    std::vector<std::byte> local;
    std::vector<std::byte>& bytes = inflated ? *inflated : local;
    bytes = gunzippedContents(path, limits);
    loaded.isGzipWrapped = !bytes.empty();

    configureDcmtk();
    if (auto deflated = readDeflated(path, bytes, file, headerOnly, expectedPixelBytes, limits)) {
        loaded.pixelDataSkipped = deflated->pixelDataSkipped;
        loaded.skippedPixelDataLength = deflated->pixelDataLength;
        return loaded;
    }
    // The encoding is guessed when the meta header does not name it (ACR-NEMA, a missing
    // TransferSyntaxUID); a wrong guess parses into nonsense, so the other plausible
    // encodings are tried before giving up. Good files succeed on the first attempt.
    OFCondition firstStatus;
    bool parsedSomething = false; // a DICOM stream, but without the attributes an image needs
    for (E_TransferSyntax guess :
         {EXS_Unknown, EXS_LittleEndianExplicit, EXS_LittleEndianImplicit, EXS_BigEndianExplicit}) {
        file.clear();
        OFCondition status;
        if (bytes.empty()) {
            status = file.loadFile(OFFilename(path.c_str()), guess, EGL_noChange,
                                   headerOnly ? kHeaderMaxReadLength : DCM_MaxReadLength,
                                   ERM_autoDetect);
        } else {
            // A memory buffer cannot be re-opened later, so everything is read at once.
            DcmInputBufferStream stream;
            stream.setBuffer(bytes.data(), offile_off_t(bytes.size()));
            stream.setEos();
            file.transferInit();
            status = file.read(stream, guess, EGL_noChange, DCM_MaxReadLength);
            file.transferEnd();
        }
        if (guess == EXS_Unknown)
            firstStatus = status;
        if (status.good() && looksLikeDicom(file))
            return loaded;
        if (status.good() && (file.getMetaInfo()->card() > 0 || file.getDataset()->card() > 0))
            parsedSomething = true;
        if (status.bad())
            break; // another guess cannot fix a broken or truncated stream
    }
    if (firstStatus.bad()) {
        // DCMTK's stream conditions read like internal jargon; say what they mean for a file.
        const std::string detail = firstStatus == EC_StreamNotifyClient
                                       ? "the file ends before its last element (truncated)"
                                       : std::string(firstStatus.text());
        throw core::Error(path.string(), "cannot parse DICOM: " + detail);
    }
    if (parsedSomething)
        throw core::Error(path.string(),
                          "DICOM data without SOPClassUID, SOPInstanceUID or Rows: "
                          "not an image object (or its encoding cannot be determined)");
    throw core::Error(path.string(), "not a DICOM file (no recognisable DICOM attributes)");
}

InstanceInfo readInstanceHeader(const std::filesystem::path& path,
                                const core::ImportLimits& limits) {
    InstanceInfo info;
    info.path = path.string();
    try {
        DcmFileFormat file;
        const LoadedDicom loaded = loadDicomFile(path, file, true, nullptr, limits);
        info.isGzipWrapped = loaded.isGzipWrapped;
        fillInstance(file, loaded, info, limits);
    } catch (const core::Error&) {
        throw;
    } catch (const std::exception& e) {
        throw core::Error(path.string(), std::string("cannot read DICOM header: ") + e.what());
    }
    if (info.hasPixelData && info.frames.empty())
        throw core::Error(path.string(), "pixel data without frames");
    return info;
}

bool isDicomdirFile(const std::filesystem::path& path) {
    DcmFileFormat file;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        return false;
    // The meta header says it; reading only the meta keeps this cheap for large DICOMDIRs.
    if (file.loadFile(OFFilename(path.c_str()), EXS_Unknown, EGL_noChange, kHeaderMaxReadLength,
                      ERM_metaOnly)
            .bad())
        return false;
    DcmMetaInfo* meta = file.getMetaInfo();
    if (!meta)
        return false;
    return getString(*meta, DCM_MediaStorageSOPClassUID) == UID_MediaStorageDirectoryStorage;
}

volume::VoxelType storedVoxelType(const InstanceInfo& instance) {
    if (!instance.hasPixelData)
        throw core::Error(instance.path, "no pixel data");
    if (instance.samplesPerPixel != 1)
        throw core::Error(instance.path,
                          "colour images (" + std::to_string(instance.samplesPerPixel) +
                              " samples per pixel, " + instance.photometricInterpretation +
                              ") cannot be a volume");
    if (instance.photometricInterpretation == "PALETTE COLOR")
        throw core::Error(instance.path, "palette colour images cannot be a volume");
    if (instance.rows <= 0 || instance.columns <= 0)
        throw core::Error(instance.path, "Rows or Columns missing or zero");
    switch (instance.bitsAllocated) {
    case 8:
        // Signed 8-bit values need a signed type; int16 holds them all.
        return instance.pixelRepresentation == 1 ? volume::VoxelType::Int16
                                                 : volume::VoxelType::UInt8;
    case 16:
        return instance.pixelRepresentation == 1 ? volume::VoxelType::Int16
                                                 : volume::VoxelType::UInt16;
    default:
        throw core::Error(instance.path, "unsupported BitsAllocated " +
                                             std::to_string(instance.bitsAllocated) +
                                             " (8 and 16 are supported)");
    }
}

} // namespace lw::dicom
