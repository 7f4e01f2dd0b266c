#pragma once

// Internal to lw::dicom: reading single DICOM files with DCMTK.

#include "lw/core/limits.h"
#include "lw/dicom/dicom_types.h"
#include "lw/volume/voxel_type.h"

#include <filesystem>
#include <memory>

namespace lw::dicom {

// Reads the header of one DICOM file (pixel data is not loaded). Enhanced multi-frame objects get
// one FrameInfo per frame from the shared and per-frame functional groups. Accepts files with
// or without preamble/meta (ACR-NEMA), gzip-wrapped files, any transfer syntax. Throws
// core::Error(path, reason) when the file is not DICOM or cannot be parsed, or when it declares
// more frames or pixel data than `limits` allow (checked before any frame is described).
InstanceInfo readInstanceHeader(const std::filesystem::path& path,
                                const core::ImportLimits& limits = {});

// True for DICOMDIR files (Media Storage Directory SOP class): they hold no images.
bool isDicomdirFile(const std::filesystem::path& path);

// The voxel type a frame of this instance is stored in after decoding (uint8, int16, uint16).
// Throws core::Error for what cannot be a volume (colour, 32-bit, no pixel data).
volume::VoxelType storedVoxelType(const InstanceInfo& instance);

// Decodes frames of one file. The file is opened once (read-only) and may be asked for
// several frames. Output values are the stored values masked to BitsStored and sign-extended
// from HighBit, MONOCHROME1 inverted; rescale is NOT applied (it is the volume's ValueMapping).
// A gzip wrapper or a deflated data set is inflated within `limits`: the caller's, so an
// import with a lower limit than the default is held to it while decoding too.
class FrameDecoder {
public:
    explicit FrameDecoder(const InstanceInfo& instance, const core::ImportLimits& limits = {});
    ~FrameDecoder();
    FrameDecoder(const FrameDecoder&) = delete;
    FrameDecoder& operator=(const FrameDecoder&) = delete;

    // Writes rows*columns voxels of `target` type to `destination`. Throws core::Error naming
    // the file, the frame and the reason.
    void decodeFrame(int frame, volume::VoxelType target, void* destination);

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::dicom
