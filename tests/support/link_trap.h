#pragma once

// An export folder laid out as an attacker would (issue 10: exports refuse to write outside the
// chosen folder), for the core, report, CLI and GUI tests alike (header only: the Qt tests do
// not link gtest). Under `root`:
//   outside/victim              a file no export may change      ("victim")
//   exports/own                 the user's file in the folder    ("own")
//   exports/<name>.to_outside   a link to outside/victim
//   exports/<name>.dangling     a link to outside/created, which does not exist
//   exports/<name>.to_inside    a link to exports/own
// untouched() says whether all of that is still exactly so.

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace lw::test {

class LinkTrap {
public:
    // `name` is the file name the export would write (the links are named after it).
    LinkTrap(const std::filesystem::path& root, const std::string& name)
        : m_exports(root / "exports"), m_outside(root / "outside"), m_name(name) {
        std::filesystem::create_directories(m_exports);
        std::filesystem::create_directories(m_outside);
        write(m_outside / "victim", "victim");
        write(m_exports / "own", "own");
    }

    const std::filesystem::path& exports() const { return m_exports; }
    const std::filesystem::path& outside() const { return m_outside; }

    // The link kinds a data-driven test runs over.
    static std::vector<std::string> kinds() { return {"to_outside", "dangling", "to_inside"}; }

    // Makes the named link as the export's target, named exactly `name` (the one link in the
    // folder at a time: each kind replaces the last) and returns its path.
    std::filesystem::path link(const std::string& kind) const {
        const std::filesystem::path target = kind == "to_outside" ? m_outside / "victim"
                                             : kind == "dangling" ? m_outside / "created"
                                                                  : m_exports / "own";
        const std::filesystem::path path = m_exports / m_name;
        std::filesystem::remove(path);
        std::filesystem::create_symlink(target, path);
        return path;
    }

    // Nothing created or changed outside, the user's file and the link kept as they were.
    bool untouched() const {
        const auto outsideEntries =
            std::distance(std::filesystem::directory_iterator(m_outside), {});
        return outsideEntries == 1 && read(m_outside / "victim") == "victim" &&
               read(m_exports / "own") == "own" &&
               std::filesystem::is_symlink(std::filesystem::symlink_status(m_exports / m_name)) &&
               std::distance(std::filesystem::directory_iterator(m_exports), {}) == 2;
    }

private:
    static void write(const std::filesystem::path& path, const std::string& text) {
        std::ofstream(path, std::ios::binary | std::ios::trunc) << text;
    }
    static std::string read(const std::filesystem::path& path) {
        std::ifstream in(path, std::ios::binary);
        return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    }

    std::filesystem::path m_exports, m_outside;
    std::string m_name;
};

} // namespace lw::test
