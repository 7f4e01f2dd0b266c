// The PACS in the workstation, against a real Orthanc that the test starts on free loopback ports
// (tests/pacs/orthanc_server.h): Settings → PACS round-trips the node file, names what is
// invalid and its Test button says "accepted" or "refused"; the study browser's query lists the
// Orthanc's study marked remote, with its series; a double-click on a remote series retrieves
// it (n of N), registers it and opens the review; a cancelled retrieve keeps what arrived
// registered and the next one fetches only the rest; a PACS that is down or does not answer is
// named with the reason. SKIPs without Orthanc or a display.
#include "browser/study_tree_model.h"
#include "gui_test_support.h"
#include "lw/pacs/pacs_node.h"
#include "orthanc_server.h"
#include "pacs/pacs_locations.h"
#include "pacs/pacs_settings_page.h"
#include "pacs/remote_panel.h"
#include "pacs/remote_study_model.h"
#include "pacs/retrieve_job.h"
#include "shell/main_window.h"
#include "window_test_support.h"

#include <QComboBox>
#include <QLabel>
#include <QLineEdit>
#include <QMessageBox>
#include <QProgressDialog>
#include <QPushButton>
#include <QSignalSpy>
#include <QTableWidget>
#include <QTreeView>
#include <QtTest>
#include <arpa/inet.h>
#include <memory>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

using namespace lw::gui;
namespace pacs = lw::pacs;
namespace fs = std::filesystem;

namespace {

constexpr int kNetworkWaitMs = 30000;
constexpr int kOpenSeriesSlices = 6;
constexpr int kCancelSeriesSlices = 12;

// Where the user guide's screenshots go when LINEWORK_SCREENSHOT_DIR is set (docs/screenshots).
void saveScreenshot(QWidget& widget, const QString& name) {
    const QString folder = qEnvironmentVariable("LINEWORK_SCREENSHOT_DIR");
    if (!folder.isEmpty())
        QVERIFY(widget.grab().save(folder + "/" + name));
}

// The workstation as the test Orthanc lists it (AE title, C-MOVE's storage port), and `node`.
pacs::PacsNodeFile nodeFileFor(const pacs::PacsNode& node, std::uint16_t storagePort) {
    pacs::PacsNodeFile file;
    file.workstation.aet = pacs::test::kWorkstationAet;
    file.workstation.storagePort = storagePort;
    file.nodes.push_back(node);
    return file;
}

void setCell(QTableWidget& table, int row, int column, const QString& text) {
    table.item(row, column)->setText(text); // itemChanged: the page saves
}

// Double-clicks `index` of `tree` with the mouse events a user's double-click sends its viewport
// (press, release, double-click, release).
void doubleClick(QTreeView& tree, const QModelIndex& index) {
    tree.scrollTo(index);
    const QPointF at = tree.visualRect(index).center();
    const QPointF global = tree.viewport()->mapToGlobal(at);
    for (const QEvent::Type type : {QEvent::MouseButtonPress, QEvent::MouseButtonRelease,
                                    QEvent::MouseButtonDblClick, QEvent::MouseButtonRelease}) {
        const bool down = type != QEvent::MouseButtonRelease;
        QMouseEvent event(type, at, global, Qt::LeftButton, down ? Qt::LeftButton : Qt::NoButton,
                          Qt::NoModifier);
        QApplication::sendEvent(tree.viewport(), &event);
    }
}

} // namespace

class PacsGuiTest : public QObject {
    Q_OBJECT
private slots:
    void initTestCase();
    void cleanupTestCase();
    void settingsPageRoundTripsTheNodeFile_data();
    void settingsPageRoundTripsTheNodeFile();
    void settingsPageNamesWhatIsInvalid_data();
    void settingsPageNamesWhatIsInvalid();
    void settingsInTheMainWindowFeedTheQueryBar();
    void testButtonSaysWhatHappened_data();
    void testButtonSaysWhatHappened();
    void queryListsTheRemoteStudy_data();
    void queryListsTheRemoteStudy();
    void queryOfAPacsThatDoesNotAnswerTimesOut();
    void doubleClickRetrievesAndOpens_data();
    void doubleClickRetrievesAndOpens();
    void cancelledRetrieveKeepsWhatArrived();
    void retrieveFromAPacsThatIsDownSaysSo();

private:
    // A browser on a fresh database in `dir`, with the Orthanc as its only node.
    std::unique_ptr<StudyBrowser> makeBrowser(const QTemporaryDir& dir);
    // Searches with the query bar's current fields; the number of studies found.
    static int search(RemotePanel& remote);
    // Expands the (only) remote study and waits for its series.
    static QModelIndex seriesRow(RemotePanel& remote, const std::string& seriesUid);

