#pragma once

// The DICOM browser: search and date filter, the patient -> study -> series tree, a details pane,
// import (buttons, drag and drop) with a progress bar and Cancel, and removal from the database.
// The database (lw::studydb), the tree model (StudyTreeModel) and the background import
// (ImportWorker) are separate classes; this widget only wires them to the user.

#include "lw/studydb/study_database.h"
#include "lw/studydb/study_records.h"

#include <QStringList>
#include <QWidget>
#include <memory>

class QDateEdit;
class QLabel;
class QLineEdit;
class QProgressBar;
class QPushButton;
class QTextBrowser;
class QTreeView;

namespace lw::gui {

class ImportWorker;
class RemotePanel;
class StudyTreeModel;

class StudyBrowser : public QWidget {
    Q_OBJECT

public:
    // Opens (or creates) the database at `databasePath`. A database that cannot be opened is
    // shown in the widget's message bar; the browser then stays empty and database() throws.
    explicit StudyBrowser(QString databasePath, QWidget* parent = nullptr);
    ~StudyBrowser() override;

    // The UI thread's connection. Throws core::Error (with the reason it could not be opened)
    // when there is none.
    studydb::StudyDatabase& database();
    bool hasDatabase() const { return m_database != nullptr; }
    const QString& databasePath() const { return m_databasePath; }

    StudyTreeModel& model() { return *m_model; }
    // The PACS query bar and its results (pacs/remote_panel.h).
    RemotePanel& remote() { return *m_remote; }
    bool isImporting() const;
    // The text in the message bar (errors and import results); empty when hidden.
    QString messageText() const;
    // Series UIDs of the selected rows (a patient or study row selects all series under it).
    QStringList selectedSeriesUids() const;
    // Selects the row of a series (and scrolls to it); false when it is not shown.
    bool selectSeries(const QString& seriesUid);

public slots:
    // Imports a folder, DICOMDIR or file in the background. While an import runs, further paths
    // are queued and imported one after the other.
    void importPath(const QString& path);
    void chooseFolderToImport();
    void chooseDicomdirToImport();
    // Asks for confirmation (the files on disk are kept), then removes the selected series.
    void removeSelectedSeries();
    // Removes without asking (tests, scripted use).
    void removeSeries(const QStringList& seriesUids);
    void cancelImport();
    // Re-reads the tree with the current filter, keeping the selection.
    void reload();

signals:
    void importStarted();
    void importFinished(const lw::studydb::ImportSummary& summary);
    void openSeriesRequested(const QString& seriesUid);
    void statusMessage(const QString& message);

protected:
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;

private:
    void buildUi();
    QWidget* buildToolbar();
    QWidget* buildImportPanel();
    QWidget* buildDetailsPane();
    void connectSignals();
    void openDatabase();
    void startNextImport();
    void onImportProgress(double fraction, const QString& message);
    void onImportFinished(const studydb::ImportSummary& summary);
    void onImportFailed(const QString& message);
    void onActivated(const QModelIndex& index);
    void onRetrieved(const QString& seriesUid, bool open);
    void showDetails();
    static QString detailsHtml(const studydb::SeriesRecord& series);
    void showMessage(const QString& text, bool isError);
    void clearMessage();
    studydb::StudyFilter currentFilter() const;

    QString m_databasePath;
    std::unique_ptr<studydb::StudyDatabase> m_database;
    QString m_databaseError;
    StudyTreeModel* m_model = nullptr;
    ImportWorker* m_worker = nullptr;
    QStringList m_pendingImports;
    QString m_currentImport;

    QLineEdit* m_searchEdit = nullptr;
    QDateEdit* m_fromEdit = nullptr;
    QDateEdit* m_toEdit = nullptr;
    QPushButton* m_importFolderButton = nullptr;
    QPushButton* m_importDicomdirButton = nullptr;
    QPushButton* m_removeButton = nullptr;
    QLabel* m_messageLabel = nullptr;
    QWidget* m_importPanel = nullptr;
    QLabel* m_importLabel = nullptr;
    QProgressBar* m_progress = nullptr;
    QPushButton* m_cancelButton = nullptr;
    QTreeView* m_tree = nullptr;
    RemotePanel* m_remote = nullptr;
    QLabel* m_thumbnail = nullptr;
    QTextBrowser* m_details = nullptr;
};

} // namespace lw::gui
