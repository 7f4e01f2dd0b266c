// The annotations in the workstation's window: kept with the series in the study database (every
// change saved at once; closing the window and opening the series again, on a fresh connection,
// brings them back; opening it once more shows its review rather than a second one), undo and
// redo from the Edit menu's keys, and the File menu's exports through modules/report: the PNG
// burns them in, the PDF report's text holds the measurement and the comment (pdftotext; SKIP
// without poppler-utils), the Secondary Capture re-imports as a series of the same study, and an
// existing file is only replaced when the caller says the user agreed, and a link at the
// target's name is never written through.
#include "annotate/annotation_document.h"
#include "link_trap.h"
#include "lw/annotation/annotation_json.h"
#include "lw/report/secondary_capture.h"
#include "lw/studydb/study_database.h"
#include "review/review_panel.h"
#include "shell/review_export.h"
#include "window_test_support.h"

#include <QAction>
#include <QFile>
#include <QMenu>
#include <QMenuBar>
#include <QProcess>
#include <QStandardPaths>
#include <QtTest>

using namespace lw::gui;
using namespace lw::test;
using lw::annotation::Annotation;
using lw::annotation::AnnotationKind;
using lw::core::Overwrite;
using lw::report::PanelLayout;

namespace {

// Coordinates with few digits: the stored JSON (10 significant digits) gives them back exactly.
const Annotation kRuler{AnnotationKind::Ruler, {{-40.5, -60.25, 30.125}, {35.75, -55.5, 28.0}}, {}};
const Annotation kLabel{AnnotationKind::Label, {{1.5, -70.0, 10.0}}, "Orbit"};

// What a fresh connection finds stored for the series.
std::vector<Annotation> storedAnnotations(const QString& databasePath, const QString& seriesUid) {
    lw::studydb::StudyDatabase fresh(databasePath);
    const std::optional<QString> json = fresh.seriesAnnotations(seriesUid);
    return json ? lw::annotation::parseAnnotationsJson(json->toStdString(), "stored")
                : std::vector<Annotation>{};
}

QString readFile(const QString& path) {
    QFile file(path);
    return file.open(QIODevice::ReadOnly) ? QString::fromLatin1(file.readAll()) : QString();
}

bool writeFile(const QString& path, const QByteArray& bytes) {
    QFile file(path);
    return file.open(QIODevice::WriteOnly) && file.write(bytes) == bytes.size();
}

// The sphere phantom at its surface's iso-value with a ruler through its centre, pole to pole.
bool openSphereWithRuler(MainWindow& window) {
    window.show();
    if (!QTest::qWaitForWindowExposed(&window))
        return false;
    window.openPath("phantom:64:sphere", 0.0);
    if (!waitForReview(window))
        return false;
    window.currentReview()->annotations().add(
        {AnnotationKind::Ruler, {{0.0, -18.9, 0.0}, {0.0, 18.9, 0.0}}, {}}); // 37.8 mm
    return true;
}

} // namespace

class AnnotationWindowTest : public QObject {
    Q_OBJECT
private slots:
    void annotationsSurviveClosingAndReopening();
    void undoAndRedoFromTheKeys();
    void pngBurnsTheAnnotationsIn();
    void reportHoldsTheMeasurementAndTheComment_data();
    void reportHoldsTheMeasurementAndTheComment();
    void secondaryCaptureJoinsTheStudy();
    void anExistingFileIsOnlyReplacedWhenAgreed_data();
    void anExistingFileIsOnlyReplacedWhenAgreed();
    void anExportNeverWritesThroughALink_data();
    void anExportNeverWritesThroughALink();
};

