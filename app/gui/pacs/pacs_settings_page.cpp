#include "pacs/pacs_settings_page.h"

#include "browser/background_task.h"
#include "lw/core/error.h"
#include "lw/pacs/pacs_client.h"

#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>

namespace lw::gui {

namespace {

constexpr int kMaxPort = 65535;

QString cellText(const QTableWidget& table, int row, int column) {
    const QTableWidgetItem* item = table.item(row, column);
    return item ? item->text().trimmed() : QString();
}

} // namespace

PacsSettingsPage::PacsSettingsPage(QString nodeFile, QWidget* parent)
    : QWidget(parent), m_nodeFile(std::move(nodeFile)) {
    setObjectName(QStringLiteral("pacsSettingsPage"));
    buildUi();
    try {
        showFile(pacs::readNodeFileOrDefaults(m_nodeFile.toStdString()));
    } catch (const core::Error& error) {
        showFile({});
        m_error->setText(gui::errorText(error));
    }
    connect(m_aet, &QLineEdit::textEdited, this, &PacsSettingsPage::save);
    connect(m_storagePort, &QSpinBox::valueChanged, this, &PacsSettingsPage::save);
    connect(m_nodes, &QTableWidget::itemChanged, this, &PacsSettingsPage::save);
}

PacsSettingsPage::~PacsSettingsPage() {
    // The echo reports to this page: it ends (within the call's timeout) before the page goes.
    m_echo.waitForFinished();
}

void PacsSettingsPage::buildUi() {
    m_aet = new QLineEdit(this);
    m_aet->setObjectName(QStringLiteral("workstationAet"));
    m_aet->setMaxLength(16);
    m_storagePort = new QSpinBox(this);
    m_storagePort->setObjectName(QStringLiteral("storagePort"));
    m_storagePort->setRange(1, kMaxPort);
    m_storagePort->setToolTip(tr("Where the workstation receives a C-MOVE's images; the PACS "
                                 "must list this AE title with this host and port"));
    auto* identity = new QFormLayout;
    identity->addRow(tr("Workstation AE title:"), m_aet);
    identity->addRow(tr("Storage port (C-MOVE):"), m_storagePort);

    m_nodes = new QTableWidget(0, NodeColumnCount, this);
    m_nodes->setObjectName(QStringLiteral("pacsNodes"));
    m_nodes->setHorizontalHeaderLabels(
        {tr("Name"), tr("Called AE title"), tr("Host"), tr("Port"), tr("Retrieve by")});
    m_nodes->horizontalHeader()->setSectionResizeMode(QHeaderView::Stretch);
    m_nodes->setSelectionBehavior(QAbstractItemView::SelectRows);
    m_nodes->setSelectionMode(QAbstractItemView::SingleSelection);

    m_error = new QLabel(this);
    m_error->setObjectName(QStringLiteral("pacsNodeError"));
    m_error->setWordWrap(true);
    m_error->setStyleSheet(QStringLiteral("color: #b00020"));
    m_testResult = new QLabel(this);
    m_testResult->setObjectName(QStringLiteral("pacsTestResult"));
    m_testResult->setWordWrap(true);
    m_testResult->setTextInteractionFlags(Qt::TextSelectableByMouse);

    auto* layout = new QVBoxLayout(this);
    layout->addLayout(identity);
    layout->addWidget(new QLabel(tr("PACS nodes:"), this));
    layout->addWidget(m_nodes, 1);
    layout->addWidget(buildNodeButtons());
    layout->addWidget(m_testResult);
    layout->addWidget(m_error);
    auto* where = new QLabel(tr("Saved in %1").arg(m_nodeFile), this);
    where->setTextInteractionFlags(Qt::TextSelectableByMouse);
    where->setWordWrap(true);
    layout->addWidget(where);
}

QWidget* PacsSettingsPage::buildNodeButtons() {
    auto* row = new QWidget(this);
    auto* layout = new QHBoxLayout(row);
    layout->setContentsMargins(0, 0, 0, 0);
    auto* add = new QPushButton(tr("Add"), row);
    add->setObjectName(QStringLiteral("addPacsNode"));
    auto* remove = new QPushButton(tr("Remove"), row);
    remove->setObjectName(QStringLiteral("removePacsNode"));
    m_test = new QPushButton(tr("Test"), row);
    m_test->setObjectName(QStringLiteral("testPacsNode"));
    m_test->setToolTip(tr("Sends a C-ECHO to the selected node"));
    connect(add, &QPushButton::clicked, this, &PacsSettingsPage::addNode);
    connect(remove, &QPushButton::clicked, this, &PacsSettingsPage::removeSelectedNode);
    connect(m_test, &QPushButton::clicked, this, &PacsSettingsPage::testSelectedNode);
    layout->addWidget(add);
    layout->addWidget(remove);
    layout->addStretch(1);
    layout->addWidget(m_test);
    return row;
}

void PacsSettingsPage::showFile(const pacs::PacsNodeFile& file) {
    m_updating = true;
    m_aet->setText(QString::fromStdString(file.workstation.aet));
    m_storagePort->setValue(file.workstation.storagePort);
    m_nodes->setRowCount(int(file.nodes.size()));
    for (int row = 0; row < int(file.nodes.size()); ++row)
        setNodeRow(row, file.nodes[std::size_t(row)]);
    m_updating = false;
}

void PacsSettingsPage::setNodeRow(int row, const pacs::PacsNode& node) {
    m_nodes->setItem(row, NameColumn, new QTableWidgetItem(QString::fromStdString(node.name)));
    m_nodes->setItem(row, CalledAetColumn,
                     new QTableWidgetItem(QString::fromStdString(node.calledAet)));
    m_nodes->setItem(row, HostColumn, new QTableWidgetItem(QString::fromStdString(node.host)));
    m_nodes->setItem(row, PortColumn, new QTableWidgetItem(QString::number(node.port)));
    // C-GET or C-MOVE: a choice, not text, so that the file never holds anything else.
    auto* method = new QComboBox(m_nodes);
    method->setObjectName(QStringLiteral("retrieveMethod"));
    method->addItem(tr("C-GET"), int(pacs::RetrieveMethod::Get));
    method->addItem(tr("C-MOVE"), int(pacs::RetrieveMethod::Move));
    method->setToolTip(tr("C-MOVE sends the images to the storage port above: the PACS must "
                          "list this workstation's AE title with its host and that port"));
    method->setCurrentIndex(method->findData(int(node.retrieve)));
    connect(method, &QComboBox::currentIndexChanged, this, &PacsSettingsPage::save);
    m_nodes->setCellWidget(row, RetrieveColumn, method);
}

pacs::PacsNodeFile PacsSettingsPage::editedFile() const {
    pacs::PacsNodeFile file;
    file.workstation.aet = m_aet->text().trimmed().toStdString();
    file.workstation.storagePort = std::uint16_t(m_storagePort->value());
    for (int row = 0; row < m_nodes->rowCount(); ++row) {
        pacs::PacsNode node;
        node.name = cellText(*m_nodes, row, NameColumn).toStdString();
        node.calledAet = cellText(*m_nodes, row, CalledAetColumn).toStdString();
        node.host = cellText(*m_nodes, row, HostColumn).toStdString();
        // Not a number, or out of range: 0, which the module's validation names as not a port.
        const uint port = cellText(*m_nodes, row, PortColumn).toUInt();
        node.port = port <= kMaxPort ? std::uint16_t(port) : 0;
        if (const auto* method = qobject_cast<QComboBox*>(m_nodes->cellWidget(row, RetrieveColumn)))
            node.retrieve = pacs::RetrieveMethod(method->currentData().toInt());
        file.nodes.push_back(node);
    }
    return file;
}

QString PacsSettingsPage::errorText() const {
    return m_error->text();
}

void PacsSettingsPage::save() {
    if (m_updating)
        return;
    try {
        pacs::writeNodeFile(m_nodeFile.toStdString(), editedFile());
        m_error->clear();
        emit saved();
    } catch (const core::Error& error) {
        m_error->setText(tr("Not saved: %1").arg(gui::errorText(error)));
    }
}

void PacsSettingsPage::addNode() {
    const int row = m_nodes->rowCount();
    m_updating = true;
    m_nodes->insertRow(row);
    setNodeRow(row, {tr("node %1").arg(row + 1).toStdString(), "", "", 104});
    m_updating = false;
    m_nodes->selectRow(row);
    save(); // an empty called AE title: the message says what to fill in
}

void PacsSettingsPage::removeSelectedNode() {
    const int row = m_nodes->currentRow();
    if (row < 0)
        return;
    m_nodes->removeRow(row);
    save();
}

void PacsSettingsPage::testSelectedNode() {
    const int row = m_nodes->currentRow();
    if (row < 0 || m_echo.isRunning())
        return showTestResult(false, row < 0 ? tr("Select a node to test") : tr("A test runs"));
    const pacs::PacsNode node = editedFile().nodes.at(std::size_t(row));
    const pacs::CallOptions options{m_aet->text().trimmed().toStdString(),
                                    pacs::CallOptions{}.timeout};
    m_test->setEnabled(false);
    m_testResult->setText(tr("Testing %1…").arg(QString::fromStdString(node.name)));
    m_echo = runInBackground(
        this, [node, options] { return pacs::echo(node, options); },
        [this](const pacs::EchoResult& result) {
            showTestResult(result.ok, QString::fromStdString(result.message));
        },
        [] {}, [this](const QString& message) { showTestResult(false, message); });
}

void PacsSettingsPage::showTestResult(bool ok, const QString& message) {
    m_test->setEnabled(true);
    m_testResult->setText(ok ? tr("Test: %1").arg(message) : tr("Test failed: %1").arg(message));
    m_testResult->setStyleSheet(ok ? QStringLiteral("color: #1b7f2a")
                                   : QStringLiteral("color: #b00020"));
    emit testFinished(ok, message);
}

} // namespace lw::gui
