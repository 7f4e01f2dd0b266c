#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace lw::test {

// Error-level log messages fail the running test (an error logged is a failure, even where the
// code goes on);
// every message is echoed to stderr. Installed by the gtest mains before RUN_ALL_TESTS.
void installFailingLogSink();
// ../shared/data (or $LINEWORK_SHARED_DATA) when it exists.
std::optional<std::filesystem::path> sharedDataDir();
// The source tree (for tests/data and resources/).
std::filesystem::path sourceDir();
// The first of the programs in `names` (separated by spaces) that is not on PATH; empty when all
// are there. Tests that run a tool (pdftotext, dciodvfy) SKIP without it.
std::string firstMissingProgram(const std::string& names);
// A fresh temporary directory removed when the object goes out of scope.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return m_path; }
    std::filesystem::path operator/(const std::filesystem::path& name) const {
        return m_path / name;
    }

private:
    std::filesystem::path m_path;
};

} // namespace lw::test
