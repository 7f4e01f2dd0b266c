#pragma once

#include <filesystem>
#include <optional>

namespace lw::test {

// ../shared/data (or $LINEWORK_SHARED_DATA) when it exists.
std::optional<std::filesystem::path> sharedDataDir();
// The source tree (for tests/data and resources/).
std::filesystem::path sourceDir();
// A fresh temporary directory removed when the object goes out of scope.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return m_path; }
    std::filesystem::path operator/(const std::filesystem::path& name) const { return m_path / name; }

private:
    std::filesystem::path m_path;
};

} // namespace lw::test