    std::unique_ptr<lw::test::TempDir> m_files;
    std::unique_ptr<pacs::test::OrthancServer> m_orthanc;
    pacs::test::SyntheticSeries m_openSeries, m_cancelSeries;
    std::uint16_t m_storagePort = 0; // the workstation's C-MOVE port, as Orthanc lists it
};

void PacsGuiTest::initTestCase() {
    m_files = std::make_unique<lw::test::TempDir>();
    m_openSeries = pacs::test::writeCtSeries(*m_files / "open", kOpenSeriesSlices, 32);
    m_cancelSeries = pacs::test::writeCtSeries(*m_files / "cancel", kCancelSeriesSlices, 32,
                                               m_openSeries.studyUid);
    m_storagePort = pacs::test::freeLoopbackPort();
    m_orthanc = std::make_unique<pacs::test::OrthancServer>(m_storagePort);
    for (const auto* series : {&m_openSeries, &m_cancelSeries})
        for (const fs::path& file : series->files)
            QVERIFY(!m_orthanc->upload(file).empty());
}

void PacsGuiTest::cleanupTestCase() {
    m_orthanc.reset();
    m_files.reset();
}

std::unique_ptr<StudyBrowser> PacsGuiTest::makeBrowser(const QTemporaryDir& dir) {
    const QString database = dir.filePath("studies.sqlite");
    pacs::writeNodeFile(pacsLocationsBeside(database).nodeFile.toStdString(),
                        nodeFileFor(m_orthanc->node(), m_storagePort));
    auto browser = std::make_unique<StudyBrowser>(database);
    browser->resize(1200, 800);
    browser->show();
    return browser;
}

int PacsGuiTest::search(RemotePanel& remote) {
    QSignalSpy finished(&remote, &RemotePanel::queryFinished);
    QTest::mouseClick(remote.findChild<QPushButton*>("remoteSearchButton"), Qt::LeftButton);
    if (!finished.wait(kNetworkWaitMs))
        return -1;
    return finished.first().first().toInt();
}

QModelIndex PacsGuiTest::seriesRow(RemotePanel& remote, const std::string& seriesUid) {
    const QModelIndex study = remote.model().index(0, 0);
    if (!remote.model().seriesListed(study)) {
        QSignalSpy listed(&remote, &RemotePanel::seriesListed);
        remote.tree().expand(study);
        if (!listed.wait(kNetworkWaitMs))
            return {};
    }
    for (int row = 0; row < remote.model().rowCount(study); ++row) {
        const QModelIndex series = remote.model().index(row, 0, study);
        if (series.data(RemoteStudyModel::SeriesUidRole).toString().toStdString() == seriesUid)
            return series;
    }
    return {};
}

void PacsGuiTest::settingsPageRoundTripsTheNodeFile_data() {
    QTest::addColumn<int>("nodes");
    QTest::newRow("no nodes") << 0;
    QTest::newRow("one node") << 1;
    QTest::newRow("three nodes") << 3;
}

