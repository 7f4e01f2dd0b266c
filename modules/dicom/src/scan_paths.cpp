#include "scan_paths.h"

#include "dicom_file.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <string_view>

namespace fs = std::filesystem;

namespace lw::dicom::detail {

std::string lower(std::string text) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return text;
}

std::string trimBlanks(std::string text) {
    const auto first = text.find_first_not_of(" \t\r\n");
    if (first == std::string::npos)
        return {};
    const auto last = text.find_last_not_of(" \t\r\n");
    return text.substr(first, last - first + 1);
}

bool isNamedDicomdir(const fs::path& path) {
    return lower(path.filename().string()) == "dicomdir";
}

fs::path canonicalOrAbsolute(const fs::path& path) {
    std::error_code ec;
    fs::path result = fs::canonical(path, ec);
    if (ec)
        result = fs::absolute(path, ec).lexically_normal();
    return result;
}

bool safeIsDicomdir(const fs::path& path) noexcept {
    try {
        return isDicomdirFile(path);
    } catch (...) {
        return false;
    }
}

bool isInside(const fs::path& child, const fs::path& root) {
    const auto rel = child.lexically_relative(root);
    if (rel.empty())
        return false;
    const auto first = rel.begin()->string();
    return first != ".." && !rel.is_absolute();
}

bool hasDicmMagic(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    char buffer[132] = {};
    if (!in.read(buffer, sizeof buffer))
        return false;
    return std::string_view(buffer + 128, 4) == "DICM";
}

} // namespace lw::dicom::detail
