#include "lw/volume/volume_reader.h"

#include "reader_util.h"

#include <cstring>
#include <fstream>

namespace lw::volume {
namespace {

std::string lowerName(const std::filesystem::path& path) {
    return detail::toLower(path.filename().string());
}

bool endsWith(const std::string& text, std::string_view suffix) {
    return text.size() >= suffix.size() &&
           text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

} // namespace

VolumeFormat detectVolumeFormat(const std::filesystem::path& path) {
    // The magic wins over the extension: files get renamed, their first bytes do not change.
    char head[352] = {};
    std::size_t got = 0;
    {
        std::ifstream in(path, std::ios::binary);
        if (in) {
            in.read(head, sizeof head);
            got = std::size_t(in.gcount());
        }
    }
    const auto startsWith = [&](std::string_view magic) {
        return got >= magic.size() && std::memcmp(head, magic.data(), magic.size()) == 0;
    };
    if (startsWith("NRRD000"))
        return VolumeFormat::Nrrd;
    if (startsWith("PVM\n") || startsWith("PVM2\n") || startsWith("PVM3\n") ||
        startsWith("DDS v3d\n") || startsWith("DDS v3e\n"))
        return VolumeFormat::Pvm;
    if (got >= 348 &&
        (std::memcmp(head + 344, "n+1\0", 4) == 0 || std::memcmp(head + 344, "ni1\0", 4) == 0))
        return VolumeFormat::Nifti;

    const std::string name = lowerName(path);
    if (endsWith(name, ".nrrd") || endsWith(name, ".nhdr"))
        return VolumeFormat::Nrrd;
    if (endsWith(name, ".nii") || endsWith(name, ".nii.gz") || endsWith(name, ".hdr") ||
        endsWith(name, ".hdr.gz") || endsWith(name, ".img") || endsWith(name, ".img.gz"))
        return VolumeFormat::Nifti;
    if (endsWith(name, ".pvm"))
        return VolumeFormat::Pvm;
    return VolumeFormat::Unknown;
}

Volume readVolumeFile(const std::filesystem::path& path, core::Progress* progress,
                      const core::ImportLimits& limits) {
    if (progress) {
        progress->throwIfCancelled();
        progress->report(0.0, "reading " + path.filename().string());
    }
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        detail::fail(path, "file does not exist");
    if (std::filesystem::is_directory(path, ec))
        detail::fail(path, "is a folder, not a volume file");
    Volume volume;
    switch (detectVolumeFormat(path)) {
    case VolumeFormat::Nrrd:
        volume = readNrrd(path, limits);
        break;
    case VolumeFormat::Nifti:
        volume = readNifti(path, limits);
        break;
    case VolumeFormat::Pvm:
        volume = readPvm(path, limits);
        break;
    case VolumeFormat::Raw:
    case VolumeFormat::Unknown:
        detail::fail(path, "unknown volume format (expected .nrrd, .nhdr, .nii, .nii.gz, .hdr/.img "
                           "or .pvm; headerless raw data needs dims and type given explicitly)");
    }
    if (progress)
        progress->report(1.0, "read " + path.filename().string());
    return volume;
}

} // namespace lw::volume
