// Annotations on the real review widgets: a ruler made by two clicks on the sphere phantom
// measures its diameter within 0.5 % (either panel, GL in the panels or on the worker, three pairs
// of opposite views, the camera turned between the clicks); undo and redo of add, move and
// delete; a label asks for its text and its text can be edited; the keys pick the tools and Esc
// backs out step by step; a click off the surface is refused; the annotations are drawn over both
// panels where the camera puts them.
#include "annotate/annotation_actions.h"
#include "annotate/annotation_document.h"
#include "annotate/annotation_tool_controller.h"
#include "gui_test_support.h"
#include "review/review_panel.h"
#include "review/review_widget.h"
#include "review_test_support.h"

#include <QAction>
#include <QLabel>
#include <QSignalSpy>
#include <QtTest>
#include <memory>

using namespace lw::gui;
using lw::annotation::Annotation;
using lw::annotation::AnnotationKind;

namespace {

// phantom:64:sphere: 1 mm voxels around the origin, iso 0 HU at 0.6 of the half-extent.
constexpr int kSphereVoxels = 64;
constexpr double kSphereRadius = 0.6 * (kSphereVoxels - 1) / 2.0; // 18.9 mm

std::unique_ptr<ReviewWidget> showSphere(PanelGl panelGl) {
    auto review = std::make_unique<ReviewWidget>(
        lw::test::phantomSource(QString("phantom:%1:sphere").arg(kSphereVoxels), 0.0),
        lw::test::settingsFor(3, Chunking::Off, panelGl));
    review->resize(900, 560);
    review->show();
    return review;
}

bool settleShown(ReviewWidget& review) {
    return QTest::qWaitForWindowExposed(&review) && lw::test::waitSettled(review);
}

// A new view, and its frame on screen: the picks read the depth of what is shown.
bool showView(ReviewWidget& review, StandardView view) {
    const std::uint64_t frames = review.status().framesShown;
    review.setStandardView(view);
    return lw::test::waitSettled(review, frames + 1);
}

ReviewPanel& panelNamed(ReviewWidget& review, const QString& name) {
    return name == "iso" ? review.isoPanel() : review.silhouettePanel();
}

void click(ReviewPanel& panel, QPoint at) {
    QTest::mouseClick(&panel, Qt::LeftButton, {}, at);
}

// A drag with the left button, as the mouse makes it (synthetic moves: QTest::mouseMove warps
// the real pointer, which another test's window may be under).
void drag(ReviewPanel& panel, QPoint from, QPoint to) {
    QTest::mousePress(&panel, Qt::LeftButton, {}, from);
    for (int step = 1; step <= 4; ++step) {
        const QPointF at = QPointF(from) + (QPointF(to - from) * step / 4.0);
        QMouseEvent move(QEvent::MouseMove, at, panel.mapToGlobal(at), Qt::NoButton, Qt::LeftButton,
                         {});
        QApplication::sendEvent(&panel, &move);
    }
    QTest::mouseRelease(&panel, Qt::LeftButton, {}, to);
}

// Where the camera puts a patient point in the panel, as a widget position.
QPoint widgetPosition(ReviewPanel& panel, glm::dvec3 point) {
    const glm::dvec2 pixel = panel.viewCamera().project(point).pixel / panel.devicePixelRatioF();
    return {int(std::floor(pixel.x)), int(std::floor(pixel.y))};
}

QAction* toolAction(ReviewWidget& review, const char* name) {
    for (QAction* action : review.annotationActions().toolActions())
        if (action->objectName() == name)
            return action;
    return nullptr;
}

} // namespace

class AnnotationTest : public QObject {
    Q_OBJECT
private slots:
    void rulerByTwoClicksMeasuresTheSphere_data();
    void rulerByTwoClicksMeasuresTheSphere();
    void undoAndRedoAddMoveDelete_data();
    void undoAndRedoAddMoveDelete();
    void anEditDuringADragEndsIt();
    void labelAsksForItsTextAndCanBeEdited();
    void keysPickToolsAndEscapeBacksOut_data();
    void keysPickToolsAndEscapeBacksOut();
    void clickOffTheSurfaceIsRefused();
    void annotationsAreDrawnWhereTheCameraPutsThem_data();
    void annotationsAreDrawnWhereTheCameraPutsThem();
};

