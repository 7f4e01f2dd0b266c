#include "pacs/remote_study_model.h"

#include <QApplication>
#include <QBrush>
#include <QDate>
#include <QStyle>

namespace lw::gui {

namespace {

// Remote rows are drawn in this blue, local ones in the palette's text colour.
const QColor kRemoteColour(30, 90, 170);

QString text(const std::string& value) {
    return QString::fromStdString(value);
}

QString count(int instances) {
    return instances < 0 ? QString() : QString::number(instances);
}

// DICOM's YYYYMMDD as the browser shows dates; anything else as it came.
QString displayDate(const std::string& value) {
    const QDate date = QDate::fromString(text(value), QStringLiteral("yyyyMMdd"));
    return date.isValid() ? date.toString(QStringLiteral("yyyy-MM-dd")) : text(value);
}

// "DOE^JANE" as "DOE, JANE": the local tree's patient rows read that way too.
QString displayName(const std::string& dicomName) {
    QStringList parts = text(dicomName).split(QLatin1Char('^'), Qt::SkipEmptyParts);
    return parts.join(QStringLiteral(", "));
}

} // namespace

RemoteStudyModel::RemoteStudyModel(QObject* parent)
    : QAbstractItemModel(parent),
      m_remoteIcon(QApplication::style()->standardIcon(QStyle::SP_DriveNetIcon)) {}

void RemoteStudyModel::setStudies(const QString& nodeName, std::vector<pacs::StudyRecord> studies) {
    beginResetModel();
    m_nodeName = nodeName;
    m_studies.clear();
    for (pacs::StudyRecord& record : studies)
        m_studies.push_back({std::move(record), {}, false});
    endResetModel();
}

void RemoteStudyModel::setSeries(const QString& studyUid, std::vector<pacs::SeriesRecord> series) {
    const QModelIndex parent = indexOfStudy(studyUid);
    if (!parent.isValid())
        return;
    Study& study = m_studies[std::size_t(parent.row())];
    if (!study.series.empty()) {
        beginRemoveRows(parent, 0, int(study.series.size()) - 1);
        study.series.clear();
        endRemoveRows();
    }
    study.seriesListed = true;
    if (series.empty())
        return;
    beginInsertRows(parent, 0, int(series.size()) - 1);
    study.series = std::move(series);
    endInsertRows();
}

void RemoteStudyModel::clear() {
    setStudies(m_nodeName, {});
}

const pacs::StudyRecord* RemoteStudyModel::studyAt(const QModelIndex& index) const {
    if (!index.isValid())
        return nullptr;
    const std::size_t study =
        index.internalId() == 0 ? std::size_t(index.row()) : std::size_t(index.internalId() - 1);
    return study < m_studies.size() ? &m_studies[study].record : nullptr;
}

const pacs::SeriesRecord* RemoteStudyModel::seriesAt(const QModelIndex& index) const {
    if (!index.isValid() || index.internalId() == 0)
        return nullptr;
    const Study& study = m_studies.at(std::size_t(index.internalId() - 1));
    return std::size_t(index.row()) < study.series.size() ? &study.series[std::size_t(index.row())]
                                                          : nullptr;
}

QModelIndex RemoteStudyModel::indexOfStudy(const QString& studyUid) const {
    for (std::size_t row = 0; row < m_studies.size(); ++row)
        if (text(m_studies[row].record.studyInstanceUid) == studyUid)
            return index(int(row), 0);
    return {};
}

bool RemoteStudyModel::seriesListed(const QModelIndex& studyIndex) const {
    return studyIndex.isValid() && studyIndex.internalId() == 0 &&
           m_studies.at(std::size_t(studyIndex.row())).seriesListed;
}

QModelIndex RemoteStudyModel::index(int row, int column, const QModelIndex& parent) const {
    if (!hasIndex(row, column, parent))
        return {};
    return createIndex(row, column, parent.isValid() ? quintptr(parent.row() + 1) : quintptr(0));
}

QModelIndex RemoteStudyModel::parent(const QModelIndex& index) const {
    if (!index.isValid() || index.internalId() == 0)
        return {};
    return createIndex(int(index.internalId() - 1), 0, quintptr(0));
}

int RemoteStudyModel::rowCount(const QModelIndex& parent) const {
    if (!parent.isValid())
        return int(m_studies.size());
    if (parent.internalId() != 0 || parent.column() != 0)
        return 0; // series rows have no children
    return int(m_studies.at(std::size_t(parent.row())).series.size());
}

int RemoteStudyModel::columnCount(const QModelIndex&) const {
    return ColumnCount;
}

bool RemoteStudyModel::hasChildren(const QModelIndex& parent) const {
    if (!parent.isValid())
        return !m_studies.empty();
    // A study not yet asked for its series can be expanded: expanding it asks the PACS.
    if (parent.internalId() == 0 && parent.column() == 0)
        return !seriesListed(parent) || rowCount(parent) > 0;
    return false;
}

QVariant RemoteStudyModel::data(const QModelIndex& index, int role) const {
    if (!index.isValid())
        return {};
    if (role == Qt::DisplayRole) {
        const pacs::SeriesRecord* series = seriesAt(index);
        return series ? seriesDisplay(*series, index.column())
                      : studyDisplay(*studyAt(index), index.column());
    }
    return roleData(index, role);
}

QVariant RemoteStudyModel::roleData(const QModelIndex& index, int role) const {
    switch (role) {
    case Qt::DecorationRole:
        return index.column() == NameColumn ? QVariant(m_remoteIcon) : QVariant();
    case Qt::ForegroundRole:
        return QBrush(kRemoteColour);
    case Qt::ToolTipRole:
        return seriesAt(index) ? tr("On %1: double-click to retrieve and open").arg(m_nodeName)
                               : tr("On %1: expand for its series, Retrieve in the context menu")
                                     .arg(m_nodeName);
    case StudyUidRole:
        return text(studyAt(index)->studyInstanceUid);
    case SeriesUidRole:
        return seriesAt(index) ? text(seriesAt(index)->seriesInstanceUid) : QVariant();
    case RemoteNodeRole:
        return m_nodeName;
    default:
        return {};
    }
}

QVariant RemoteStudyModel::studyDisplay(const pacs::StudyRecord& study, int column) const {
    switch (column) {
    case NameColumn:
        return QStringLiteral("%1 (%2)").arg(displayName(study.patientName), text(study.patientId));
    case ModalityColumn:
        return text(study.modalities).replace(QLatin1Char('\\'), QLatin1Char(' '));
    case DateColumn:
        return displayDate(study.studyDate);
    case InstancesColumn:
        return count(study.numberOfInstances);
    case DescriptionColumn:
        return text(study.studyDescription);
    default:
        return {};
    }
}

QVariant RemoteStudyModel::seriesDisplay(const pacs::SeriesRecord& series, int column) const {
    switch (column) {
    case NameColumn:
        return QStringLiteral("#%1 %2").arg(text(series.seriesNumber),
                                            text(series.seriesDescription));
    case ModalityColumn:
        return text(series.modality);
    case InstancesColumn:
        return count(series.numberOfInstances);
    default:
        return {};
    }
}

QVariant RemoteStudyModel::headerData(int section, Qt::Orientation orientation, int role) const {
    if (orientation != Qt::Horizontal || role != Qt::DisplayRole)
        return {};
    switch (section) {
    case NameColumn:
        return tr("Remote: %1").arg(m_nodeName);
    case ModalityColumn:
        return tr("Modality");
    case DateColumn:
        return tr("Date");
    case InstancesColumn:
        return tr("Images");
    case DescriptionColumn:
        return tr("Description");
    default:
        return {};
    }
}

} // namespace lw::gui
