#pragma once

// The study browser's remote part: a query bar (node, patient name, patient ID, date range,
// modality, Search, Cancel) and the PACS's answer in a tree of its own (RemoteStudyModel),
// marked remote. Study-level C-FIND runs on a pool thread with a cancel token; expanding a
// study asks for its series; double-clicking a series (or "Retrieve" in the context menu of a
// study or series) retrieves it with a progress dialog (n of N, Cancel) through RetrieveJob,
// which registers what arrived in the study database. The nodes come from the node file beside
// the database (Settings → PACS edits it).

#include "lw/core/progress.h"
#include "lw/pacs/pacs_client.h"
#include "pacs/pacs_locations.h"

#include <QFuture>
#include <QList>
#include <QWidget>
#include <memory>

class QComboBox;
class QLabel;
class QLineEdit;
class QProgressDialog;
class QPushButton;
class QTreeView;

namespace lw::gui {

class RemoteStudyModel;
class RetrieveJob;
struct RetrieveOutcome;

class RemotePanel : public QWidget {
    Q_OBJECT
public:
    RemotePanel(QString databasePath, QWidget* parent = nullptr);
    // Cancels the queries and the retrieve and waits for them.
    ~RemotePanel() override;

    RemoteStudyModel& model() { return *m_model; }
    QTreeView& tree() { return *m_tree; }
    RetrieveJob& retrieveJob() { return *m_retrieve; }
    // The message line (query results, errors in words); empty when none.
    QString statusText() const;
    bool isQuerying() const;

public slots:
    // Re-reads the node file (after Settings saved it); keeps the chosen node when it is there.
    void reloadNodes();
    // C-FIND at study level with the query bar's fields on the chosen node.
    void search();
    void cancelQuery();
    // C-FIND at series level for a study row (once per study and query).
    void listSeries(const QModelIndex& studyIndex);
    // Retrieves the study or series of a row; a series is opened once it is here.
    void retrieve(const QModelIndex& index);

signals:
    void queryFinished(int studies);
    void seriesListed(const QString& studyUid, int series);
    void queryFailed(const QString& message);
    // What arrived is registered in the database (also after a cancel): the browser reloads;
    // `open` when the retrieved series should be opened in the review.
    void retrieved(const QString& seriesUid, bool open);

private:
    QWidget* buildQueryBar();
    void buildTree();
    void showContextMenu(const QPoint& at);
    void onActivated(const QModelIndex& index);
    void onRetrieveFinished(const RetrieveOutcome& outcome);
    void onRetrieveFailed(const QString& message);
    void showProgress(int done, int toTransfer);
    void showStatus(const QString& text, bool isError);
    void setQuerying(bool querying);
    // The chosen node, or nullptr (with a message) when there is none.
    const pacs::PacsNode* chosenNode();
    pacs::CallOptions callOptions() const;
    void keep(QFuture<void> query);

    QString m_databasePath;
    PacsLocations m_locations;
    pacs::PacsNodeFile m_nodeFile;
    RemoteStudyModel* m_model = nullptr;
    RetrieveJob* m_retrieve = nullptr;
    bool m_openAfterRetrieve = false;
    std::shared_ptr<core::CancelToken> m_queryCancel;
    bool m_querying = false;
    QList<QFuture<void>> m_queries; // waited for by the destructor; finished ones dropped

    QComboBox* m_node = nullptr;
    QLineEdit* m_patientName = nullptr;
    QLineEdit* m_patientId = nullptr;
    QLineEdit* m_dates = nullptr;
    QComboBox* m_modality = nullptr;
    QPushButton* m_search = nullptr;
    QPushButton* m_cancel = nullptr;
    QLabel* m_status = nullptr;
    QTreeView* m_tree = nullptr;
    QProgressDialog* m_progress = nullptr;
};

} // namespace lw::gui