void AnnotationWindowTest::annotationsSurviveClosingAndReopening() {
    QTemporaryDir dir;
    const MainWindowOptions options = isolatedOptions(dir);
    QString uid;
    {
        MainWindow window(options);
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        uid = importAndFindSeries(window, demoStudy());
        QVERIFY(!uid.isEmpty());
        window.openSeries(uid);
        QVERIFY(waitForReview(window));
        AnnotationDocument& document = window.currentReview()->annotations();
        document.add(kRuler);
        QCOMPARE(storedAnnotations(options.databasePath, uid).size(), std::size_t(1)); // at once
        document.add(kLabel);
        document.moveAnchor(0, 1, {30.0, -50.0, 20.0});
        QCOMPARE(storedAnnotations(options.databasePath, uid).at(0).anchors[1],
                 glm::dvec3(30.0, -50.0, 20.0));
        QVERIFY(window.currentReview()->storageProblem().isEmpty());
    } // the window closes: nothing is left to save
    MainWindow window(options);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.openSeries(uid);
    QVERIFY(waitForReview(window));
    const AnnotationDocument& document = window.currentReview()->annotations();
    QCOMPARE(document.count(), 2);
    QCOMPARE(document.at(0).kind, AnnotationKind::Ruler);
    QCOMPARE(document.at(0).anchors[0], kRuler.anchors[0]);
    QCOMPARE(document.at(0).anchors[1], glm::dvec3(30.0, -50.0, 20.0));
    QCOMPARE(document.at(1).text, std::string("Orbit"));
    QCOMPARE(document.at(1).anchors, kLabel.anchors);
    // Loaded, not edited: nothing to undo yet.
    QCOMPARE(window.currentReview()->annotations().undoStack().count(), 0);
    // Opened again (here by its folder), the series' review comes forward: a second review
    // would save its own list over the first one's.
    QSignalSpy opened(&window, &MainWindow::reviewOpened);
    window.openPath(demoStudy());
    QVERIFY(opened.wait(60000));
    QCOMPARE(window.reviews().size(), 1);
    QCOMPARE(window.currentReview()->annotations().count(), 2);
}

void AnnotationWindowTest::undoAndRedoFromTheKeys() {
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, "phantom:48"));
    QVERIFY(lw::test::makeActiveForKeys(window));
    AnnotationDocument& document = window.currentReview()->annotations();
    document.add(kRuler);
    document.add(kLabel);
    QTest::keyClick(&window, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(document.count(), 1);
    QTest::keyClick(&window, Qt::Key_Z, Qt::ControlModifier);
    QCOMPARE(document.count(), 0);
    QTest::keyClick(&window, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
    QCOMPARE(document.count(), 1);
    QCOMPARE(document.at(0).anchors, kRuler.anchors);
    // The Annotate menu lists the review's tools; the Edit menu names what Ctrl+Z undoes.
    QStringList annotate;
    for (QAction* menu : window.menuBar()->actions())
        if (menu->menu() && menu->text() == "&Annotate")
            for (QAction* action : menu->menu()->actions())
                annotate << action->objectName();
    QVERIFY2(annotate.contains("rulerTool") && annotate.contains("deleteAnnotation"),
             qPrintable(annotate.join(' ')));
    QVERIFY(window.findChild<QAction*>("undoAction")->text().contains("ruler"));
}

void AnnotationWindowTest::pngBurnsTheAnnotationsIn() {
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, "phantom:64:sphere"));
    ReviewWidget& review = *window.currentReview();
    const Annotation across{AnnotationKind::Ruler, {{-12.0, -24.0, 0.0}, {12.0, -24.0, 0.0}}, {}};
    review.annotations().add(across);
    const QString path = dir.filePath("sphere.png");
    QCOMPARE(exportReviewPng(review, path, {QSize(480, 360), PanelLayout::SideBySide}), QString());
    const QImage written(path);
    QCOMPARE(written.size(), QSize(960, 360));
    // Where the export's camera puts the ends, in both panels of the pair.
    const lw::render::Camera camera = review.camera().camera(480, 360);
    for (const glm::dvec3& anchor : across.anchors) {
        const glm::dvec2 pixel = camera.project(anchor).pixel;
        QVERIFY(annotationColourNear(written, {pixel.x, pixel.y}));
        QVERIFY(annotationColourNear(written, {pixel.x + 480.0, pixel.y}));
    }
}