void AnnotationTest::rulerByTwoClicksMeasuresTheSphere_data() {
    QTest::addColumn<QString>("panel");
    QTest::addColumn<int>("panelGl");
    QTest::addColumn<int>("first");
    QTest::addColumn<int>("second");
    const std::pair<StandardView, StandardView> pairs[] = {
        {StandardView::Anterior, StandardView::Posterior},
        {StandardView::Left, StandardView::Right},
        {StandardView::Superior, StandardView::Inferior}};
    const char* const names[] = {"anterior-posterior", "left-right", "superior-inferior"};
    for (const QString panel : {"iso", "silhouette"})
        for (auto [panelGl, where] : {std::pair{PanelGl::InPanels, "GL in panels"},
                                      std::pair{PanelGl::OnWorker, "GL on worker"}})
            for (int i = 0; i < 3; ++i)
                QTest::addRow("%s panel, %s, %s", qPrintable(panel), where, names[i])
                    << panel << int(panelGl) << int(pairs[i].first) << int(pairs[i].second);
}

void AnnotationTest::rulerByTwoClicksMeasuresTheSphere() {
    QFETCH(QString, panel);
    QFETCH(int, panelGl);
    QFETCH(int, first);
    QFETCH(int, second);
    const auto review = showSphere(PanelGl(panelGl));
    QVERIFY(settleShown(*review));
    toolAction(*review, "rulerTool")->trigger();
    QCOMPARE(review->annotationTools().tool(), AnnotationTool::Ruler);
    ReviewPanel& target = panelNamed(*review, panel);
    // One end on each pole: the camera turns to the opposite side between the clicks.
    QVERIFY(showView(*review, StandardView(first)));
    click(target, target.rect().center());
    QCOMPARE(review->annotationTools().pendingAnchors(), 1);
    QVERIFY(showView(*review, StandardView(second)));
    click(target, target.rect().center());

    AnnotationDocument& document = review->annotations();
    QCOMPARE(document.count(), 1);
    QCOMPARE(document.at(0).kind, AnnotationKind::Ruler);
    const double length = lw::annotation::rulerLengthMm(document.at(0));
    const double diameter = 2.0 * kSphereRadius;
    qInfo("ruler %.3f mm for a %.1f mm sphere (%+.3f %%)", length, diameter,
          100.0 * (length - diameter) / diameter);
    QVERIFY2(std::abs(length - diameter) <= 0.005 * diameter,
             qPrintable(QString("%1 mm for a %2 mm sphere").arg(length).arg(diameter)));
    QCOMPARE(document.selected(), 0);                                  // the new ruler is selected
    QCOMPARE(review->annotationTools().tool(), AnnotationTool::Ruler); // ready for the next one
}

void AnnotationTest::undoAndRedoAddMoveDelete_data() {
    QTest::addColumn<QString>("panel");
    QTest::addRow("iso panel") << "iso";
    QTest::addRow("silhouette panel") << "silhouette";
}

void AnnotationTest::undoAndRedoAddMoveDelete() {
    QFETCH(QString, panel);
    const auto review = showSphere(PanelGl::OnWorker);
    QVERIFY(settleShown(*review));
    ReviewPanel& target = panelNamed(*review, panel);
    AnnotationDocument& document = review->annotations();
    QUndoStack& history = document.undoStack();
    const QPoint centre = target.rect().center();

    review->annotationTools().setTool(AnnotationTool::Ruler);
    click(target, centre + QPoint(-50, 10));
    click(target, centre + QPoint(50, 10));
    QCOMPARE(document.count(), 1);
    const Annotation added = document.at(0);
    review->annotationTools().setTool(AnnotationTool::None);
    click(target, widgetPosition(target, added.anchors[0])); // a click on a handle only selects
    QCOMPARE(history.count(), 1);
    QCOMPARE(document.at(0).anchors, added.anchors);

    // Drag the first end up: it is picked again where it is dropped.
    const QPoint dropAt = centre + QPoint(-20, -60);
    drag(target, widgetPosition(target, added.anchors[0]), dropAt);
    const std::optional<glm::dvec3> expected = review->pickSurface(target, dropAt);
    QVERIFY(expected);
    QCOMPARE(document.at(0).anchors[0], *expected);
    QCOMPARE(document.at(0).anchors[1], added.anchors[1]);
    const Annotation moved = document.at(0);

    review->annotationActions().deleteAction()->trigger(); // the moved ruler is still selected
    QCOMPARE(document.count(), 0);
    QCOMPARE(history.count(), 3); // one command each: add, move, delete

    history.undo(); // the delete
    QCOMPARE(document.count(), 1);
    QCOMPARE(document.at(0).anchors, moved.anchors);
    history.undo(); // the move: back to the very point first picked
    QCOMPARE(document.at(0).anchors, added.anchors);
    history.undo(); // the add
    QCOMPARE(document.count(), 0);
    history.redo();
    QCOMPARE(document.at(0).anchors, added.anchors);
    history.redo();
    QCOMPARE(document.at(0).anchors, moved.anchors);
    history.redo();
    QCOMPARE(document.count(), 0);
}

