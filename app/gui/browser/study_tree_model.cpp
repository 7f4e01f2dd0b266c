#include "browser/study_tree_model.h"

#include "lw/studydb/study_database.h"

#include <QPixmap>

namespace lw::gui {

using studydb::PatientRecord;
using studydb::SeriesRecord;
using studydb::StudyRecord;

namespace {

QString formatDate(const QString& dicomDate) {
    const QDate date = studydb::parseDicomDate(dicomDate);
    return date.isValid() ? date.toString(Qt::ISODate) : dicomDate;
}

QString formatNumber(double value) {
    return QString::number(value, 'g', 4);
}

} // namespace

StudyTreeModel::StudyTreeModel(QObject* parent) : QAbstractItemModel(parent) {
    rebuild();
}

void StudyTreeModel::reload(const studydb::StudyDatabase& database,
                            const studydb::StudyFilter& filter) {
    beginResetModel();
    try {
        m_patients = database.patients(filter);
    } catch (...) {
        m_patients.clear();
        rebuild();
        endResetModel();
        throw;
    }
    rebuild();
    endResetModel();
}

int StudyTreeModel::addNode(Node node) {
    const int id = int(m_nodes.size());
    Node& parent = m_nodes[std::size_t(node.parent)];
    node.row = int(parent.children.size());
    parent.children.push_back(id);
    m_nodes.push_back(std::move(node));
    return id;
}

void StudyTreeModel::rebuild() {
    m_nodes.clear();
    m_nodes.push_back(Node{}); // the root
    for (int p = 0; p < m_patients.size(); ++p) {
        const int patientNode = addNode({Kind::Patient, 0, 0, p, -1, -1, {}, {}});
        const PatientRecord& patient = m_patients[p];
        for (int s = 0; s < patient.studies.size(); ++s) {
            const int studyNode = addNode({Kind::Study, patientNode, 0, p, s, -1, {}, {}});
            for (int r = 0; r < patient.studies[s].series.size(); ++r) {
                // Decoded once here: painting a PNG per repaint would stall scrolling.
                const QImage thumbnail = patient.studies[s].series[r].thumbnail();
                const QIcon icon =
                    thumbnail.isNull() ? QIcon() : QIcon(QPixmap::fromImage(thumbnail));
                addNode({Kind::Series, studyNode, 0, p, s, r, {}, icon});
            }
        }
    }
}

const StudyTreeModel::Node& StudyTreeModel::nodeAt(const QModelIndex& index) const {
    return m_nodes[index.isValid() ? std::size_t(index.internalId()) : 0];
}

const SeriesRecord* StudyTreeModel::seriesAt(const QModelIndex& index) const {
    if (!index.isValid())
        return nullptr;
    const Node& node = nodeAt(index);
    if (node.kind != Kind::Series)
        return nullptr;
    return &m_patients[node.patient].studies[node.study].series[node.series];
}

QModelIndex StudyTreeModel::indexOfSeries(const QString& seriesUid) const {
    for (std::size_t i = 1; i < m_nodes.size(); ++i) {
        const Node& node = m_nodes[i];
        if (node.kind == Kind::Series &&
            m_patients[node.patient].studies[node.study].series[node.series].uid == seriesUid)
            return createIndex(node.row, 0, quintptr(i));
    }
    return {};
}

QStringList StudyTreeModel::seriesUidsUnder(const QModelIndex& index) const {
    QStringList result;
    if (const SeriesRecord* series = seriesAt(index))
        return {series->uid};
    for (int row = 0; row < rowCount(index.siblingAtColumn(0)); ++row)
        result += seriesUidsUnder(this->index(row, 0, index.siblingAtColumn(0)));
    return result;
}

int StudyTreeModel::seriesRowCount() const {
    int count = 0;
    for (const Node& node : m_nodes)
        count += node.kind == Kind::Series ? 1 : 0;
    return count;
}

QModelIndex StudyTreeModel::index(int row, int column, const QModelIndex& parent) const {
    if (column < 0 || column >= ColumnCount || (parent.isValid() && parent.column() != 0))
        return {};
    const Node& node = nodeAt(parent);
    if (row < 0 || std::size_t(row) >= node.children.size())
        return {};
    return createIndex(row, column, quintptr(node.children[std::size_t(row)]));
}

QModelIndex StudyTreeModel::parent(const QModelIndex& index) const {
    if (!index.isValid())
        return {};
    const Node& node = nodeAt(index);
    if (node.parent <= 0)
        return {};
    return createIndex(m_nodes[std::size_t(node.parent)].row, 0, quintptr(node.parent));
}

int StudyTreeModel::rowCount(const QModelIndex& parent) const {
    if (parent.isValid() && parent.column() != 0)
        return 0;
    return int(nodeAt(parent).children.size());
}

int StudyTreeModel::columnCount(const QModelIndex&) const {
    return ColumnCount;
}

QVariant StudyTreeModel::headerData(int section, Qt::Orientation orientation, int role) const {
    if (orientation != Qt::Horizontal || role != Qt::DisplayRole)
        return {};
    switch (section) {
    case NameColumn:
        return tr("Patient / study / series");
    case ModalityColumn:
        return tr("Modality");
    case DateColumn:
        return tr("Date");
    case SlicesColumn:
        return tr("Slices");
    case DimsColumn:
        return tr("Dimensions");
    case SpacingColumn:
        return tr("Spacing (mm)");
    case WarningsColumn:
        return tr("Warnings");
    default:
        return {};
    }
}

QString StudyTreeModel::warningText(const SeriesRecord& series) {
    QStringList lines;
    for (const QString& warning : series.warnings())
        lines.append(warning);
    for (const studydb::SeriesMessage& error : series.fileErrors())
        lines.append(tr("%1: %2").arg(error.file, error.text));
    return lines.join(QLatin1Char('\n'));
}

QVariant StudyTreeModel::seriesDisplay(const SeriesRecord& series, int column) const {
    switch (column) {
    case NameColumn: {
        const QString description =
            series.description.isEmpty() ? tr("(no description)") : series.description;
        return series.number ? QStringLiteral("%1  %2").arg(*series.number).arg(description)
                             : description;
    }
    case ModalityColumn:
        return series.modality;
    case DateColumn:
        return formatDate(series.studyDate);
    case SlicesColumn:
        return series.sliceCount;
    case DimsColumn:
        return series.sliceCount > 0 ? QStringLiteral("%1 × %2 × %3")
                                           .arg(series.dims[0])
                                           .arg(series.dims[1])
                                           .arg(series.dims[2])
                                     : QString();
    case SpacingColumn:
        return series.sliceCount > 0
                   ? QStringLiteral("%1 × %2 × %3")
                         .arg(formatNumber(series.spacing[0]), formatNumber(series.spacing[1]),
                              formatNumber(series.spacing[2]))
                   : QString();
    case WarningsColumn: {
        const auto count = series.warnings().size() + series.fileErrors().size();
        return count > 0 ? QVariant(int(count)) : QVariant(QString());
    }
    default:
        return {};
    }
}

QVariant StudyTreeModel::displayData(const Node& node, int column) const {
    const PatientRecord& patient = m_patients[node.patient];
    if (node.kind == Kind::Patient) {
        if (column != NameColumn)
            return {};
        const QString name =
            patient.name.isEmpty() ? tr("(no name)") : studydb::displayName(patient.name);
        return patient.patientId.isEmpty() ? name
                                           : QStringLiteral("%1 (%2)").arg(name, patient.patientId);
    }
    const StudyRecord& study = patient.studies[node.study];
    if (node.kind == Kind::Study) {
        if (column == NameColumn)
            return study.description.isEmpty() ? tr("Study %1").arg(study.studyId)
                                               : study.description;
        return column == DateColumn ? QVariant(formatDate(study.date)) : QVariant();
    }
    return seriesDisplay(study.series[node.series], column);
}

QVariant StudyTreeModel::data(const QModelIndex& index, int role) const {
    if (!index.isValid())
        return {};
    const Node& node = nodeAt(index);
    const SeriesRecord* series = seriesAt(index);
    switch (role) {
    case Qt::DisplayRole:
        return displayData(node, index.column());
    case Qt::DecorationRole:
        return index.column() == NameColumn && series && !node.icon.isNull() ? QVariant(node.icon)
                                                                             : QVariant();
    case Qt::ToolTipRole:
        return series && index.column() == WarningsColumn ? QVariant(warningText(*series))
                                                          : QVariant();
    case SeriesUidRole:
        return series ? QVariant(series->uid) : QVariant();
    case StudyUidRole:
        return node.kind == Kind::Patient
                   ? QVariant()
                   : QVariant(m_patients[node.patient].studies[node.study].uid);
    case KindRole:
        return int(node.kind);
    case WarningCountRole:
        return series ? QVariant(int(series->warnings().size() + series->fileErrors().size()))
                      : QVariant();
    case WarningTextRole:
        return series ? QVariant(warningText(*series)) : QVariant();
    default:
        return {};
    }
}

} // namespace lw::gui
