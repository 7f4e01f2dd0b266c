#pragma once

// What a PACS answered to a query: study rows (C-FIND, study level) and, once a study was
// expanded, its series rows (series level), for the remote part of the study browser. Every
// row is marked remote: a network icon, the node's name in tooltips and RemoteNodeRole.
//
//   (root)
//    ├─ study  "DOE^JANE"   CT   2024-03-01   140   "Chest"     ← studyAt(), hasChildren
//    │   ├─ series "#2 Axial 1mm"  CT   140                     ← seriesAt()
//    │   └─ series ...
//    └─ study ...
//   internalId: 0 for a study row; study row + 1 for a series row (its parent).

#include "lw/pacs/pacs_client.h"

#include <QAbstractItemModel>
#include <QIcon>
#include <vector>

namespace lw::gui {

class RemoteStudyModel : public QAbstractItemModel {
    Q_OBJECT

public:
    enum Column {
        NameColumn,
        ModalityColumn,
        DateColumn,
        InstancesColumn,
        DescriptionColumn,
        ColumnCount
    };
    enum Role {
        StudyUidRole = Qt::UserRole + 1, // study and series rows
        SeriesUidRole,                   // series rows
        RemoteNodeRole,                  // the node's name, every row
    };

    explicit RemoteStudyModel(QObject* parent = nullptr);

    // Replaces everything with `studies` found on `nodeName`; no series are known yet.
    void setStudies(const QString& nodeName, std::vector<pacs::StudyRecord> studies);
    // The series of the study `studyUid` (ignored when that study is no longer shown).
    void setSeries(const QString& studyUid, std::vector<pacs::SeriesRecord> series);
    void clear();

    const QString& nodeName() const { return m_nodeName; }
    const pacs::StudyRecord* studyAt(const QModelIndex& index) const;   // study and series rows
    const pacs::SeriesRecord* seriesAt(const QModelIndex& index) const; // series rows only
    QModelIndex indexOfStudy(const QString& studyUid) const;
    // Whether the series of a study were listed (an expanded study asks only once).
    bool seriesListed(const QModelIndex& studyIndex) const;

    QModelIndex index(int row, int column, const QModelIndex& parent = {}) const override;
    QModelIndex parent(const QModelIndex& index) const override;
    int rowCount(const QModelIndex& parent = {}) const override;
    int columnCount(const QModelIndex& parent = {}) const override;
    bool hasChildren(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    QVariant headerData(int section, Qt::Orientation orientation,
                        int role = Qt::DisplayRole) const override;

private:
    struct Study {
        pacs::StudyRecord record;
        std::vector<pacs::SeriesRecord> series;
        bool seriesListed = false;
    };

    QVariant studyDisplay(const pacs::StudyRecord& study, int column) const;
    QVariant seriesDisplay(const pacs::SeriesRecord& series, int column) const;
    QVariant roleData(const QModelIndex& index, int role) const;

    QString m_nodeName;
    std::vector<Study> m_studies;
    QIcon m_remoteIcon;
};

} // namespace lw::gui