void AnnotationTest::anEditDuringADragEndsIt() {
    const auto review = showSphere(PanelGl::OnWorker);
    QVERIFY(settleShown(*review));
    AnnotationDocument& document = review->annotations();
    document.add({AnnotationKind::Ruler, {{-10, -15, 0}, {10, -15, 0}}, {}});
    ReviewPanel& iso = review->isoPanel();
    const QPoint handle = widgetPosition(iso, document.at(0).anchors[0]);
    QTest::mousePress(&iso, Qt::LeftButton, {}, handle);
    document.undoStack().undo(); // Ctrl+Z while the mouse button is down: the ruler goes
    QTest::mouseRelease(&iso, Qt::LeftButton, {}, handle + QPoint(30, 30));
    QCOMPARE(document.count(), 0); // and the drop moves nothing that is not there
    QCOMPARE(document.undoStack().index(), 0);
}

void AnnotationTest::labelAsksForItsTextAndCanBeEdited() {
    const auto review = showSphere(PanelGl::OnWorker);
    QVERIFY(settleShown(*review));
    QList<std::optional<QString>> answers{QString(" Lesion "), std::nullopt, QString("Cyst"),
                                          QString("  "), QString("Mass")};
    QStringList asked;
    review->annotationTools().setTextPrompt([&](const QString&, const QString& initial) {
        asked << initial;
        return answers.takeFirst();
    });
    QSignalSpy refused(&review->annotationTools(), &AnnotationToolController::refused);
    AnnotationDocument& document = review->annotations();
    ReviewPanel& iso = review->isoPanel();

    toolAction(*review, "textLabelTool")->trigger();
    click(iso, iso.rect().center());
    QCOMPARE(document.count(), 1);
    QCOMPARE(document.at(0).kind, AnnotationKind::Label);
    QCOMPARE(document.at(0).text, std::string("Lesion")); // trimmed
    click(iso, iso.rect().center() + QPoint(20, 0));      // the user cancels the text: no label
    QCOMPARE(document.count(), 1);

    review->annotationActions().editTextAction()->trigger(); // F2 on the selected label
    QCOMPARE(asked.last(), QString("Lesion"));
    QCOMPARE(document.at(0).text, std::string("Cyst"));
    review->annotationActions().editTextAction()->trigger(); // a label without text is refused
    QCOMPARE(document.at(0).text, std::string("Cyst"));
    QCOMPARE(refused.count(), 1);
    document.undoStack().undo();
    QCOMPARE(document.at(0).text, std::string("Lesion"));
    document.select(-1);
    review->annotationTools().setTool(AnnotationTool::None); // with the tool, clicks place labels
    const std::vector<glm::dvec3> placed = document.at(0).anchors;
    QTest::mouseDClick(&iso, Qt::LeftButton, {}, widgetPosition(iso, placed[0]));
    QCOMPARE(document.at(0).text, std::string("Mass")); // a double-click edits the text too
    QCOMPARE(document.at(0).anchors, placed);           // and moves nothing
    QVERIFY(answers.isEmpty());
}

void AnnotationTest::keysPickToolsAndEscapeBacksOut_data() {
    QTest::addColumn<int>("key");
    QTest::addColumn<int>("tool");
    QTest::addRow("T text label") << int(Qt::Key_T) << int(AnnotationTool::Label);
    QTest::addRow("A arrow") << int(Qt::Key_A) << int(AnnotationTool::Arrow);
    QTest::addRow("R ruler") << int(Qt::Key_R) << int(AnnotationTool::Ruler);
    QTest::addRow("G angle") << int(Qt::Key_G) << int(AnnotationTool::Angle);
}

