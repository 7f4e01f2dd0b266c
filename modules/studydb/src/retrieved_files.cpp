#include "lw/studydb/retrieved_files.h"

#include "lw/core/error.h"
#include "lw/studydb/study_importer.h"

namespace lw::studydb {

Registration registerRetrievedFolder(const QString& databasePath, const QString& folder) {
    const ImportSummary summary = importStudies(databasePath, folder);
    if (!summary.errors.isEmpty())
        throw core::Error(
            folder.toStdString(),
            "registering in " + databasePath.toStdString() + ": " +
                std::to_string(summary.errors.size()) +
                " import errors, the first: " + summary.errors.first().file.toStdString() + ": " +
                summary.errors.first().reason.toStdString());
    return {databasePath, summary.seriesAdded, summary.seriesUpdated};
}

} // namespace lw::studydb
