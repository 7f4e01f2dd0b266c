#include "folder_walk.h"

#include "scan_paths.h"

#include <algorithm>

namespace fs = std::filesystem;

namespace lw::dicom::detail {

void walkFolder(const fs::path& dir, WalkState& state) {
    if (!state.visitedDirs.insert(canonicalOrAbsolute(dir)).second)
        return;
    if (state.progress)
        state.progress->throwIfCancelled();
    std::error_code ec;
    fs::directory_iterator it(dir, fs::directory_options::skip_permission_denied, ec);
    if (ec) {
        state.errors.push_back({dir.string(), "cannot list folder: " + ec.message()});
        return;
    }
    std::vector<fs::path> subdirs;
    for (; it != fs::directory_iterator(); it.increment(ec)) {
        if (ec)
            break;
        const fs::path entry = it->path();
        std::error_code statEc;
        const auto status = fs::status(entry, statEc); // follows symlinks
        if (statEc) {
            // A dangling symlink is a file someone expected to be there: say so.
            state.errors.push_back({entry.string(), "cannot access: " + statEc.message()});
            continue;
        }
        if (fs::is_directory(status))
            subdirs.push_back(entry);
        else if (fs::is_regular_file(status))
            state.files.push_back(entry);
    }
    if (ec)
        state.errors.push_back({dir.string(), "error while listing folder: " + ec.message()});
    std::sort(subdirs.begin(), subdirs.end());
    for (const auto& sub : subdirs)
        walkFolder(sub, state);
}

} // namespace lw::dicom::detail
