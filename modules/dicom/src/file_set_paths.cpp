#include "file_set_paths.h"

#include "scan_paths.h"

#include <algorithm>

namespace fs = std::filesystem;

namespace lw::dicom::detail {

std::optional<std::vector<std::string>> splitFileId(const std::string& id) {
    std::vector<std::string> components;
    if (id.empty() || id.front() == '\\' || id.front() == '/')
        return std::nullopt;
    std::string current;
    auto flush = [&]() -> bool {
        const std::string component = trimBlanks(current);
        current.clear();
        if (component.empty() || component == "." || component == ".." ||
            component.find(':') != std::string::npos)
            return false;
        components.push_back(component);
        return true;
    };
    for (char c : id) {
        if (c == '\\' || c == '/') {
            if (!flush())
                return std::nullopt;
        } else {
            current += c;
        }
    }
    if (!flush())
        return std::nullopt;
    return components;
}

std::optional<fs::path>
CaseInsensitiveResolver::resolve(const fs::path& base, const std::vector<std::string>& components) {
    fs::path current = base;
    for (const auto& component : components) {
        fs::path candidate = current / component;
        std::error_code ec;
        if (fs::exists(candidate, ec)) {
            current = std::move(candidate);
            continue;
        }
        const auto& listing = listFolder(current);
        const auto found = listing.find(lower(component));
        if (found == listing.end())
            return std::nullopt;
        current = current / found->second;
    }
    std::error_code ec;
    if (!fs::is_regular_file(current, ec))
        return std::nullopt;
    return current;
}

const std::map<std::string, std::string>&
CaseInsensitiveResolver::listFolder(const fs::path& folder) {
    auto [it, inserted] = m_listings.try_emplace(folder.string());
    if (inserted) {
        std::error_code ec;
        std::vector<std::string> names;
        for (fs::directory_iterator d(folder, ec), end; !ec && d != end; d.increment(ec))
            names.push_back(d->path().filename().string());
        // Sorted so that two names differing only in case resolve the same way every run.
        std::sort(names.begin(), names.end());
        for (const auto& name : names)
            it->second.try_emplace(lower(name), name);
    }
    return it->second;
}

} // namespace lw::dicom::detail
