#pragma once

// Patient -> study -> series tree of the study database, for a QTreeView. Holds plain records
// (read once per reload), so painting never touches the database.

#include "lw/studydb/study_records.h"

#include <QAbstractItemModel>
#include <QIcon>
#include <vector>

namespace lw::studydb {
class StudyDatabase;
}

namespace lw::gui {

class StudyTreeModel : public QAbstractItemModel {
    Q_OBJECT

public:
    enum Column {
        NameColumn,
        ModalityColumn,
        DateColumn,
        SlicesColumn,
        DimsColumn,
        SpacingColumn,
        WarningsColumn,
        ColumnCount
    };
    enum class Kind { Patient, Study, Series };
    enum Role {
        SeriesUidRole = Qt::UserRole + 1, // QString, series rows only
        StudyUidRole,                     // QString, study and series rows
        KindRole,                         // int(Kind)
        WarningCountRole,                 // int: warnings + failed files, series rows only
        WarningTextRole,                  // QString: every warning and failed file, one per line
    };

    explicit StudyTreeModel(QObject* parent = nullptr);

    // Re-reads the tree that passes `filter`. Throws core::Error when the database cannot be read
    // (the model is then empty).
    void reload(const studydb::StudyDatabase& database, const studydb::StudyFilter& filter = {});

    // The series behind a series row; nullptr for patient and study rows.
    const studydb::SeriesRecord* seriesAt(const QModelIndex& index) const;
    QModelIndex indexOfSeries(const QString& seriesUid) const;
    // Series UIDs of `index` and everything below it.
    QStringList seriesUidsUnder(const QModelIndex& index) const;
    int seriesRowCount() const;

    QModelIndex index(int row, int column, const QModelIndex& parent = {}) const override;
    QModelIndex parent(const QModelIndex& index) const override;
    int rowCount(const QModelIndex& parent = {}) const override;
    int columnCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    QVariant headerData(int section, Qt::Orientation orientation,
                        int role = Qt::DisplayRole) const override;

    // All warnings and failed files of a series, one per line (tooltips and the details pane).
    static QString warningText(const studydb::SeriesRecord& series);

private:
    struct Node {
        Kind kind = Kind::Patient;
        int parent = -1; // node index; -1 for the invisible root
        int row = 0;
        int patient = -1, study = -1, series = -1; // indices into m_patients
        std::vector<int> children;
        QIcon icon;
    };

    void rebuild();
    int addNode(Node node);
    const Node& nodeAt(const QModelIndex& index) const;
    QVariant displayData(const Node& node, int column) const;
    QVariant seriesDisplay(const studydb::SeriesRecord& series, int column) const;

    QList<studydb::PatientRecord> m_patients;
    std::vector<Node> m_nodes; // m_nodes[0] is the invisible root
};

} // namespace lw::gui
