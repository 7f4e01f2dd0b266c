#pragma once

// Registers what a PACS retrieve put into the managed store in the study database, in place
// (the importer references files where they are). Shared by `linework-cli pacs get` and the
// workstation's retrieve, so both register exactly the same way.

#include <QString>

namespace lw::studydb {

struct Registration {
    QString database;
    int seriesAdded = 0;
    int seriesUpdated = 0;
};

// Imports `folder` (a retrieved series or study folder of the store) into the database at
// `databasePath`, on the calling thread with its own connection. Throws core::Error naming the
// folder, the database and the first file that failed, when any file did not import.
Registration registerRetrievedFolder(const QString& databasePath, const QString& folder);

} // namespace lw::studydb
