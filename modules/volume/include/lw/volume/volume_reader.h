#pragma once

#include "lw/core/limits.h"
#include "lw/core/progress.h"
#include "lw/volume/volume.h"

#include <filesystem>
#include <string>

namespace lw::volume {

enum class VolumeFormat { Unknown, Raw, Nrrd, Nifti, Pvm };

// Headerless raw data: everything comes from the caller (the command line).
struct RawOptions {
    glm::ivec3 dims{0};
    VoxelType type = VoxelType::UInt8;
    bool bigEndian = false;
    glm::dvec3 spacing{1.0};
    std::size_t headerBytes = 0; // bytes to skip at the start of the file
};

// Recognises a volume file by its extension and, where there is one, its magic
// (NRRD0004, NIfTI "n+1", PVM/PVM2/PVM3/DDS v3d). Raw files are never guessed: they need RawOptions.
VolumeFormat detectVolumeFormat(const std::filesystem::path& path);

// Reads NRRD (.nrrd, .nhdr), NIfTI-1 (.nii, .nii.gz, .hdr/.img) or PVM (.pvm). Throws core::Error
// naming the file and the reason. Files are opened read-only. The sizes a header declares are
// checked against `limits` before anything is allocated, and gzip data may inflate only to
// what the header declares (plus a small margin).
Volume readVolumeFile(const std::filesystem::path& path, core::Progress* progress = nullptr,
                      const core::ImportLimits& limits = {});

Volume readRawVolume(const std::filesystem::path& path, const RawOptions& options,
                     const core::ImportLimits& limits = {});
Volume readNrrd(const std::filesystem::path& path, const core::ImportLimits& limits = {});
Volume readNifti(const std::filesystem::path& path, const core::ImportLimits& limits = {});
Volume readPvm(const std::filesystem::path& path, const core::ImportLimits& limits = {});

// Writes an attached-header NRRD (raw encoding, little endian) atomically, with spacing,
// space directions and origin from the volume's geometry (mean slice step when uneven).
void writeNrrd(const std::filesystem::path& path, const Volume& volume);

} // namespace lw::volume
