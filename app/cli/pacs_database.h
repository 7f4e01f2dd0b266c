#pragma once

// Registers what `pacs get` retrieved in the workstation's study database, in place in the
// managed store (modules/studydb's importer; compiled in where it is built, Qt SQL).
#include <filesystem>
#include <optional>
#include <string>

namespace lw::cli {

struct Registration {
    std::string database;
    int seriesAdded = 0;
    int seriesUpdated = 0;
};

// False in a build without modules/studydb.
bool canRegisterInDatabase();

// Imports `folder` into `database` (empty: the workstation's, as the GUI opens it). Throws
// core::Error naming the database or the folder.
Registration registerInDatabase(const std::filesystem::path& folder, const std::string& database);

} // namespace lw::cli
