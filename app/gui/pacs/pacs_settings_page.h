#pragma once

// Settings → "PACS": edits the node file (lw::pacs::readNodeFile / writeNodeFile) that the
// workstation and `linework-cli pacs` share: the workstation's AE title and storage port, and
// the table of nodes (name, called AE title, host, port). Like the rest of the settings dialog,
// every change is applied at once: a valid file is written (atomically, by the module), an
// invalid one is not, and the module's message says what is wrong. "Test" sends a C-ECHO to
// the selected node off the UI thread and says what happened in words.

#include "lw/pacs/pacs_node.h"

#include <QFuture>
#include <QString>
#include <QWidget>

class QLabel;
class QLineEdit;
class QPushButton;
class QSpinBox;
class QTableWidget;

namespace lw::gui {

class PacsSettingsPage : public QWidget {
    Q_OBJECT
public:
    enum NodeColumn {
        NameColumn,
        CalledAetColumn,
        HostColumn,
        PortColumn,
        RetrieveColumn,
        NodeColumnCount
    };

    // Reads `nodeFile` (missing: no nodes, the AE title LINEWORK); a file that does not read is
    // shown as an error and the page starts empty (nothing is written until the user edits).
    explicit PacsSettingsPage(QString nodeFile, QWidget* parent = nullptr);
    ~PacsSettingsPage() override;

    const QString& nodeFile() const { return m_nodeFile; }
    // What the controls hold now (written to the file when valid).
    pacs::PacsNodeFile editedFile() const;
    // The problem the last edit has (the module's words), or empty when the file was written.
    QString errorText() const;

public slots:
    void addNode();
    void removeSelectedNode();
    // C-ECHO to the selected row's node, calling with the page's AE title.
    void testSelectedNode();

signals:
    // A valid node file was written.
    void saved();
    // The outcome of "Test", in words ("accepted", "connection refused: ...").
    void testFinished(bool ok, const QString& message);

private:
    void buildUi();
    QWidget* buildNodeButtons();
    void showFile(const pacs::PacsNodeFile& file);
    void setNodeRow(int row, const pacs::PacsNode& node);
    void save();
    void showTestResult(bool ok, const QString& message);

    QString m_nodeFile;
    bool m_updating = false;
    QLineEdit* m_aet = nullptr;
    QSpinBox* m_storagePort = nullptr;
    QTableWidget* m_nodes = nullptr;
    QPushButton* m_test = nullptr;
    QLabel* m_error = nullptr;
    QLabel* m_testResult = nullptr;
    QFuture<void> m_echo;
};

} // namespace lw::gui