void AnnotationWindowTest::reportHoldsTheMeasurementAndTheComment_data() {
    QTest::addColumn<QString>("input");
    QTest::addColumn<bool>("anonymise");
    QTest::addRow("phantom") << "phantom" << false;
    QTest::addRow("DICOM, with the patient") << "demo" << false;
    QTest::addRow("DICOM, anonymised") << "demo" << true;
}

void AnnotationWindowTest::reportHoldsTheMeasurementAndTheComment() {
    QFETCH(QString, input);
    QFETCH(bool, anonymise);
    const QString pdftotext = QStandardPaths::findExecutable("pdftotext");
    if (pdftotext.isEmpty())
        QSKIP("pdftotext (poppler-utils) is not installed");
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    if (input == "phantom") {
        QVERIFY(openSphereWithRuler(window));
    } else {
        QVERIFY(showAndOpen(window, demoStudy()));
        window.currentReview()->annotations().add(
            {AnnotationKind::Ruler, {{0.0, 0.0, 0.0}, {30.0, 40.0, 0.0}}, {}}); // 50.0 mm
    }
    ReviewWidget& review = *window.currentReview();
    const QString path = dir.filePath("report.pdf");
    const ReportOptions options{{QSize(400, 300), PanelLayout::SideBySide},
                                "Compared with the prior study: unchanged.",
                                anonymise};
    QCOMPARE(exportReviewReport(review, path, options), QString());
    QProcess process;
    process.start(pdftotext, {path, "-"});
    QVERIFY(process.waitForFinished(30000));
    const QString text = QString::fromUtf8(process.readAllStandardOutput());
    QVERIFY2(text.contains(input == "phantom" ? "37.8 mm" : "50.0 mm"), qPrintable(text));
    QVERIFY2(text.contains("Compared with the prior study: unchanged."), qPrintable(text));
    if (input == "demo") {
        const QString patientId = QString::fromStdString(review.source().dicom->patientId);
        QVERIFY(!patientId.isEmpty());
        QCOMPARE(text.contains(patientId), !anonymise);
        QVERIFY(text.contains(QString::fromStdString(review.source().dicom->studyDate).left(4)));
    }
}

void AnnotationWindowTest::secondaryCaptureJoinsTheStudy() {
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, demoStudy()));
    ReviewWidget& review = *window.currentReview();
    review.annotations().add(kLabel);
    const QString folder = dir.filePath("sc");
    QCOMPARE(
        exportReviewSecondaryCapture(review, folder, {QSize(256, 256), PanelLayout::SideBySide}),
        QString());
    QVERIFY(QFileInfo::exists(folder + "/LWSC0001.dcm"));
    // Imported back, it is a new series of the same study.
    QSignalSpy finished(&window.browser(), &StudyBrowser::importFinished);
    window.browser().importPath(folder);
    QVERIFY(finished.wait(60000));
    const QString studyUid = QString::fromStdString(review.source().dicom->studyInstanceUid);
    QStringList seriesOfTheStudy;
    for (const auto& patient : window.browser().database().patients())
        for (const auto& study : patient.studies)
            if (study.uid == studyUid)
                for (const auto& series : study.series)
                    seriesOfTheStudy << series.uid;
    QCOMPARE(seriesOfTheStudy.size(), 1); // the demo was opened without importing it
    QVERIFY(seriesOfTheStudy.front() != review.source().seriesUid);

    // A phantom has no study to join: said, and nothing is written.
    window.openPath("phantom:32");
    QVERIFY(waitForReview(window));
    const QString phantomFolder = dir.filePath("phantom-sc");
    const QString error = exportReviewSecondaryCapture(*window.currentReview(), phantomFolder,
                                                       {QSize(128, 128), PanelLayout::IsoPanel});
    QVERIFY2(error.contains(phantomFolder) && error.contains("not a DICOM series"),
             qPrintable(error));
    QVERIFY(!QFileInfo::exists(phantomFolder));
}