void PacsGuiTest::settingsPageRoundTripsTheNodeFile() {
    QFETCH(int, nodes);
    QTemporaryDir dir;
    const QString path = dir.filePath("pacs-nodes.json");
    pacs::PacsNodeFile written;
    written.workstation = {"WS_ROUND", 11200};
    for (int i = 0; i < nodes; ++i)
        written.nodes.push_back({"node " + std::to_string(i), "AE" + std::to_string(i),
                                 "10.0.0." + std::to_string(i + 1), std::uint16_t(4242 + i)});
    pacs::writeNodeFile(path.toStdString(), written);

    PacsSettingsPage page(path);
    page.show();
    auto* table = page.findChild<QTableWidget*>("pacsNodes");
    QCOMPARE(table->rowCount(), nodes);
    for (int i = 0; i < nodes; ++i)
        QCOMPARE(table->item(i, PacsSettingsPage::HostColumn)->text(),
                 QString("10.0.0.%1").arg(i + 1));
    QCOMPARE(page.findChild<QLineEdit*>("workstationAet")->text(), QString("WS_ROUND"));

    // Typing in the AE title, then adding a node and filling it in: each valid state is written.
    QSignalSpy saved(&page, &PacsSettingsPage::saved);
    auto* aet = page.findChild<QLineEdit*>("workstationAet");
    aet->setFocus();
    aet->selectAll();
    QTest::keyClicks(aet, "WS_EDITED");
    QTest::mouseClick(page.findChild<QPushButton*>("addPacsNode"), Qt::LeftButton);
    QVERIFY(page.errorText().contains("empty")); // the new row has no called AE title yet
    setCell(*table, nodes, PacsSettingsPage::CalledAetColumn, "NEW_AE");
    setCell(*table, nodes, PacsSettingsPage::HostColumn, "pacs.example");
    setCell(*table, nodes, PacsSettingsPage::PortColumn, "11113");
    auto* method =
        qobject_cast<QComboBox*>(table->cellWidget(nodes, PacsSettingsPage::RetrieveColumn));
    QVERIFY(method);
    method->setCurrentIndex(method->findText("C-MOVE")); // currentIndexChanged: the page saves
    QVERIFY2(page.errorText().isEmpty(), qPrintable(page.errorText()));
    QVERIFY(saved.count() > 0);

    const pacs::PacsNodeFile reread = pacs::readNodeFile(path.toStdString());
    QCOMPARE(reread.workstation.aet, std::string("WS_EDITED"));
    QCOMPARE(int(reread.nodes.size()), nodes + 1);
    QCOMPARE(reread.nodes.back().calledAet, std::string("NEW_AE"));
    QCOMPARE(int(reread.nodes.back().port), 11113);
    QVERIFY(reread.nodes.back().retrieve == pacs::RetrieveMethod::Move);
    PacsSettingsPage again(path); // and a new page shows what was written
    QCOMPARE(again.findChild<QTableWidget*>("pacsNodes")->rowCount(), nodes + 1);
    QCOMPARE(again.editedFile().nodes.back().host, std::string("pacs.example"));
}

void PacsGuiTest::settingsPageNamesWhatIsInvalid_data() {
    QTest::addColumn<int>("column");
    QTest::addColumn<QString>("text");
    QTest::addColumn<QString>("message");
    QTest::newRow("AE title over 16")
        << int(PacsSettingsPage::CalledAetColumn) << "SEVENTEEN_LETTERS"
        << "1 to 16 characters";
    QTest::newRow("duplicate name") << int(PacsSettingsPage::NameColumn) << "first"
                                    << "two nodes are named \"first\"";
    QTest::newRow("empty host") << int(PacsSettingsPage::HostColumn) << ""
                                << "empty host";
    QTest::newRow("port not a number") << int(PacsSettingsPage::PortColumn) << "http"
                                       << "port 0";
}

void PacsGuiTest::settingsPageNamesWhatIsInvalid() {
    QFETCH(int, column);
    QFETCH(QString, text);
    QFETCH(QString, message);
    QTemporaryDir dir;
    const QString path = dir.filePath("pacs-nodes.json");
    pacs::PacsNodeFile valid;
    valid.nodes = {{"first", "AE1", "host1", 104}, {"second", "AE2", "host2", 105}};
    pacs::writeNodeFile(path.toStdString(), valid);

    PacsSettingsPage page(path);
    page.show();
    auto* table = page.findChild<QTableWidget*>("pacsNodes");
    setCell(*table, 1, column, text);
    QVERIFY2(page.errorText().contains(message), qPrintable(page.errorText()));
    QVERIFY(page.findChild<QLabel*>("pacsNodeError")->isVisible());
    // The file keeps its last valid state.
    QCOMPARE(pacs::readNodeFile(path.toStdString()).nodes[1].calledAet, std::string("AE2"));
    QCOMPARE(pacs::readNodeFile(path.toStdString()).nodes[1].name, std::string("second"));
}

