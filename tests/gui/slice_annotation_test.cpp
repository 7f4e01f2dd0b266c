// Measuring on the review's slice panels, with synthetic events sent to the real widgets: a ruler
// placed by two clicks on an axial slice of a phantom (1 mm voxels) measures the distance between
// the points clicked, names its plane, shows on its slice and not two slices away, and Ctrl+Z's
// undo removes it; an angle by three clicks on a coronal slice; dragging an anchor keeps it on its
// plane; the slices' own gestures (Shift+click) keep their meaning with a tool on; a slice
// annotation survives closing and reopening the series (study database in a temporary folder).
#include "annotate/annotation_document.h"
#include "annotate/annotation_tool_controller.h"
#include "lw/annotation/annotation_json.h"
#include "lw/studydb/study_database.h"
#include "review/slice_view.h"
#include "review/slice_views.h"
#include "review_test_support.h"
#include "shell/review_export.h"
#include "window_test_support.h"

#include <QApplication>
#include <QMouseEvent>
#include <QProcess>
#include <QStandardPaths>
#include <QWheelEvent>
#include <QtTest>
#include <cmath>

using namespace lw::gui;
using lw::annotation::Annotation;
using lw::annotation::AnnotationKind;
using lw::test::phantomSource;
using lw::test::settingsFor;
using lw::test::waitSlices;
using lw::volume::SliceOrientation;

namespace {

std::unique_ptr<ReviewWidget> slicesReview(const QString& spec, double iso) {
    auto review = std::make_unique<ReviewWidget>(phantomSource(spec, iso),
                                                 settingsFor(3, Chunking::Off, PanelGl::Auto));
    review->setLayoutChoice({ReviewLayout::SurfacesAndSlices, SliceOrientation::Axial});
    review->resize(1200, 900);
    review->show();
    return review;
}

void sendMouse(QWidget& widget, QEvent::Type type, QPointF at, Qt::MouseButton button,
               Qt::MouseButtons buttons, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
    QMouseEvent event(type, at, widget.mapToGlobal(at), button, buttons, modifiers);
    QApplication::sendEvent(&widget, &event);
}

void click(QWidget& widget, QPointF at) {
    sendMouse(widget, QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton);
    sendMouse(widget, QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton);
}

void drag(QWidget& widget, QPointF from, QPointF to) {
    sendMouse(widget, QEvent::MouseButtonPress, from, Qt::LeftButton, Qt::LeftButton);
    sendMouse(widget, QEvent::MouseMove, (from + to) / 2.0, Qt::NoButton, Qt::LeftButton);
    sendMouse(widget, QEvent::MouseMove, to, Qt::NoButton, Qt::LeftButton);
    sendMouse(widget, QEvent::MouseButtonRelease, to, Qt::LeftButton, Qt::NoButton);
}

// The widget point of a patient point, rounded as a mouse event's position is.
QPoint clickPoint(const SliceView& view, glm::dvec3 patient) {
    return view.widgetPointOf(patient).toPoint();
}

// The view's picture as painted now.
QImage shown(SliceView& view) {
    return view.grab().toImage();
}

// Orange pixels along the segment's middle third: the ruler is drawn there.
bool drawnBetween(const QImage& image, QPointF a, QPointF b) {
    for (const double t : {0.4, 0.5, 0.6})
        if (!lw::test::annotationColourNear(image, a + t * (b - a), 3))
            return false;
    return true;
}

} // namespace

class SliceAnnotationTest : public QObject {
    Q_OBJECT
private slots:
    void rulerOnAnAxialSlice();
    void angleOnACoronalSlice();
    void draggedAnchorStaysOnItsPlane();
    void shiftClickStillLinksWithATool();
    void sliceAnnotationsSurviveReopening();
    void exportsShowTheSlicesWithTheRuler();
};

