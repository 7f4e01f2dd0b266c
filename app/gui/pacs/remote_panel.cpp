#include "pacs/remote_panel.h"

#include "browser/background_task.h"
#include "pacs/remote_study_model.h"
#include "pacs/retrieve_job.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMessageBox>
#include <QProgressDialog>
#include <QPushButton>
#include <QTreeView>
#include <QVBoxLayout>
#include <algorithm>

namespace lw::gui {

namespace {

QLineEdit* makeEdit(QWidget* parent, const QString& objectName, const QString& placeholder) {
    auto* edit = new QLineEdit(parent);
    edit->setObjectName(objectName);
    edit->setPlaceholderText(placeholder);
    edit->setClearButtonEnabled(true);
    return edit;
}

} // namespace

RemotePanel::RemotePanel(QString databasePath, QWidget* parent)
    : QWidget(parent), m_databasePath(std::move(databasePath)),
      m_locations(pacsLocationsBeside(m_databasePath)) {
    setObjectName(QStringLiteral("remotePanel"));
    m_model = new RemoteStudyModel(this);
    m_retrieve = new RetrieveJob(m_databasePath, this);
    connect(m_retrieve, &RetrieveJob::instanceArrived, this, &RemotePanel::showProgress);
    connect(m_retrieve, &RetrieveJob::finished, this, &RemotePanel::onRetrieveFinished);
    connect(m_retrieve, &RetrieveJob::failed, this, &RemotePanel::onRetrieveFailed);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(buildQueryBar());
    m_status = new QLabel(this);
    m_status->setObjectName(QStringLiteral("remoteStatus"));
    m_status->setWordWrap(true);
    m_status->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_status->hide();
    layout->addWidget(m_status);
    buildTree();
    layout->addWidget(m_tree, 1);
    m_progress = new QProgressDialog(this);
    m_progress->setObjectName(QStringLiteral("retrieveProgress"));
    m_progress->setWindowTitle(tr("Retrieve"));
    m_progress->setAutoClose(false);
    m_progress->setAutoReset(false);
    m_progress->setMinimumDuration(0);
    connect(m_progress, &QProgressDialog::canceled, m_retrieve, &RetrieveJob::cancel);
    m_progress->reset();
    m_progress->hide();
    reloadNodes();
}

RemotePanel::~RemotePanel() {
    // Their results are queued to this panel: nothing may still be running once it goes.
    m_retrieve->cancel();
    m_retrieve->waitForDone();
    cancelQuery();
    for (QFuture<void>& query : m_queries)
        query.waitForFinished();
}

QWidget* RemotePanel::buildQueryBar() {
    auto* bar = new QWidget(this);
    auto* layout = new QHBoxLayout(bar);
    layout->setContentsMargins(0, 0, 0, 0);
    m_node = new QComboBox(bar);
    m_node->setObjectName(QStringLiteral("pacsNodeCombo"));
    m_node->setToolTip(tr("The PACS to query (Settings → PACS)"));
    m_patientName = makeEdit(bar, QStringLiteral("remotePatientName"), tr("Patient name (DOE^J*)"));
    m_patientId = makeEdit(bar, QStringLiteral("remotePatientId"), tr("Patient ID"));
    m_dates = makeEdit(bar, QStringLiteral("remoteDates"), tr("Dates YYYYMMDD-YYYYMMDD"));
    m_modality = new QComboBox(bar);
    m_modality->setObjectName(QStringLiteral("remoteModality"));
    m_modality->setEditable(true);
    m_modality->addItems({QString(), QStringLiteral("CT"), QStringLiteral("MR"),
                          QStringLiteral("PT"), QStringLiteral("US"), QStringLiteral("CR")});
    m_modality->setMinimumContentsLength(4);
    m_modality->setToolTip(tr("Modality in the study (empty: any)"));
    m_search = new QPushButton(tr("Search PACS"), bar);
    m_search->setObjectName(QStringLiteral("remoteSearchButton"));
    m_cancel = new QPushButton(tr("Cancel"), bar);
    m_cancel->setObjectName(QStringLiteral("remoteCancelButton"));
    m_cancel->setEnabled(false);
    connect(m_search, &QPushButton::clicked, this, &RemotePanel::search);
    connect(m_cancel, &QPushButton::clicked, this, &RemotePanel::cancelQuery);
    for (QLineEdit* edit : {m_patientName, m_patientId, m_dates})
        connect(edit, &QLineEdit::returnPressed, this, &RemotePanel::search);
    layout->addWidget(m_node);
    layout->addWidget(m_patientName, 2);
    layout->addWidget(m_patientId, 1);
    layout->addWidget(m_dates, 1);
    layout->addWidget(m_modality);
    layout->addWidget(m_search);
    layout->addWidget(m_cancel);
    return bar;
}

void RemotePanel::buildTree() {
    m_tree = new QTreeView(this);
    m_tree->setObjectName(QStringLiteral("remoteTree"));
    m_tree->setModel(m_model);
    m_tree->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_tree->setAllColumnsShowFocus(true);
    m_tree->setContextMenuPolicy(Qt::CustomContextMenu);
    m_tree->header()->setSectionResizeMode(QHeaderView::ResizeToContents);
    connect(m_tree, &QTreeView::expanded, this, &RemotePanel::listSeries);
    connect(m_tree, &QTreeView::activated, this, &RemotePanel::onActivated);
    connect(m_tree, &QTreeView::customContextMenuRequested, this, &RemotePanel::showContextMenu);
}

QString RemotePanel::statusText() const {
    return m_status->isVisible() ? m_status->text() : QString();
}

bool RemotePanel::isQuerying() const {
    return m_querying;
}

void RemotePanel::reloadNodes() {
    const QString chosen = m_node->currentText();
    try {
        m_nodeFile = pacs::readNodeFileOrDefaults(m_locations.nodeFile.toStdString());
    } catch (const core::Error& error) {
        m_nodeFile = {};
        showStatus(tr("The PACS nodes cannot be read: %1").arg(errorText(error)), true);
    }
    m_node->clear();
    for (const pacs::PacsNode& node : m_nodeFile.nodes)
        m_node->addItem(QString::fromStdString(node.name));
    m_node->setCurrentIndex(std::max(0, m_node->findText(chosen)));
    m_search->setEnabled(!m_querying && m_node->count() > 0);
    m_node->setPlaceholderText(tr("no PACS: Settings → PACS"));
}

const pacs::PacsNode* RemotePanel::chosenNode() {
    const pacs::PacsNode* node = m_nodeFile.find(m_node->currentText().toStdString());
    if (!node)
        showStatus(tr("Choose a PACS node (Settings → PACS adds one)"), true);
    return node;
}

pacs::CallOptions RemotePanel::callOptions() const {
    return {m_nodeFile.workstation.aet, pacs::CallOptions{}.timeout};
}

void RemotePanel::keep(QFuture<void> query) {
    m_queries.removeIf([](const QFuture<void>& done) { return done.isFinished(); });
    m_queries.append(std::move(query));
}

void RemotePanel::setQuerying(bool querying) {
    m_querying = querying;
    m_search->setEnabled(!querying && m_node->count() > 0);
    m_cancel->setEnabled(querying);
}

void RemotePanel::search() {
    if (m_querying)
        return;
    const pacs::PacsNode* chosen = chosenNode();
    if (!chosen)
        return;
    pacs::StudyQuery query;
    query.patientName = m_patientName->text().trimmed().toStdString();
    query.patientId = m_patientId->text().trimmed().toStdString();
    query.modality = m_modality->currentText().trimmed().toStdString();
    try {
        if (!m_dates->text().trimmed().isEmpty())
            std::tie(query.dateFrom, query.dateTo) =
                pacs::parseDateRange(m_dates->text().trimmed().toStdString());
    } catch (const core::Error& error) {
        return showStatus(tr("Dates: %1").arg(errorText(error)), true);
    }
    const pacs::PacsNode node = *chosen;
    const QString nodeName = QString::fromStdString(node.name);
    m_queryCancel = std::make_shared<core::CancelToken>();
    setQuerying(true);
    showStatus(tr("Searching %1…").arg(nodeName), false);
    keep(runInBackground(
        this,
        [node, query, options = callOptions(), cancel = m_queryCancel] {
            return pacs::findStudies(node, query, options, cancel.get());
        },
        [this, nodeName](const std::vector<pacs::StudyRecord>& studies) {
            setQuerying(false);
            m_model->setStudies(nodeName, studies);
            showStatus(tr("Studies found on %1: %2").arg(nodeName).arg(studies.size()), false);
            emit queryFinished(int(studies.size()));
        },
        [this] {
            setQuerying(false);
            showStatus(tr("Query cancelled"), false);
        },
        [this, nodeName](const QString& message) {
            setQuerying(false);
            showStatus(tr("Query of %1 failed: %2").arg(nodeName, message), true);
            emit queryFailed(message);
        }));
}

void RemotePanel::cancelQuery() {
    if (m_queryCancel)
        m_queryCancel->cancel();
}

void RemotePanel::listSeries(const QModelIndex& studyIndex) {
    const pacs::StudyRecord* study = m_model->studyAt(studyIndex);
    const pacs::PacsNode* node = m_nodeFile.find(m_model->nodeName().toStdString());
    if (!study || m_model->seriesAt(studyIndex) || m_model->seriesListed(studyIndex) || !node)
        return;
    const QString studyUid = QString::fromStdString(study->studyInstanceUid);
    if (!m_queryCancel || m_queryCancel->isCancelled())
        m_queryCancel = std::make_shared<core::CancelToken>();
    keep(runInBackground(
        this,
        [node = *node, uid = study->studyInstanceUid, options = callOptions(),
         cancel = m_queryCancel] { return pacs::findSeries(node, uid, options, cancel.get()); },
        [this, studyUid](const std::vector<pacs::SeriesRecord>& series) {
            m_model->setSeries(studyUid, series);
            emit seriesListed(studyUid, int(series.size()));
        },
        [] {},
        [this](const QString& message) {
            showStatus(tr("Series query failed: %1").arg(message), true);
            emit queryFailed(message);
        }));
}

void RemotePanel::onActivated(const QModelIndex& index) {
    if (m_model->seriesAt(index))
        retrieve(index);
}

void RemotePanel::showContextMenu(const QPoint& at) {
    const QModelIndex index = m_tree->indexAt(at);
    if (!index.isValid())
        return;
    QMenu menu(this);
    QAction* retrieveAction = menu.addAction(
        m_model->seriesAt(index) ? tr("Retrieve series and open") : tr("Retrieve study"));
    if (menu.exec(m_tree->viewport()->mapToGlobal(at)) == retrieveAction)
        retrieve(index);
}

void RemotePanel::retrieve(const QModelIndex& index) {
    const pacs::StudyRecord* study = m_model->studyAt(index);
    const pacs::PacsNode* node = m_nodeFile.find(m_model->nodeName().toStdString());
    if (!study)
        return;
    if (!node)
        return showStatus(tr("%1 is no longer a PACS node").arg(m_model->nodeName()), true);
    if (m_retrieve->isRunning())
        return showStatus(tr("A retrieve is running: wait for it or cancel it"), true);
    const pacs::SeriesRecord* series = m_model->seriesAt(index);
    pacs::RetrieveRequest request;
    request.studyUid = study->studyInstanceUid;
    request.seriesUid = series ? series->seriesInstanceUid : std::string();
    request.store = m_locations.store.toStdString();
    request.storagePort = m_nodeFile.workstation.storagePort;
    request.method = node->retrieve; // C-MOVE where Settings → PACS says so
    m_openAfterRetrieve = series != nullptr;
    m_retrieve->start(*node, request, callOptions());
    m_progress->setLabelText(tr("Retrieving from %1…").arg(m_model->nodeName()));
    m_progress->setRange(0, 0); // how many are missing is known with the first instance
    m_progress->setValue(0);
    m_progress->show();
}

void RemotePanel::showProgress(int done, int toTransfer) {
    m_progress->setRange(0, toTransfer);
    m_progress->setValue(done);
    m_progress->setLabelText(tr("Retrieving from %1: %2 of %3 images")
                                 .arg(m_model->nodeName())
                                 .arg(done)
                                 .arg(toTransfer));
}

void RemotePanel::onRetrieveFinished(const RetrieveOutcome& outcome) {
    m_progress->hide();
    const QString here = tr("%1 of %2 images are here (%3 were already)")
                             .arg(outcome.transferred + outcome.skipped)
                             .arg(outcome.instances)
                             .arg(outcome.skipped);
    if (outcome.cancelled)
        showStatus(tr("Retrieve cancelled: %1; a new retrieve fetches the others").arg(here),
                   false);
    else if (outcome.complete())
        showStatus(tr("Retrieved from %1: %2").arg(outcome.nodeName, here), false);
    else
        onRetrieveFailed(QStringLiteral("%1 (%2)").arg(outcome.message, here));
    emit retrieved(outcome.seriesUid, m_openAfterRetrieve && outcome.complete());
}

void RemotePanel::onRetrieveFailed(const QString& message) {
    m_progress->hide();
    const QString text = tr("Retrieve from %1 failed: %2").arg(m_model->nodeName(), message);
    showStatus(text, true);
    // Not modal, so tests and a busy user carry on; the status line keeps the message too.
    auto* box = new QMessageBox(QMessageBox::Warning, tr("Retrieve"), text, QMessageBox::Ok, this);
    box->setObjectName(QStringLiteral("retrieveErrorBox"));
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->open();
}

void RemotePanel::showStatus(const QString& text, bool isError) {
    m_status->setText(text);
    m_status->setStyleSheet(isError ? QStringLiteral("color: #b00020") : QString());
    m_status->setVisible(!text.isEmpty());
}

} // namespace lw::gui