void PacsGuiTest::settingsInTheMainWindowFeedTheQueryBar() {
    QTemporaryDir dir;
    MainWindow window(lw::test::isolatedOptions(dir));
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    auto* nodes = window.browser().remote().findChild<QComboBox*>("pacsNodeCombo");
    QCOMPARE(nodes->count(), 0); // no node file beside the new database yet
    window.showSettings();
    auto* page = window.findChild<PacsSettingsPage*>("pacsSettingsPage");
    QVERIFY(page);
    QCOMPARE(page->nodeFile(), pacsLocationsBeside(window.browser().databasePath()).nodeFile);
    QTest::mouseClick(page->findChild<QPushButton*>("addPacsNode"), Qt::LeftButton);
    auto* table = page->findChild<QTableWidget*>("pacsNodes");
    setCell(*table, 0, PacsSettingsPage::NameColumn, "radiology");
    setCell(*table, 0, PacsSettingsPage::CalledAetColumn, "RAD_PACS");
    setCell(*table, 0, PacsSettingsPage::HostColumn, "127.0.0.1");
    QVERIFY2(page->errorText().isEmpty(), qPrintable(page->errorText()));
    QCOMPARE(nodes->count(), 1);
    QCOMPARE(nodes->currentText(), QString("radiology"));
}

void PacsGuiTest::testButtonSaysWhatHappened_data() {
    QTest::addColumn<bool>("toOrthanc");
    QTest::addColumn<bool>("ok");
    QTest::addColumn<QString>("words");
    QTest::newRow("the test Orthanc") << true << true << "accepted";
    QTest::newRow("a closed port") << false << false << "refused";
}

void PacsGuiTest::testButtonSaysWhatHappened() {
    QFETCH(bool, toOrthanc);
    QFETCH(bool, ok);
    QFETCH(QString, words);
    QTemporaryDir dir;
    const QString path = dir.filePath("pacs-nodes.json");
    pacs::PacsNode node = m_orthanc->node();
    if (!toOrthanc)
        node.port = pacs::test::freeLoopbackPort();
    pacs::writeNodeFile(path.toStdString(), nodeFileFor(node, m_storagePort));

    PacsSettingsPage page(path);
    page.resize(640, 420);
    page.show();
    QVERIFY(QTest::qWaitForWindowExposed(&page));
    page.findChild<QTableWidget*>("pacsNodes")->selectRow(0);
    QSignalSpy finished(&page, &PacsSettingsPage::testFinished);
    QTest::mouseClick(page.findChild<QPushButton*>("testPacsNode"), Qt::LeftButton);
    QVERIFY(finished.wait(kNetworkWaitMs));
    QCOMPARE(finished.first().at(0).toBool(), ok);
    const QString shown = page.findChild<QLabel*>("pacsTestResult")->text();
    QVERIFY2(shown.contains(words), qPrintable(shown));
    if (ok)
        saveScreenshot(page, "pacs_settings.png");
}

void PacsGuiTest::queryListsTheRemoteStudy_data() {
    QTest::addColumn<QString>("patientName");
    QTest::addColumn<QString>("patientId");
    QTest::addColumn<QString>("modality");
    QTest::addColumn<int>("studies");
    QTest::newRow("everything") << ""
                                << ""
                                << "" << 1;
    QTest::newRow("by name, wildcard") << "Test^Line*"
                                       << ""
                                       << "" << 1;
    QTest::newRow("by ID") << ""
                           << "LW-TEST"
                           << "CT" << 1;
    QTest::newRow("another patient") << "Nobody*"
                                     << ""
                                     << "" << 0;
    QTest::newRow("another modality") << ""
                                      << ""
                                      << "MR" << 0;
}

void PacsGuiTest::queryListsTheRemoteStudy() {
    QFETCH(QString, patientName);
    QFETCH(QString, patientId);
    QFETCH(QString, modality);
    QFETCH(int, studies);
    QTemporaryDir dir;
    auto browser = makeBrowser(dir);
    QVERIFY(QTest::qWaitForWindowExposed(browser.get()));
    RemotePanel& remote = browser->remote();
    QTest::keyClicks(remote.findChild<QLineEdit*>("remotePatientName"), patientName);
    QTest::keyClicks(remote.findChild<QLineEdit*>("remotePatientId"), patientId);
    remote.findChild<QComboBox*>("remoteModality")->setCurrentText(modality);
    QCOMPARE(search(remote), studies);
    QCOMPARE(remote.model().rowCount(), studies);
    if (studies == 0)
        return;
    const QModelIndex study = remote.model().index(0, 0);
    QCOMPARE(study.data(RemoteStudyModel::StudyUidRole).toString().toStdString(),
             m_openSeries.studyUid);
    QCOMPARE(study.data(RemoteStudyModel::RemoteNodeRole).toString(), QString("orthanc"));
    QVERIFY(!study.data(Qt::DecorationRole).value<QIcon>().isNull()); // the remote marker
    QCOMPARE(remote.model().headerData(0, Qt::Horizontal).toString(), QString("Remote: orthanc"));
    QVERIFY(seriesRow(remote, m_openSeries.seriesUid).isValid());
    QVERIFY(seriesRow(remote, m_cancelSeries.seriesUid).isValid());
    QCOMPARE(remote.model().rowCount(study), 2);
}

