#include "pacs_database.h"

#include "lw/studydb/retrieved_files.h"
#include "lw/studydb/study_database.h"

#include <QCoreApplication>

namespace lw::cli {

bool canRegisterInDatabase() {
    return true;
}

Registration registerInDatabase(const std::filesystem::path& folder, const std::string& database) {
    // Qt SQL loads its SQLite driver as a plugin, through a QCoreApplication; the names are the
    // workstation's, so the default database is the one it opens (app/gui/main.cpp).
    int argc = 1;
    char name[] = "linework-cli";
    char* argv[] = {name, nullptr};
    const QCoreApplication application(argc, argv);
    QCoreApplication::setOrganizationName("Linework");
    QCoreApplication::setApplicationName("linework");
    const QString path =
        database.empty() ? studydb::StudyDatabase::defaultPath() : QString::fromStdString(database);
    const studydb::Registration registration =
        studydb::registerRetrievedFolder(path, QString::fromStdString(folder.string()));
    return {path.toStdString(), registration.seriesAdded, registration.seriesUpdated};
}

} // namespace lw::cli