void SliceAnnotationTest::rulerOnAnAxialSlice() {
    auto review = slicesReview("phantom:48x40x24", 300.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(waitSlices(*review));
    SliceView& view = review->slices().view(SliceOrientation::Axial);
    const std::optional<glm::dvec3> centre = view.patientAt(QRectF(view.rect()).center());
    QVERIFY(centre);
    // 30 mm right-left and 16 mm anterior-posterior: a 34 mm ruler on the phantom's 1 mm grid.
    const glm::dvec3 from = *centre + glm::dvec3(-15.0, -8.0, 0.0);
    const glm::dvec3 to = *centre + glm::dvec3(15.0, 8.0, 0.0);
    review->annotationTools().setTool(AnnotationTool::Ruler);
    click(view, clickPoint(view, from));
    QCOMPARE(review->annotationTools().pendingAnchors(), 1);
    click(view, clickPoint(view, to));
    AnnotationDocument& document = review->annotations();
    QCOMPARE(document.count(), 1);
    const Annotation& ruler = document.at(0);
    QCOMPARE(ruler.kind, AnnotationKind::Ruler);
    QVERIFY(ruler.slice);
    QCOMPARE(ruler.slice->orientation, SliceOrientation::Axial);
    QCOMPARE(ruler.slice->positionMm, view.position());
    QCOMPARE(ruler.slice->spacingMm, std::abs(view.geometry().step));
    // Within a widget pixel of each end (the view shows about 7 pixels per mm here).
    const double pixelMm =
        1.0 / (view.widgetPointOf(*centre + glm::dvec3(1, 0, 0)) - view.widgetPointOf(*centre))
                  .manhattanLength();
    QVERIFY2(std::abs(lw::annotation::rulerLengthMm(ruler) - 34.0) <= 2.0 * pixelMm,
             qPrintable(QString::number(lw::annotation::rulerLengthMm(ruler))));
    const std::string text = lw::annotation::measurementText(ruler);
    QVERIFY2(text.find("mm · axial") != std::string::npos, text.c_str());
    document.select(-1); // drawn in the burnt-in orange, not the selection's blue
    QVERIFY(drawnBetween(shown(view), view.widgetPointOf(from), view.widgetPointOf(to)));
    // Two slices on, the ruler is not there; back on its slice it is.
    view.stepBy(2);
    QVERIFY(!drawnBetween(shown(view), view.widgetPointOf(from), view.widgetPointOf(to)));
    view.stepBy(-2);
    QVERIFY(drawnBetween(shown(view), view.widgetPointOf(from), view.widgetPointOf(to)));
    // The 3D panels draw it too (its anchors are patient points); undo removes it.
    QVERIFY(lw::test::makeActiveForKeys(*review));
    document.undoStack().undo();
    QCOMPARE(document.count(), 0);
    QVERIFY(!drawnBetween(shown(view), view.widgetPointOf(from), view.widgetPointOf(to)));
}

void SliceAnnotationTest::angleOnACoronalSlice() {
    auto review = slicesReview("phantom:48x40x24", 300.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(waitSlices(*review));
    SliceView& view = review->slices().view(SliceOrientation::Coronal);
    const std::optional<glm::dvec3> vertex = view.patientAt(QRectF(view.rect()).center());
    QVERIFY(vertex);
    // Arms of 12 mm along x and 60° up towards the head (+z), in the coronal plane.
    const double radians = 60.0 * M_PI / 180.0;
    const glm::dvec3 first = *vertex + glm::dvec3(12.0, 0.0, 0.0);
    const glm::dvec3 second =
        *vertex + glm::dvec3(12.0 * std::cos(radians), 0.0, 12.0 * std::sin(radians));
    review->annotationTools().setTool(AnnotationTool::Angle);
    for (const glm::dvec3& point : {first, *vertex, second})
        click(view, clickPoint(view, point));
    AnnotationDocument& document = review->annotations();
    QCOMPARE(document.count(), 1);
    const Annotation& angle = document.at(0);
    QCOMPARE(angle.kind, AnnotationKind::Angle);
    QVERIFY(angle.slice && angle.slice->orientation == SliceOrientation::Coronal);
    QVERIFY2(std::abs(lw::annotation::angleDegrees(angle) - 60.0) < 1.5,
             qPrintable(QString::number(lw::annotation::angleDegrees(angle))));
    QVERIFY(QString::fromStdString(lw::annotation::measurementText(angle)).contains("coronal"));
    // Every anchor on the coronal plane (y is its normal).
    for (const glm::dvec3& anchor : angle.anchors)
        QCOMPARE(anchor.y, view.position());
    document.select(-1); // drawn in the burnt-in orange, not the selection's blue
    // The second arm (the first one lies under the measurement's text).
    QVERIFY(drawnBetween(shown(view), view.widgetPointOf(*vertex), view.widgetPointOf(second)));
}

void SliceAnnotationTest::draggedAnchorStaysOnItsPlane() {
    auto review = slicesReview("phantom:48x40x24", 300.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(waitSlices(*review));
    SliceView& view = review->slices().view(SliceOrientation::Axial);
    const glm::dvec3 centre = *view.patientAt(QRectF(view.rect()).center());
    review->annotationTools().setTool(AnnotationTool::Ruler);
    click(view, clickPoint(view, centre));
    click(view, clickPoint(view, centre + glm::dvec3(10.0, 0.0, 0.0)));
    review->annotationTools().setTool(AnnotationTool::None);
    AnnotationDocument& document = review->annotations();
    QCOMPARE(document.count(), 1);
    const glm::dvec3 end = document.at(0).anchors[1];
    // Dragged on the slice: the end follows the mouse and stays on the plane.
    drag(view, view.widgetPointOf(end), clickPoint(view, end + glm::dvec3(0.0, 8.0, 0.0)));
    QCOMPARE(document.count(), 1);
    QVERIFY(glm::distance(document.at(0).anchors[1], end + glm::dvec3(0.0, 8.0, 0.0)) < 0.5);
    QCOMPARE(document.at(0).anchors[1].z, view.position());
    // Moved to a point off the plane (as a drop on the surface in 3D does): onto the plane.
    document.moveAnchor(0, 0, centre + glm::dvec3(0.0, 0.0, 5.0));
    QCOMPARE(document.at(0).anchors[0], centre);
    document.undoStack().undo();
    document.undoStack().undo();
    QCOMPARE(document.at(0).anchors[1], end);
}

void SliceAnnotationTest::shiftClickStillLinksWithATool() {
    auto review = slicesReview("phantom:48x40x24", 300.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(waitSlices(*review));
    SliceView& view = review->slices().view(SliceOrientation::Axial);
    review->annotationTools().setTool(AnnotationTool::Ruler);
    const QPointF at = QRectF(view.rect()).center() + QPointF(10, 5);
    sendMouse(view, QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton,
              Qt::ShiftModifier);
    sendMouse(view, QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton,
              Qt::ShiftModifier);
    QVERIFY(review->slices().linkedPoint());
    QCOMPARE(review->annotationTools().pendingAnchors(), 0);
    // The wheel still steps the slice with a tool on.
    const double before = view.position();
    QWheelEvent wheel(at, view.mapToGlobal(at), QPoint(), QPoint(0, 120), Qt::NoButton,
                      Qt::NoModifier, Qt::NoScrollPhase, false);
    QApplication::sendEvent(&view, &wheel);
    QCOMPARE(view.position(), before + view.geometry().step);
}

void SliceAnnotationTest::sliceAnnotationsSurviveReopening() {
    QTemporaryDir dir;
    const MainWindowOptions options = lw::test::isolatedOptions(dir);
    QString uid;
    Annotation placed;
    {
        MainWindow window(options);
        window.show();
        QVERIFY(QTest::qWaitForWindowExposed(&window));
        uid = lw::test::importAndFindSeries(window, lw::test::demoStudy());
        QVERIFY(!uid.isEmpty());
        window.openSeries(uid);
        QVERIFY(lw::test::waitForReview(window));
        ReviewWidget& review = *window.currentReview();
        review.setLayoutChoice({ReviewLayout::SurfacesAndSlices, SliceOrientation::Axial});
        QVERIFY(waitSlices(review));
        SliceView& view = review.slices().view(SliceOrientation::Sagittal);
        const glm::dvec3 centre = *view.patientAt(QRectF(view.rect()).center());
        review.annotationTools().setTool(AnnotationTool::Ruler);
        click(view, clickPoint(view, centre));
        click(view, clickPoint(view, centre + glm::dvec3(0.0, 20.0, 10.0)));
        QCOMPARE(review.annotations().count(), 1);
        placed = review.annotations().at(0);
        QVERIFY(placed.slice);
    }
    MainWindow window(options);
    window.show();
    QVERIFY(QTest::qWaitForWindowExposed(&window));
    window.openSeries(uid);
    QVERIFY(lw::test::waitForReview(window));
    const AnnotationDocument& document = window.currentReview()->annotations();
    QCOMPARE(document.count(), 1);
    const Annotation& loaded = document.at(0);
    QVERIFY(loaded.slice);
    QCOMPARE(loaded.slice->orientation, SliceOrientation::Sagittal);
    QVERIFY(std::abs(loaded.slice->positionMm - placed.slice->positionMm) < 1e-6);
    QVERIFY(std::abs(loaded.slice->spacingMm - placed.slice->spacingMm) < 1e-6);
    for (int i = 0; i < 2; ++i)
        QVERIFY(glm::distance(loaded.anchors[std::size_t(i)], placed.anchors[std::size_t(i)]) <
                1e-6);
    QCOMPARE(lw::annotation::measurementText(loaded), lw::annotation::measurementText(placed));
}

// The PNG holds the three slices below the 3D panels, with the ruler's pixels on the axial one;
// the PDF's measurement table names the ruler's plane (pdftotext; that part SKIPs without it).
void SliceAnnotationTest::exportsShowTheSlicesWithTheRuler() {
    auto review = slicesReview("phantom:48x40x24", 300.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(waitSlices(*review));
    QVERIFY(lw::test::waitSettled(*review));
    SliceView& view = review->slices().view(SliceOrientation::Axial);
    const glm::dvec3 centre = *view.patientAt(QRectF(view.rect()).center());
    const glm::dvec3 from = centre + glm::dvec3(-15.0, -10.0, 0.0);
    const glm::dvec3 to = centre + glm::dvec3(15.0, 10.0, 0.0);
    review->annotationTools().setTool(AnnotationTool::Ruler);
    click(view, clickPoint(view, from));
    click(view, clickPoint(view, to));
    QCOMPARE(review->annotations().count(), 1);
    const Annotation ruler = review->annotations().at(0);
    QTemporaryDir dir;
    const QString png = dir.filePath("slices.png");
    const QSize panel(400, 300);
    QCOMPARE(exportReviewPng(*review, png, {panel, lw::report::PanelLayout::SideBySide}),
             QString());
    const QImage written(png);
    const int side = 2 * panel.width() / 3; // three square slices under the two 3D panels
    QCOMPARE(written.size(), QSize(2 * panel.width(), panel.height() + side));
    // The axial slice fitted into the first square, as the export fits it.
    const lw::volume::SliceGeometry& geometry = view.slice()->image->geometry;
    const double scale = side / double(std::max(geometry.size.x, geometry.size.y));
    const QPointF origin = QPointF(side, side) / 2.0 -
                           QPointF(geometry.size.x, geometry.size.y) * scale / 2.0 +
                           QPointF(0, panel.height());
    const auto inPicture = [&](glm::dvec3 patient) {
        const glm::dvec2 pixel = geometry.pixelOf(patient);
        return origin + QPointF(pixel.x + 0.5, pixel.y + 0.5) * scale;
    };
    QVERIFY(drawnBetween(written, inPicture(from), inPicture(to)));
    // The coronal square beside it does not show the axial ruler there.
    QVERIFY(!drawnBetween(written, inPicture(from) + QPointF(side, 0),
                          inPicture(to) + QPointF(side, 0)));
    const QString pdftotext = QStandardPaths::findExecutable("pdftotext");
    if (pdftotext.isEmpty())
        QSKIP("pdftotext (poppler-utils) is not installed: the PDF's text is not checked");
    const QString pdf = dir.filePath("slices.pdf");
    QCOMPARE(exportReviewReport(*review, pdf, {{panel, lw::report::PanelLayout::SideBySide}, {}}),
             QString());
    QProcess process;
    process.start(pdftotext, {pdf, "-"});
    QVERIFY(process.waitForFinished(30000));
    const QString text = QString::fromUtf8(process.readAllStandardOutput());
    const QString plane = QString::fromStdString(lw::annotation::placementText(ruler));
    QVERIFY2(plane.startsWith("axial ") && text.contains(plane), qPrintable(text));
}

LW_GUI_TEST_MAIN(SliceAnnotationTest)
#include "slice_annotation_test.moc"
