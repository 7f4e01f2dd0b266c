#pragma once

// Where the PACS files of a workstation live: beside its study database, as modules/pacs's
// defaults are beside the default database (so a test's temporary database gets its own).

#include <QFileInfo>
#include <QString>

namespace lw::gui {

struct PacsLocations {
    QString nodeFile; // pacs-nodes.json: the nodes and the workstation's AE title
    QString store;    // pacs-store: the managed store of retrieved instances
};

inline PacsLocations pacsLocationsBeside(const QString& databasePath) {
    const QString folder = QFileInfo(databasePath).absolutePath();
    return {folder + QStringLiteral("/pacs-nodes.json"), folder + QStringLiteral("/pacs-store")};
}

} // namespace lw::gui
