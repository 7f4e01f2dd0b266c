#include "browser/study_browser.h"

#include "browser/background_task.h"
#include "browser/import_worker.h"
#include "browser/study_tree_model.h"
#include "lw/core/error.h"
#include "lw/studydb/study_database.h"
#include "pacs/remote_panel.h"

#include <QDateEdit>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QShortcut>
#include <QSplitter>
#include <QTextBrowser>
#include <QTreeView>
#include <QVBoxLayout>

namespace lw::gui {

namespace {

// QDateEdit has no empty state: its minimum shows as "any" and means "no bound".
const QDate kAnyDate(1900, 1, 1);
constexpr int kDetailsThumbnailSize = 256;

QDateEdit* makeDateEdit(QWidget* parent, const QString& objectName) {
    auto* edit = new QDateEdit(parent);
    edit->setObjectName(objectName);
    edit->setCalendarPopup(true);
    edit->setMinimumDate(kAnyDate);
    edit->setSpecialValueText(StudyBrowser::tr("any"));
    edit->setDisplayFormat(QStringLiteral("yyyy-MM-dd"));
    edit->setDate(kAnyDate);
    return edit;
}

} // namespace

StudyBrowser::StudyBrowser(QString databasePath, QWidget* parent)
    : QWidget(parent), m_databasePath(std::move(databasePath)) {
    m_model = new StudyTreeModel(this);
    m_worker = new ImportWorker(m_databasePath, this);
    buildUi();
    connectSignals();
    setAcceptDrops(true);
    openDatabase();
}

StudyBrowser::~StudyBrowser() {
    // The worker's thread holds its own connection: stop it before the UI connection closes.
    m_pendingImports.clear();
    m_worker->cancel();
    m_worker->waitForDone();
}

void StudyBrowser::openDatabase() {
    try {
        m_database = std::make_unique<studydb::StudyDatabase>(m_databasePath);
        m_databaseError.clear();
        reload();
    } catch (const core::Error& error) {
        m_database.reset();
        m_databaseError = errorText(error);
        showMessage(tr("The study database cannot be opened: %1").arg(m_databaseError), true);
    }
    m_importFolderButton->setEnabled(m_database != nullptr);
    m_importDicomdirButton->setEnabled(m_database != nullptr);
}

studydb::StudyDatabase& StudyBrowser::database() {
    if (!m_database)
        throw core::Error(m_databasePath.toStdString(),
                          "the study database is not open: " + m_databaseError.toStdString());
    return *m_database;
}

void StudyBrowser::buildUi() {
    m_messageLabel = new QLabel(this);
    m_messageLabel->setObjectName(QStringLiteral("messageLabel"));
    m_messageLabel->setWordWrap(true);
    m_messageLabel->setTextInteractionFlags(Qt::TextSelectableByMouse);
    m_messageLabel->hide();

    m_tree = new QTreeView(this);
    m_tree->setObjectName(QStringLiteral("studyTree"));
    m_tree->setModel(m_model);
    m_tree->setSelectionMode(QAbstractItemView::ExtendedSelection);
    m_tree->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_tree->setIconSize(QSize(48, 48));
    m_tree->setUniformRowHeights(false);
    m_tree->setAllColumnsShowFocus(true);
    m_tree->header()->setSectionResizeMode(QHeaderView::ResizeToContents);

    // The local studies above, a PACS's answer below (marked remote).
    m_remote = new RemotePanel(m_databasePath, this);
    auto* localAndRemote = new QSplitter(Qt::Vertical, this);
    localAndRemote->addWidget(m_tree);
    localAndRemote->addWidget(m_remote);
    localAndRemote->setStretchFactor(0, 3);
    localAndRemote->setStretchFactor(1, 2);

    auto* splitter = new QSplitter(Qt::Horizontal, this);
    splitter->addWidget(localAndRemote);
    splitter->addWidget(buildDetailsPane());
    splitter->setStretchFactor(0, 3);
    splitter->setStretchFactor(1, 1);

    auto* layout = new QVBoxLayout(this);
    layout->addWidget(buildToolbar());
    layout->addWidget(m_messageLabel);
    layout->addWidget(buildImportPanel());
    layout->addWidget(splitter, 1);
}

QWidget* StudyBrowser::buildToolbar() {
    auto* bar = new QWidget(this);
    auto* layout = new QHBoxLayout(bar);
    layout->setContentsMargins(0, 0, 0, 0);
    m_importFolderButton = new QPushButton(tr("Import folder…"), bar);
    m_importFolderButton->setObjectName(QStringLiteral("importFolderButton"));
    m_importDicomdirButton = new QPushButton(tr("Import DICOMDIR…"), bar);
    m_importDicomdirButton->setObjectName(QStringLiteral("importDicomdirButton"));
    m_removeButton = new QPushButton(tr("Remove from database"), bar);
    m_removeButton->setObjectName(QStringLiteral("removeSeriesButton"));
    m_removeButton->setToolTip(
        tr("Removes the selected series from the database; the files on disk are kept"));
    m_removeButton->setEnabled(false);
    m_searchEdit = new QLineEdit(bar);
    m_searchEdit->setObjectName(QStringLiteral("searchEdit"));
    m_searchEdit->setPlaceholderText(tr("Search patient, ID, description…"));
    m_searchEdit->setClearButtonEnabled(true);
    m_fromEdit = makeDateEdit(bar, QStringLiteral("dateFromEdit"));
    m_toEdit = makeDateEdit(bar, QStringLiteral("dateToEdit"));
    layout->addWidget(m_importFolderButton);
    layout->addWidget(m_importDicomdirButton);
    layout->addWidget(m_removeButton);
    layout->addSpacing(12);
    layout->addWidget(m_searchEdit, 1);
    layout->addWidget(new QLabel(tr("From"), bar));
    layout->addWidget(m_fromEdit);
    layout->addWidget(new QLabel(tr("to"), bar));
    layout->addWidget(m_toEdit);
    return bar;
}

QWidget* StudyBrowser::buildImportPanel() {
    m_importPanel = new QWidget(this);
    m_importPanel->setObjectName(QStringLiteral("importPanel"));
    auto* layout = new QHBoxLayout(m_importPanel);
    layout->setContentsMargins(0, 0, 0, 0);
    m_importLabel = new QLabel(m_importPanel);
    m_progress = new QProgressBar(m_importPanel);
    m_progress->setObjectName(QStringLiteral("importProgress"));
    m_progress->setRange(0, 1000);
    m_cancelButton = new QPushButton(tr("Cancel"), m_importPanel);
    m_cancelButton->setObjectName(QStringLiteral("cancelImportButton"));
    layout->addWidget(m_importLabel);
    layout->addWidget(m_progress, 1);
    layout->addWidget(m_cancelButton);
    m_importPanel->hide();
    return m_importPanel;
}

QWidget* StudyBrowser::buildDetailsPane() {
    auto* pane = new QWidget(this);
    auto* layout = new QVBoxLayout(pane);
    layout->setContentsMargins(0, 0, 0, 0);
    m_thumbnail = new QLabel(pane);
    m_thumbnail->setObjectName(QStringLiteral("detailsThumbnail"));
    m_thumbnail->setAlignment(Qt::AlignCenter);
    m_thumbnail->setMinimumSize(kDetailsThumbnailSize, kDetailsThumbnailSize);
    m_details = new QTextBrowser(pane);
    m_details->setObjectName(QStringLiteral("detailsText"));
    layout->addWidget(m_thumbnail);
    layout->addWidget(m_details, 1);
    return pane;
}

void StudyBrowser::connectSignals() {
    connect(m_searchEdit, &QLineEdit::textChanged, this, &StudyBrowser::reload);
    connect(m_fromEdit, &QDateEdit::dateChanged, this, &StudyBrowser::reload);
    connect(m_toEdit, &QDateEdit::dateChanged, this, &StudyBrowser::reload);
    connect(m_importFolderButton, &QPushButton::clicked, this, &StudyBrowser::chooseFolderToImport);
    connect(m_importDicomdirButton, &QPushButton::clicked, this,
            &StudyBrowser::chooseDicomdirToImport);
    connect(m_removeButton, &QPushButton::clicked, this, &StudyBrowser::removeSelectedSeries);
    connect(m_cancelButton, &QPushButton::clicked, this, &StudyBrowser::cancelImport);
    connect(m_tree, &QTreeView::activated, this, &StudyBrowser::onActivated);
    connect(m_remote, &RemotePanel::retrieved, this, &StudyBrowser::onRetrieved);
    connect(m_tree->selectionModel(), &QItemSelectionModel::selectionChanged, this,
            &StudyBrowser::showDetails);
    connect(m_worker, &ImportWorker::progress, this, &StudyBrowser::onImportProgress);
    connect(m_worker, &ImportWorker::finished, this, &StudyBrowser::onImportFinished);
    connect(m_worker, &ImportWorker::failed, this, &StudyBrowser::onImportFailed);
    auto* remove = new QShortcut(QKeySequence::Delete, m_tree);
    remove->setContext(Qt::WidgetWithChildrenShortcut);
    connect(remove, &QShortcut::activated, this, &StudyBrowser::removeSelectedSeries);
}

studydb::StudyFilter StudyBrowser::currentFilter() const {
    studydb::StudyFilter filter;
    filter.text = m_searchEdit->text();
    if (m_fromEdit->date() != kAnyDate)
        filter.from = m_fromEdit->date();
    if (m_toEdit->date() != kAnyDate)
        filter.to = m_toEdit->date();
    return filter;
}

void StudyBrowser::reload() {
    if (!m_database)
        return;
    const QStringList selected = selectedSeriesUids();
    try {
        m_model->reload(*m_database, currentFilter());
    } catch (const core::Error& error) {
        showMessage(tr("The study database cannot be read: %1").arg(errorText(error)), true);
        return;
    }
    m_tree->expandAll();
    for (const QString& uid : selected) {
        const QModelIndex index = m_model->indexOfSeries(uid);
        if (index.isValid())
            m_tree->selectionModel()->select(index, QItemSelectionModel::Select |
                                                        QItemSelectionModel::Rows);
    }
    showDetails();
}

QStringList StudyBrowser::selectedSeriesUids() const {
    QStringList result;
    for (const QModelIndex& index : m_tree->selectionModel()->selectedRows())
        for (const QString& uid : m_model->seriesUidsUnder(index))
            if (!result.contains(uid))
                result.append(uid);
    return result;
}

bool StudyBrowser::selectSeries(const QString& seriesUid) {
    const QModelIndex index = m_model->indexOfSeries(seriesUid);
    if (!index.isValid())
        return false;
    m_tree->selectionModel()->setCurrentIndex(index, QItemSelectionModel::ClearAndSelect |
                                                         QItemSelectionModel::Rows);
    m_tree->scrollTo(index);
    return true;
}

bool StudyBrowser::isImporting() const {
    return m_worker->isRunning() || !m_pendingImports.isEmpty();
}

QString StudyBrowser::messageText() const {
    return m_messageLabel->isHidden() ? QString() : m_messageLabel->text();
}

void StudyBrowser::showMessage(const QString& text, bool isError) {
    m_messageLabel->setText(text);
    m_messageLabel->setStyleSheet(
        isError ? QStringLiteral("QLabel { background: #f8d7da; color: #58151c; padding: 4px; }")
                : QStringLiteral("QLabel { background: #fff3cd; color: #664d03; padding: 4px; }"));
    m_messageLabel->show();
}

void StudyBrowser::clearMessage() {
    m_messageLabel->clear();
    m_messageLabel->hide();
}

// ---- import ---------------------------------------------------------------------------------

void StudyBrowser::importPath(const QString& path) {
    if (!m_database) {
        showMessage(
            tr("Cannot import %1: the study database is not open (%2)").arg(path, m_databaseError),
            true);
        return;
    }
    m_pendingImports.append(path);
    if (!m_worker->isRunning())
        startNextImport();
    else
        emit statusMessage(tr("%1 will be imported after the current import").arg(path));
}

void StudyBrowser::startNextImport() {
    if (m_pendingImports.isEmpty())
        return;
    m_currentImport = m_pendingImports.takeFirst();
    clearMessage();
    m_importLabel->setText(tr("Importing %1").arg(QFileInfo(m_currentImport).fileName()));
    m_progress->setValue(0);
    m_cancelButton->setEnabled(true);
    m_importPanel->show();
    m_worker->start(m_currentImport);
    emit importStarted();
    emit statusMessage(tr("Importing %1…").arg(m_currentImport));
}

void StudyBrowser::chooseFolderToImport() {
    const QString folder = QFileDialog::getExistingDirectory(this, tr("Import a DICOM folder"));
    if (!folder.isEmpty())
        importPath(folder);
}

void StudyBrowser::chooseDicomdirToImport() {
    const QString file =
        QFileDialog::getOpenFileName(this, tr("Import a DICOMDIR"), QString(),
                                     tr("DICOMDIR (DICOMDIR dicomdir);;All files (*)"));
    if (!file.isEmpty())
        importPath(file);
}

void StudyBrowser::cancelImport() {
    // Queued paths are dropped too: Cancel means "stop importing".
    m_pendingImports.clear();
    m_worker->cancel();
    m_cancelButton->setEnabled(false);
    m_importLabel->setText(tr("Cancelling…"));
}

void StudyBrowser::onImportProgress(double fraction, const QString& message) {
    m_progress->setValue(int(fraction * 1000.0));
    m_progress->setFormat(message + QStringLiteral("  %p%"));
}

void StudyBrowser::onImportFinished(const studydb::ImportSummary& summary) {
    m_importPanel->hide();
    reload();
    QString text;
    if (summary.cancelled)
        text = tr("Import of %1 cancelled; the database is unchanged").arg(m_currentImport);
    else
        text = tr("Imported %1: %2 new, %3 updated series from %4 files")
                   .arg(m_currentImport)
                   .arg(summary.seriesAdded)
                   .arg(summary.seriesUpdated)
                   .arg(summary.filesExamined);
    if (!summary.cancelled && !summary.errors.isEmpty()) {
        QStringList lines;
        for (const studydb::ImportProblem& problem : summary.errors.mid(0, 5))
            lines.append(QStringLiteral("%1: %2").arg(problem.file, problem.reason));
        if (summary.errors.size() > 5)
            lines.append(tr("… and %1 more").arg(summary.errors.size() - 5));
        showMessage(tr("%1. %2 file(s) could not be used:\n%3")
                        .arg(text)
                        .arg(summary.errors.size())
                        .arg(lines.join(QLatin1Char('\n'))),
                    false);
    } else if (!summary.cancelled && summary.seriesAdded + summary.seriesUpdated == 0) {
        showMessage(tr("%1: no DICOM series found").arg(m_currentImport), false);
    }
    emit statusMessage(text);
    emit importFinished(summary);
    startNextImport();
}

void StudyBrowser::onImportFailed(const QString& message) {
    m_importPanel->hide();
    showMessage(tr("Import of %1 failed: %2").arg(m_currentImport, message), true);
    emit statusMessage(tr("Import failed: %1").arg(message));
    studydb::ImportSummary summary;
    summary.errors.append({m_currentImport, message});
    emit importFinished(summary);
    startNextImport();
}

// ---- drag and drop -------------------------------------------------------------------------

void StudyBrowser::dragEnterEvent(QDragEnterEvent* event) {
    if (!m_database || !event->mimeData()->hasUrls())
        return;
    for (const QUrl& url : event->mimeData()->urls())
        if (url.isLocalFile()) {
            event->acceptProposedAction();
            return;
        }
}

void StudyBrowser::dropEvent(QDropEvent* event) {
    for (const QUrl& url : event->mimeData()->urls())
        if (url.isLocalFile())
            importPath(url.toLocalFile());
    event->acceptProposedAction();
}

// ---- remove, open, details -----------------------------------------------------------------

void StudyBrowser::removeSelectedSeries() {
    const QStringList uids = selectedSeriesUids();
    if (uids.isEmpty() || !m_database)
        return;
    const auto answer =
        QMessageBox::question(this, tr("Remove from database"),
                              tr("Remove %n series from the study database?\n\nThe files on disk "
                                 "are kept; you can import them again.",
                                 nullptr, int(uids.size())),
                              QMessageBox::Yes | QMessageBox::Cancel, QMessageBox::Cancel);
    if (answer == QMessageBox::Yes)
        removeSeries(uids);
}

void StudyBrowser::removeSeries(const QStringList& seriesUids) {
    if (!m_database)
        return;
    int removed = 0;
    try {
        for (const QString& uid : seriesUids)
            removed += m_database->removeSeries(uid) ? 1 : 0;
    } catch (const core::Error& error) {
        showMessage(tr("Cannot remove the series: %1").arg(errorText(error)), true);
    }
    m_tree->selectionModel()->clearSelection();
    reload();
    emit statusMessage(
        tr("Removed %n series from the database (files on disk kept)", nullptr, removed));
}

void StudyBrowser::onRetrieved(const QString& seriesUid, bool open) {
    reload();
    if (seriesUid.isEmpty())
        return;
    selectSeries(seriesUid);
    if (open)
        emit openSeriesRequested(seriesUid); // as a double-click on the local series
}

void StudyBrowser::onActivated(const QModelIndex& index) {
    const studydb::SeriesRecord* series = m_model->seriesAt(index);
    if (!series || !m_database)
        return;
    const QString uid = series->uid;
    QStringList files;
    try {
        files = m_database->seriesFiles(uid);
    } catch (const core::Error& error) {
        return showMessage(errorText(error), true);
    }
    // Files referenced in place may have moved since the import: say so instead of opening.
    int missing = 0;
    for (const QString& file : files)
        missing += QFileInfo::exists(file) ? 0 : 1;
    if (files.isEmpty() || missing == files.size()) {
        showMessage(
            tr("The files of series \"%1\" are missing (%2): import its folder again or remove it")
                .arg(series->description,
                     files.isEmpty() ? tr("none referenced") : QFileInfo(files[0]).absolutePath()),
            true);
        return;
    }
    if (missing > 0)
        showMessage(tr("%1 of %2 files of series \"%3\" are missing")
                        .arg(missing)
                        .arg(files.size())
                        .arg(series->description),
                    false);
    emit openSeriesRequested(uid);
}

void StudyBrowser::showDetails() {
    const QStringList uids = selectedSeriesUids();
    m_removeButton->setEnabled(!uids.isEmpty());
    const studydb::SeriesRecord* series =
        m_model->seriesAt(m_tree->selectionModel()->currentIndex());
    if (!series || !m_tree->selectionModel()->isRowSelected(
                       m_tree->selectionModel()->currentIndex().row(),
                       m_tree->selectionModel()->currentIndex().parent())) {
        m_thumbnail->clear();
        m_details->setHtml(uids.isEmpty() ? QString()
                                          : tr("%n series selected", nullptr, int(uids.size())));
        return;
    }
    const QImage image = series->thumbnail();
    if (image.isNull())
        m_thumbnail->setText(tr("no thumbnail"));
    else
        m_thumbnail->setPixmap(
            QPixmap::fromImage(image.scaled(kDetailsThumbnailSize, kDetailsThumbnailSize,
                                            Qt::KeepAspectRatio, Qt::SmoothTransformation)));
    m_details->setHtml(detailsHtml(*series));
}

QString StudyBrowser::detailsHtml(const studydb::SeriesRecord& s) {
    const auto row = [](const QString& name, const QString& value) {
        return QStringLiteral("<tr><td><b>%1</b></td><td>%2</td></tr>")
            .arg(name, value.toHtmlEscaped());
    };
    QString html = QStringLiteral("<table>");
    html += row(tr("Description"), s.description);
    html += row(tr("Modality"), s.modality);
    html += row(tr("Series number"), s.number ? QString::number(*s.number) : QString());
    html += row(tr("Study date"), studydb::parseDicomDate(s.studyDate).toString(Qt::ISODate));
    html += row(tr("Slices"), QString::number(s.sliceCount));
    html += row(tr("Files"), QString::number(s.fileCount));
    html += row(tr("Dimensions"),
                QStringLiteral("%1 × %2 × %3").arg(s.dims[0]).arg(s.dims[1]).arg(s.dims[2]));
    html += row(
        tr("Spacing"),
        QStringLiteral("%1 × %2 × %3 mm").arg(s.spacing[0]).arg(s.spacing[1]).arg(s.spacing[2]));
    html += row(tr("Gantry tilt"), QStringLiteral("%1°").arg(s.tiltDegrees, 0, 'f', 2));
    html +=
        row(tr("Slice gaps"), s.unevenGaps ? tr("uneven, %1 to %2 mm").arg(s.minGap).arg(s.maxGap)
                                           : tr("even (%1 mm)").arg(s.minGap));
    html += row(tr("Missing slices"), QString::number(s.missingSlices));
    html += row(tr("Volumes"), QString::number(s.volumeCount));
    html += row(tr("Imported from"), s.sourceRoot);
    html += row(tr("Imported at"), s.importedAt.toLocalTime().toString(Qt::ISODate));
    html += row(tr("Series UID"), s.uid);
    html += QStringLiteral("</table>");
    const QStringList warnings = s.warnings();
    if (!warnings.isEmpty()) {
        html += QStringLiteral("<h4>%1</h4><ul>").arg(tr("Warnings"));
        for (const QString& warning : warnings)
            html += QStringLiteral("<li>%1</li>").arg(warning.toHtmlEscaped());
        html += QStringLiteral("</ul>");
    }
    const QList<studydb::SeriesMessage> errors = s.fileErrors();
    if (!errors.isEmpty()) {
        html += QStringLiteral("<h4>%1</h4><ul>").arg(tr("Files that could not be used"));
        for (const studydb::SeriesMessage& error : errors)
            html += QStringLiteral("<li>%1: %2</li>")
                        .arg(error.file.toHtmlEscaped(), error.text.toHtmlEscaped());
        html += QStringLiteral("</ul>");
    }
    return html;
}

} // namespace lw::gui
