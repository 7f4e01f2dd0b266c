#pragma once

// Internal to lw::dicom: DICOMDIR ReferencedFileIDs turned into paths below the file-set root.

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

namespace lw::dicom::detail {

// Splits a ReferencedFileID ("DIR\SUB\FILE") into components; nullopt when the ID would leave
// the file-set root (absolute, drive letter, "..") or is malformed.
std::optional<std::vector<std::string>> splitFileId(const std::string& id);

// Resolves ReferencedFileID components below `base`, exact case first and then
// case-insensitively: CD exports write upper-case IDs, but copies to case-sensitive file
// systems often end up lower case (or the other way round).
class CaseInsensitiveResolver {
public:
    std::optional<std::filesystem::path> resolve(const std::filesystem::path& base,
                                                 const std::vector<std::string>& components);

private:
    const std::map<std::string, std::string>& listFolder(const std::filesystem::path& folder);

    std::unordered_map<std::string, std::map<std::string, std::string>> m_listings;
};

} // namespace lw::dicom::detail