void PacsGuiTest::queryOfAPacsThatDoesNotAnswerTimesOut() {
    // A PACS that takes the connection and never answers (a hung server): the kernel completes
    // the TCP handshake into the listen backlog, nobody reads.
    const struct Socket {
        int fd = ::socket(AF_INET, SOCK_STREAM, 0);
        ~Socket() { ::close(fd); }
    } listening;
    const int hung = listening.fd;
    QVERIFY(hung >= 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    QVERIFY(::bind(hung, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0);
    QVERIFY(::listen(hung, 4) == 0);
    socklen_t length = sizeof address;
    QVERIFY(::getsockname(hung, reinterpret_cast<sockaddr*>(&address), &length) == 0);
    pacs::PacsNode node = m_orthanc->node();
    node.port = ntohs(address.sin_port);

    QTemporaryDir dir;
    const QString database = dir.filePath("studies.sqlite");
    pacs::writeNodeFile(pacsLocationsBeside(database).nodeFile.toStdString(),
                        nodeFileFor(node, m_storagePort));
    StudyBrowser browser(database);
    browser.show();
    RemotePanel& remote = browser.remote();
    QSignalSpy failed(&remote, &RemotePanel::queryFailed);
    QTest::mouseClick(remote.findChild<QPushButton*>("remoteSearchButton"), Qt::LeftButton);
    QVERIFY(remote.isQuerying());
    QVERIFY(failed.wait(kNetworkWaitMs)); // the module's timeout, 10 s
    const QString message = remote.statusText();
    QVERIFY2(message.contains("timed out") && message.contains("orthanc"), qPrintable(message));
    QVERIFY(!remote.isQuerying());
    QVERIFY(remote.findChild<QPushButton*>("remoteSearchButton")->isEnabled());
}

void PacsGuiTest::doubleClickRetrievesAndOpens_data() {
    QTest::addColumn<int>("method");
    QTest::newRow("C-GET") << int(pacs::RetrieveMethod::Get);
    // Settings → PACS set to C-MOVE: Orthanc sends the images to the workstation's storage SCP.
    QTest::newRow("C-MOVE") << int(pacs::RetrieveMethod::Move);
}

void PacsGuiTest::doubleClickRetrievesAndOpens() {
    QFETCH(int, method);
    QTemporaryDir dir;
    const QString database = dir.filePath("studies.sqlite");
    pacs::PacsNode node = m_orthanc->node();
    node.retrieve = pacs::RetrieveMethod(method);
    pacs::writeNodeFile(pacsLocationsBeside(database).nodeFile.toStdString(),
                        nodeFileFor(node, m_storagePort));
    MainWindow window(lw::test::isolatedOptions(dir));
    window.resize(1200, 800);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    RemotePanel& remote = window.browser().remote();
    QCOMPARE(search(remote), 1);
    const QModelIndex series = seriesRow(remote, m_openSeries.seriesUid);
    QVERIFY(series.isValid());

    QSignalSpy arrived(&remote.retrieveJob(), &RetrieveJob::instanceArrived);
    doubleClick(remote.tree(), series);
    QVERIFY(lw::test::waitForReview(window));
    QCOMPARE(arrived.count(), kOpenSeriesSlices);
    QCOMPARE(arrived.last().at(0).toInt(), kOpenSeriesSlices); // n of N, one signal per image
    QCOMPARE(arrived.last().at(1).toInt(), kOpenSeriesSlices);
    auto* progress = remote.findChild<QProgressDialog*>("retrieveProgress");
    QCOMPARE(progress->value(), kOpenSeriesSlices);
    QCOMPARE(progress->maximum(), kOpenSeriesSlices);
    QVERIFY(!progress->isVisible());

    const QString uid = QString::fromStdString(m_openSeries.seriesUid);
    const QStringList files = window.browser().database().seriesFiles(uid);
    QCOMPARE(files.size(), kOpenSeriesSlices);
    for (const QString& file : files)
        QVERIFY2(file.startsWith(pacsLocationsBeside(database).store), qPrintable(file));
    QVERIFY(window.currentReview());
    QCOMPARE(window.currentReview()->source().seriesUid, uid);
    QVERIFY(window.browser().model().indexOfSeries(uid).isValid()); // listed as local now
}

void PacsGuiTest::cancelledRetrieveKeepsWhatArrived() {
    QTemporaryDir dir;
    auto browser = makeBrowser(dir);
    RemotePanel& remote = browser->remote();
    QCOMPARE(search(remote), 1);
    const QModelIndex series = seriesRow(remote, m_cancelSeries.seriesUid);
    QVERIFY(series.isValid());
    const QString uid = QString::fromStdString(m_cancelSeries.seriesUid);

    // Cancel on the retrieve's own thread after the first image, before the module checks the
    // token: deterministic, unlike a click that races the transfer.
    RetrieveJob& job = remote.retrieveJob();
    const QMetaObject::Connection cancelAfterFirst = connect(
        &job, &RetrieveJob::instanceArrived, &job, [&job](int) { job.cancel(); },
        Qt::DirectConnection);
    QSignalSpy finished(&job, &RetrieveJob::finished);
    remote.retrieve(series);
    QVERIFY(finished.wait(kNetworkWaitMs));
    disconnect(cancelAfterFirst);
    const auto first = finished.first().first().value<RetrieveOutcome>();
    QVERIFY(first.cancelled);
    QVERIFY(first.transferred >= 1);
    QVERIFY2(first.transferred < kCancelSeriesSlices,
             qPrintable(QString::number(first.transferred)));
    QVERIFY2(remote.statusText().contains("cancelled"), qPrintable(remote.statusText()));
    QCOMPARE(browser->database().seriesFiles(uid).size(), first.transferred);
    QVERIFY(browser->model().indexOfSeries(uid).isValid());

    // The next retrieve fetches only the rest, and the database then lists all of them.
    finished.clear();
    remote.retrieve(series);
    QVERIFY(finished.wait(kNetworkWaitMs));
    const auto second = finished.first().first().value<RetrieveOutcome>();
    QVERIFY2(second.complete(), qPrintable(second.message));
    QCOMPARE(second.skipped, first.transferred);
    QCOMPARE(second.transferred, kCancelSeriesSlices - first.transferred);
    QCOMPARE(browser->database().seriesFiles(uid).size(), kCancelSeriesSlices);
    saveScreenshot(*browser, "browser_remote.png"); // local above, remote below
}

void PacsGuiTest::retrieveFromAPacsThatIsDownSaysSo() {
    QTemporaryDir dir;
    auto browser = makeBrowser(dir);
    RemotePanel& remote = browser->remote();
    QCOMPARE(search(remote), 1);
    const QModelIndex series = seriesRow(remote, m_openSeries.seriesUid);
    QVERIFY(series.isValid());
    // The node now points where nothing listens (the PACS went down since the query).
    pacs::PacsNode down = m_orthanc->node();
    down.port = pacs::test::freeLoopbackPort();
    pacs::writeNodeFile(pacsLocationsBeside(browser->databasePath()).nodeFile.toStdString(),
                        nodeFileFor(down, m_storagePort));
    remote.reloadNodes();
    QSignalSpy failed(&remote.retrieveJob(), &RetrieveJob::failed);
    remote.retrieve(series);
    QVERIFY(failed.wait(kNetworkWaitMs));
    const QString message = remote.statusText();
    QVERIFY2(message.contains("orthanc") && message.contains("refused") &&
                 message.contains(QString::number(down.port)),
             qPrintable(message));
    QVERIFY(remote.findChild<QMessageBox*>("retrieveErrorBox"));
    QVERIFY(
        browser->database().seriesFiles(QString::fromStdString(m_openSeries.seriesUid)).isEmpty());
}

int main(int argc, char** argv) {
    if (!pacs::test::orthancBinary()) {
        std::fprintf(stderr, "SKIP: Orthanc is not installed (Debian: apt-get install orthanc)\n");
        return lw::test::kGuiSkipCode;
    }
    return lw::test::runGuiTest<PacsGuiTest>(argc, argv);
}

#include "pacs_gui_test.moc"