void AnnotationWindowTest::anExistingFileIsOnlyReplacedWhenAgreed_data() {
    QTest::addColumn<QString>("format");
    QTest::addRow("PNG") << "png";
    QTest::addRow("PDF report") << "pdf";
    QTest::addRow("Secondary Capture") << "sc";
}

namespace {

// The File menu's export of `format` ("png", "pdf" or "sc") to `target`; its error or "".
QString exportAs(const QString& format, ReviewWidget& review, const QString& target,
                 const ExportPicture& picture, Overwrite overwrite) {
    if (format == "png")
        return exportReviewPng(review, target, picture, overwrite);
    if (format == "pdf")
        return exportReviewReport(review, target, {picture, "", false}, overwrite);
    return exportReviewSecondaryCapture(review, target, picture, overwrite);
}

} // namespace

void AnnotationWindowTest::anExistingFileIsOnlyReplacedWhenAgreed() {
    QFETCH(QString, format);
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, demoStudy()));
    ReviewWidget& review = *window.currentReview();
    const ExportPicture picture{QSize(160, 120), PanelLayout::SideBySide};
    // A folder of its own: nothing but the user's file before, and the export's after.
    const QString target =
        format == "sc" ? dir.filePath("exports/sc") : dir.filePath("exports/out." + format);
    const QString existing = format == "sc" ? target + "/LWSC0001.dcm" : target;
    QVERIFY(QDir().mkpath(QFileInfo(existing).path()));
    QVERIFY(writeFile(existing, "the user's own file"));
    const auto run = [&](Overwrite overwrite) {
        return exportAs(format, review, target, picture, overwrite);
    };
    const QString refused = run(Overwrite::Refuse);
    QVERIFY2(refused.contains(existing) && refused.contains("exists"), qPrintable(refused));
    QCOMPARE(readFile(existing), QString("the user's own file"));
    QCOMPARE(QDir(QFileInfo(existing).path()).entryList(QDir::Files).size(), 1); // nothing else
    QCOMPARE(run(Overwrite::Allow), QString());
    QVERIFY(readFile(existing) != "the user's own file");
}

void AnnotationWindowTest::anExportNeverWritesThroughALink_data() {
    QTest::addColumn<QString>("format");
    QTest::addColumn<QString>("kind");
    for (const char* format : {"png", "pdf", "sc"})
        for (const std::string& kind : LinkTrap::kinds())
            QTest::addRow("%s %s", format, kind.c_str())
                << QString(format) << QString::fromStdString(kind);
}

// A link at the name the export would write (out of the chosen folder, dangling, or to the
// user's own file there) is refused with the file and the reason, even where the user agreed
// to replace what is there, and nothing is written anywhere.
void AnnotationWindowTest::anExportNeverWritesThroughALink() {
    QFETCH(QString, format);
    QFETCH(QString, kind);
    QTemporaryDir dir;
    MainWindow window(isolatedOptions(dir));
    QVERIFY(showAndOpen(window, demoStudy()));
    const std::string name =
        format == "sc" ? lw::report::secondaryCaptureFileName(1) : "out." + format.toStdString();
    const LinkTrap trap(dir.filePath("trap").toStdString(), name);
    const std::filesystem::path link = trap.link(kind.toStdString());
    const QString target =
        QString::fromStdString((format == "sc" ? trap.exports() : link).string());
    const QString refused = exportAs(format, *window.currentReview(), target,
                                     {QSize(160, 120), PanelLayout::SideBySide}, Overwrite::Allow);
    QVERIFY2(refused.contains(QString::fromStdString(link.string())) &&
                 refused.contains("symbolic link"),
             qPrintable(refused));
    QVERIFY(trap.untouched());
}

LW_GUI_TEST_MAIN(AnnotationWindowTest)
#include "annotation_window_test.moc"
