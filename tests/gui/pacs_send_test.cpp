// "Send to PACS" in the main window against a real Orthanc (tests/pacs's OrthancServer, started
// for this test on free loopback ports): the File menu's action, driven through its dialog,
// stores the review's Secondary Capture and Encapsulated PDF report as two new series of the
// demo's study and says what the PACS answered per object; it is disabled with a tooltip while
// no node is configured and refused, before anything is written or sent, for an anonymised
// report or a review that is not of a DICOM series. SKIP without Orthanc or a display.
#include "gui_test_support.h"
#include "orthanc_server.h"
#include "review/review_widget.h"
#include "shell/export_dialogs.h"
#include "shell/main_window.h"
#include "shell/pacs_send_action.h"
#include "window_test_support.h"

#include <QAction>
#include <QMessageBox>
#include <QSignalSpy>
#include <QSpinBox>
#include <QTimer>
#include <QtTest>

using namespace lw::gui;
using namespace lw::test;
using lw::pacs::test::OrthancServer;

namespace {

// The node file the main window reads, beside its (temporary) study database.
void writeNodeFile(const QTemporaryDir& dir, const OrthancServer& server) {
    lw::pacs::PacsNodeFile file;
    file.workstation.aet = lw::pacs::test::kWorkstationAet;
    file.nodes.push_back(server.node());
    lw::pacs::writeNodeFile(std::filesystem::path(dir.filePath("pacs-nodes.json").toStdString()),
                            file);
}

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
        ++n;
    return n;
}

} // namespace

class PacsSendTest : public QObject {
    Q_OBJECT
private slots:
    void initTestCase() { m_server = std::make_unique<OrthancServer>(); }
    void cleanupTestCase() { m_server.reset(); }
    void sendStoresTheCaptureAndTheReportInTheStudy();
    void disabledWithoutANode();
    void refused_data();
    void refused();

private:
    std::unique_ptr<OrthancServer> m_server;
};

void PacsSendTest::sendStoresTheCaptureAndTheReportInTheStudy() {
    QTemporaryDir dir;
    writeNodeFile(dir, *m_server);
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, demoStudy()));
    QAction& send = *window.pacsSend().action();
    QVERIFY(send.isEnabled());
    // The dialog the action opens: the node chosen, smaller pictures, accepted.
    QTimer::singleShot(0, &window, [&window] {
        auto* dialog = window.findChild<SendToPacsDialog*>("sendToPacsDialog");
        QVERIFY(dialog);
        QCOMPARE(dialog->nodeIndex(), 0);
        for (QSpinBox* box : dialog->findChildren<QSpinBox*>())
            box->setValue(160);
        dialog->accept();
    });
    QSignalSpy finished(&window.pacsSend().sender(), &PacsSender::finished);
    send.trigger();
    QVERIFY(finished.count() == 1 || finished.wait(120000));
    const auto result = finished.at(0).at(0).value<PacsSendResult>();
    QVERIFY2(result.allStored(), qPrintable(result.summary()));
    QCOMPARE(int(result.objects.size()), 2);
    QVERIFY2(result.summary().contains("Secondary Capture: stored"), qPrintable(result.summary()));
    QVERIFY2(result.summary().contains("Report (Encapsulated PDF): stored"),
             qPrintable(result.summary()));
    auto* box = window.findChild<QMessageBox*>("sendToPacsResult");
    QVERIFY(box && box->isVisible());
    QCOMPARE(box->text(), result.summary());
    box->close();

    // In Orthanc: the demo's study (which the PACS did not hold) with the two new series.
    const std::string studyUid = window.currentReview()->source().dicom->studyInstanceUid;
    const std::string series = m_server->seriesOfStudy(studyUid);
    QCOMPARE(count(series, "\"Type\" : \"Series\""), 2);
    QVERIFY2(series.find("\"Modality\" : \"OT\"") != std::string::npos, series.c_str());
    QVERIFY2(series.find("\"Modality\" : \"DOC\"") != std::string::npos, series.c_str());
}

void PacsSendTest::disabledWithoutANode() {
    QTemporaryDir dir; // no node file beside the database
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, demoStudy()));
    QAction& send = *window.pacsSend().action();
    QVERIFY(!send.isEnabled());
    QVERIFY2(send.toolTip().contains("No PACS node is configured"), qPrintable(send.toolTip()));
    writeNodeFile(dir, *m_server);
    window.pacsSend().refresh(); // as when the File menu opens
    QVERIFY(send.isEnabled());
}

void PacsSendTest::refused_data() {
    QTest::addColumn<QString>("input");
    QTest::addColumn<bool>("anonymise");
    QTest::addColumn<QString>("reason");
    QTest::addRow("anonymised report")
        << demoStudy() << true
        << "An anonymised export cannot be sent to the PACS because it would no longer belong to "
           "the patient's study";
    QTest::addRow("phantom, not DICOM") << "phantom:32" << false << "has no study to join";
}

void PacsSendTest::refused() {
    QFETCH(QString, input);
    QFETCH(bool, anonymise);
    QFETCH(QString, reason);
    QTemporaryDir dir;
    writeNodeFile(dir, *m_server);
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, input));
    const std::string before = m_server->http("GET", "/instances").body;
    PacsSendRequest request;
    request.node = m_server->node();
    request.call.callingAet = lw::pacs::test::kWorkstationAet;
    request.report = {{QSize(96, 96), lw::report::PanelLayout::SideBySide}, QString(), anonymise};
    QSignalSpy finished(&window.pacsSend().sender(), &PacsSender::finished);
    const QString error = window.pacsSend().sender().start(*window.currentReview(), request);
    QVERIFY2(error.contains(reason), qPrintable(error));
    QVERIFY(!window.pacsSend().sender().isSending());
    QCOMPARE(finished.count(), 0);
    QCOMPARE(m_server->http("GET", "/instances").body, before); // nothing sent
}

int main(int argc, char** argv) {
    if (!lw::pacs::test::orthancBinary()) {
        std::fprintf(stderr, "SKIP: Orthanc is not installed (Debian: apt-get install orthanc)\n");
        return kGuiSkipCode;
    }
    return runGuiTest<PacsSendTest>(argc, argv);
}

#include "pacs_send_test.moc"