void AnnotationTest::keysPickToolsAndEscapeBacksOut() {
    QFETCH(int, key);
    QFETCH(int, tool);
    const auto review = showSphere(PanelGl::OnWorker);
    QVERIFY(settleShown(*review));
    QVERIFY(lw::test::makeActiveForKeys(*review));
    ReviewPanel& iso = review->isoPanel();
    iso.setFocus();
    AnnotationToolController& tools = review->annotationTools();
    review->annotations().add({AnnotationKind::Ruler, {{0, -30, 0}, {10, -30, 0}}, {}});
    review->annotations().select(0);

    QTest::keyClick(&iso, Qt::Key(key));
    QCOMPARE(int(tools.tool()), tool);
    QVERIFY(toolAction(*review, "textLabelTool")->isChecked() ==
            (tool == int(AnnotationTool::Label)));
    if (AnnotationTool(tool) != AnnotationTool::Label) { // a label is done in one click
        click(iso, iso.rect().center());
        QCOMPARE(tools.pendingAnchors(), 1);
        QTest::keyClick(&iso, Qt::Key_Escape); // drops the annotation being placed
        QCOMPARE(tools.pendingAnchors(), 0);
        QCOMPARE(int(tools.tool()), tool);
    }
    QTest::keyClick(&iso, Qt::Key_Escape); // puts the tool away
    QCOMPARE(tools.tool(), AnnotationTool::None);
    QCOMPARE(review->annotations().selected(), 0);
    QTest::keyClick(&iso, Qt::Key_Escape); // and then the selection
    QCOMPARE(review->annotations().selected(), -1);
    review->annotations().select(0);
    QTest::keyClick(&iso, Qt::Key_Delete);
    QCOMPARE(review->annotations().count(), 0);
}

void AnnotationTest::clickOffTheSurfaceIsRefused() {
    const auto review = showSphere(PanelGl::OnWorker);
    QVERIFY(settleShown(*review));
    QSignalSpy refused(&review->annotationTools(), &AnnotationToolController::refused);
    review->annotationTools().setTool(AnnotationTool::Ruler);
    for (ReviewPanel* panel : {&review->isoPanel(), &review->silhouettePanel()})
        click(*panel, QPoint(4, 4)); // the background: no surface there
    QCOMPARE(refused.count(), 2);
    QVERIFY(refused.front().front().toString().contains("No surface"));
    QCOMPARE(review->annotationTools().pendingAnchors(), 0);
    QCOMPARE(review->annotations().count(), 0);
    QVERIFY(review->findChild<QLabel*>("reviewHint")->text().contains("No surface"));
}

void AnnotationTest::annotationsAreDrawnWhereTheCameraPutsThem_data() {
    QTest::addColumn<int>("panelGl");
    QTest::addRow("GL in panels") << int(PanelGl::InPanels);
    QTest::addRow("GL on worker") << int(PanelGl::OnWorker);
}

void AnnotationTest::annotationsAreDrawnWhereTheCameraPutsThem() {
    QFETCH(int, panelGl);
    const auto review = showSphere(PanelGl(panelGl));
    QVERIFY(settleShown(*review));
    // In front of the sphere, across it: seen from the front it lies at the height of the centre,
    // seen from above 14 mm toward the viewer's feet.
    const Annotation ruler{AnnotationKind::Ruler, {{-12, -24, 0}, {12, -24, 0}}, {}};
    review->annotations().add(ruler);
    review->annotations().select(-1); // drawn in the burnt-in colour, not the selection's
    QMap<StandardView, QPoint> seen;
    for (StandardView view : {StandardView::Anterior, StandardView::Superior}) {
        QVERIFY(showView(*review, view));
        for (ReviewPanel* panel : {&review->isoPanel(), &review->silhouettePanel()}) {
            const QImage shown = panel->grabImage();
            for (const glm::dvec3& anchor : ruler.anchors)
                QVERIFY2(lw::test::annotationColourNear(shown, widgetPosition(*panel, anchor)),
                         qPrintable(
                             QString("%1 panel, view %2").arg(panel->objectName()).arg(int(view))));
        }
        seen[view] = widgetPosition(review->isoPanel(), ruler.anchors[0]);
    }
    QVERIFY((seen[StandardView::Anterior] - seen[StandardView::Superior]).manhattanLength() > 20);
}

LW_GUI_TEST_MAIN(AnnotationTest)
#include "annotation_test.moc"
