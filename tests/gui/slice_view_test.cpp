// The review's slice panels driven as a user drives them, with synthetic events sent to the
// real widgets: the wheel and Page Up/Down step one slice, window presets and the right drag,
// the iso contour following the iso-value, the linked cursor both ways, and the layouts (and
// that a new review remembers the last one).
#include "gui_test_support.h"
#include "review/iso_control.h"
#include "review/review_panel.h"
#include "review/slice_view.h"
#include "review/slice_views.h"
#include "review_test_support.h"

#include <QAction>
#include <QApplication>
#include <QComboBox>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QSignalSpy>
#include <QWheelEvent>
#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

using lw::gui::ReviewLayout;
using lw::gui::ReviewLayoutChoice;
using lw::gui::ReviewWidget;
using lw::gui::SliceView;
using lw::gui::WindowPreset;
using lw::test::phantomSource;
using lw::test::settingsFor;
using lw::test::waitSlices;
using lw::volume::SliceOrientation;

Q_DECLARE_METATYPE(SliceOrientation)
Q_DECLARE_METATYPE(WindowPreset)
Q_DECLARE_METATYPE(ReviewLayoutChoice)
Q_DECLARE_METATYPE(lw::render::ThickSlices)

namespace {

constexpr SliceOrientation kOrientations[] = {SliceOrientation::Axial, SliceOrientation::Coronal,
                                              SliceOrientation::Sagittal};

// A review of `spec` in layout b (3D panels above, the three slices below), shown and settled.
std::unique_ptr<ReviewWidget> slicesReview(const QString& spec, double iso,
                                           lw::gui::PanelGl panelGl = lw::gui::PanelGl::Auto) {
    auto review = std::make_unique<ReviewWidget>(phantomSource(spec, iso),
                                                 settingsFor(3, lw::gui::Chunking::Off, panelGl));
    review->setLayoutChoice({ReviewLayout::SurfacesAndSlices, SliceOrientation::Axial});
    review->resize(1200, 900);
    review->show();
    return review;
}

void sendMouse(QWidget& widget, QEvent::Type type, QPointF at, Qt::MouseButton button,
               Qt::MouseButtons buttons, Qt::KeyboardModifiers modifiers) {
    QMouseEvent event(type, at, widget.mapToGlobal(at), button, buttons, modifiers);
    QApplication::sendEvent(&widget, &event);
}

void shiftClick(QWidget& widget, QPointF at) {
    sendMouse(widget, QEvent::MouseButtonPress, at, Qt::LeftButton, Qt::LeftButton,
              Qt::ShiftModifier);
    sendMouse(widget, QEvent::MouseButtonRelease, at, Qt::LeftButton, Qt::NoButton,
              Qt::ShiftModifier);
}

bool cyanNear(const QImage& image, QPointF at, int radius) {
    for (int y = int(at.y()) - radius; y <= int(at.y()) + radius; ++y)
        for (int x = int(at.x()) - radius; x <= int(at.x()) + radius; ++x)
            if (image.valid(x, y)) {
                const QColor c = image.pixelColor(x, y);
                if (c.red() < 60 && c.green() > 150 && c.blue() > 200)
                    return true;
            }
    return false;
}

// The contour's mean distance from the image's centre (pixels).
double meanContourRadius(const lw::gui::SliceResult& slice) {
    const glm::dvec2 centre = (glm::dvec2(slice.image->geometry.size) - 1.0) / 2.0;
    double sum = 0.0;
    for (const lw::volume::ContourSegment& segment : slice.contour)
        sum += glm::distance(segment.a, centre) + glm::distance(segment.b, centre);
    return slice.contour.empty() ? 0.0 : sum / (2.0 * double(slice.contour.size()));
}

// A frame asked for after the layout settled, and shown: the iso panel's depth (picking) is of
// the panel's final size, not of a frame rendered before the window was laid out.
bool settleAtView(ReviewWidget& review) {
    if (!lw::test::waitSettled(review))
        return false;
    const std::uint64_t shown = review.status().framesShown;
    review.setStandardView(lw::gui::StandardView::Anterior);
    return lw::test::waitSettled(review, shown + 1);
}

// The surface under the pixels beside `at` lies within 2 mm of `picked` (a pixel is ~0.5 mm).
bool smoothPatch(ReviewWidget& review, lw::gui::ReviewPanel& panel, QPoint at, glm::dvec3 picked) {
    for (const QPoint offset : {QPoint(-1, 0), QPoint(1, 0), QPoint(0, -1), QPoint(0, 1)}) {
        const std::optional<glm::dvec3> near = review.pickSurface(panel, at + offset);
        if (!near || glm::distance(*near, picked) > 2.0)
            return false;
    }
    return true;
}

// The layouts' menu on the view bar checks the layout shown (and only it).
bool layoutChecked(ReviewWidget& review, int index) {
    for (int i = 0; i < 5; ++i) {
        auto* action = review.findChild<QAction*>(QStringLiteral("reviewLayout%1").arg(i + 1));
        if (!action || action->isChecked() != (i == index))
            return false;
    }
    return true;
}

} // namespace

class SliceViewTest : public QObject {
    Q_OBJECT
private slots:
    void wheelAndPageKeysStepOneSlice_data();
    void wheelAndPageKeysStepOneSlice();
    void presetsSetTheWindow_data();
    void presetsSetTheWindow();
    void rightDragChangesWindowOnEverySlice();
    void contourFollowsTheIsoValue();
    void shiftClickOnTheSurfaceMovesTheSlices_data();
    void shiftClickOnTheSurfaceMovesTheSlices();
    void linkedCursorOnTheTiltedSeriesFollowsTheContours_data();
    void linkedCursorOnTheTiltedSeriesFollowsTheContours();
    void shiftDragStillPans();
    void shiftClickOnASliceShowsThe3dCrossHair();
    void layoutIsRememberedByTheNextReview_data();
    void layoutIsRememberedByTheNextReview();
};

void SliceViewTest::wheelAndPageKeysStepOneSlice_data() {
    QTest::addColumn<SliceOrientation>("orientation");
    QTest::addColumn<QString>("input");
    QTest::addColumn<int>("steps");
    for (SliceOrientation orientation : kOrientations) {
        const char* name = lw::volume::sliceOrientationName(orientation).data();
        QTest::addRow("%s wheel up", name) << orientation << "wheel" << 1;
        QTest::addRow("%s wheel down", name) << orientation << "wheel" << -1;
        QTest::addRow("%s page up", name) << orientation << "pageUp" << 1;
        QTest::addRow("%s page down", name) << orientation << "pageDown" << -1;
    }
}

void SliceViewTest::wheelAndPageKeysStepOneSlice() {
    QFETCH(SliceOrientation, orientation);
    QFETCH(QString, input);
    QFETCH(int, steps);
    // Uneven axes (48 x 40 x 24, 1 mm voxels) so each plane has its own extent.
    auto review = slicesReview("phantom:48x40x24", 300.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(waitSlices(*review));
    SliceView& view = review->slices().view(orientation);
    const double before = view.position();
    const QString label = view.positionText();
    const std::vector<float> valuesBefore = view.slice()->image->values;
    const QImage shownBefore = view.grab().toImage();
    const QPointF centre = QRectF(view.rect()).center();
    if (input == "wheel") {
        QWheelEvent wheel(centre, view.mapToGlobal(centre), QPoint(), QPoint(0, 120 * steps),
                          Qt::NoButton, Qt::NoModifier, Qt::NoScrollPhase, false);
        QApplication::sendEvent(&view, &wheel);
    } else {
        QKeyEvent key(QEvent::KeyPress, input == "pageUp" ? Qt::Key_PageUp : Qt::Key_PageDown,
                      Qt::NoModifier);
        QApplication::sendEvent(&view, &key);
    }
    QCOMPARE(view.position(), before + steps * view.geometry().step);
    QVERIFY(view.positionText() != label);
    QVERIFY(waitSlices(*review));
    QVERIFY(view.slice()->image->values != valuesBefore);
    QVERIFY(view.grab().toImage() != shownBefore);
}

void SliceViewTest::presetsSetTheWindow_data() {
    QTest::addColumn<WindowPreset>("preset");
    QTest::addColumn<double>("width");
    QTest::addColumn<double>("level");
    QTest::newRow("bone") << WindowPreset::Bone << 1800.0 << 400.0;
    QTest::newRow("soft tissue") << WindowPreset::SoftTissue << 400.0 << 40.0;
    QTest::newRow("lung") << WindowPreset::Lung << 1500.0 << -600.0;
    QTest::newRow("brain") << WindowPreset::Brain << 80.0 << 40.0;
}

void SliceViewTest::presetsSetTheWindow() {
    QFETCH(WindowPreset, preset);
    QFETCH(double, width);
    QFETCH(double, level);
    auto review = slicesReview("phantom:64", 300.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(waitSlices(*review));
    auto* chooser = review->findChild<QComboBox*>("sliceWindow");
    QVERIFY(chooser);
    QVERIFY(chooser->isEnabled()); // the phantom's values are HU
    const int index = chooser->findData(int(preset));
    QVERIFY(index >= 0);
    emit chooser->activated(index); // what the user's choice in the list emits
    QCOMPARE(review->slices().windowLevel().width, width);
    QCOMPARE(review->slices().windowLevel().level, level);
    QCOMPARE(chooser->currentIndex(), index);
    // Every image pixel's centre on screen shows the window's grey of its value (away from the
    // labels at the view's edges; the contour's yellow is skipped).
    SliceView& view = review->slices().view(SliceOrientation::Axial);
    const QImage shown = view.grab().toImage().convertToFormat(QImage::Format_RGB32);
    const double ratio = view.devicePixelRatioF();
    const lw::volume::SliceImage& image = *view.slice()->image;
    const QRectF inner(view.width() * 0.2, view.height() * 0.2, view.width() * 0.6,
                       view.height() * 0.6);
    int checked = 0;
    for (int y = 0; y < image.geometry.size.y; y += 3)
        for (int x = 0; x < image.geometry.size.x; x += 3) {
            const float value = image.at(x, y);
            const QPointF at =
                view.widgetPointOf(image.geometry.patientPoint(glm::dvec2(x, y), image.position));
            if (std::isnan(value) || !inner.contains(at))
                continue;
            const QColor c = shown.pixelColor(int(at.x() * ratio), int(at.y() * ratio));
            if (c.red() != c.green() || c.green() != c.blue())
                continue; // the contour
            const double grey =
                std::clamp((value - (level - width / 2)) / width * 255.0, 0.0, 255.0);
            QVERIFY2(std::abs(c.red() - grey) <= 2,
                     qPrintable(QStringLiteral("value %1 HU shown as %2, expected %3")
                                    .arg(value)
                                    .arg(c.red())
                                    .arg(grey)));
            ++checked;
        }
    QVERIFY(checked > 20);
}

void SliceViewTest::rightDragChangesWindowOnEverySlice() {
    auto review = slicesReview("phantom:64", 300.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(waitSlices(*review));
    SliceView& axial = review->slices().view(SliceOrientation::Axial);
    const lw::gui::WindowLevel before = axial.windowLevel();
    const QPointF start = QRectF(axial.rect()).center();
    sendMouse(axial, QEvent::MouseButtonPress, start, Qt::RightButton, Qt::RightButton, {});
    sendMouse(axial, QEvent::MouseMove, start + QPointF(40, 20), Qt::NoButton, Qt::RightButton, {});
    sendMouse(axial, QEvent::MouseButtonRelease, start + QPointF(40, 20), Qt::RightButton,
              Qt::NoButton, {});
    const lw::gui::WindowLevel after = axial.windowLevel();
    QVERIFY(after.width > before.width);
    QVERIFY(after.level > before.level);
    for (SliceOrientation orientation : kOrientations)
        QVERIFY(review->slices().view(orientation).windowLevel() == after);
    QCOMPARE(review->findChild<QComboBox*>("sliceWindow")->currentIndex(), -1); // custom
    QVERIFY(review->camera().cameraSetup().zoom == 1.0); // no 3D zoom from a slice's drag
}

void SliceViewTest::contourFollowsTheIsoValue() {
    // The sphere phantom: the contour of a lower iso-value is a larger circle on the axial slice
    // through the centre, and every step of the iso slider reaches the slices.
    auto review = slicesReview("phantom:64:sphere", 0.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(waitSlices(*review));
    SliceView& axial = review->slices().view(SliceOrientation::Axial);
    const std::size_t segments = axial.slice()->contour.size();
    const double radius = meanContourRadius(*axial.slice());
    QVERIFY(segments > 20);
    const double low = review->source().range.min +
                       0.2 * (review->source().range.max - review->source().range.min);
    review->isoControl().setIso(low);
    QCOMPARE(review->slices().iso(), review->iso());
    QVERIFY(waitSlices(*review));
    QCOMPARE(axial.slice()->iso, review->iso());
    // Values fall off outwards: the lower iso-value's circle is the larger one.
    QVERIFY2(
        meanContourRadius(*axial.slice()) > radius + 0.2,
        qPrintable(
            QStringLiteral("%1 -> %2 pixels").arg(radius).arg(meanContourRadius(*axial.slice()))));
    QVERIFY(axial.slice()->sampleMs >= 0.0);
}

void SliceViewTest::shiftClickOnTheSurfaceMovesTheSlices_data() {
    QTest::addColumn<bool>("isoPanel");
    QTest::addColumn<int>("panelGl");
    // The silhouette panel picks by a ray against the host's mesh: GL in the panels keeps one.
    QTest::newRow("iso panel") << true << int(lw::gui::PanelGl::Auto);
    QTest::newRow("iso panel, GL in panels") << true << int(lw::gui::PanelGl::InPanels);
    QTest::newRow("silhouette panel, GL in panels") << false << int(lw::gui::PanelGl::InPanels);
}

void SliceViewTest::shiftClickOnTheSurfaceMovesTheSlices() {
    QFETCH(bool, isoPanel);
    QFETCH(int, panelGl);
    auto review = slicesReview("phantom:64:sphere", 0.0, lw::gui::PanelGl(panelGl));
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(settleAtView(*review));
    QVERIFY(waitSlices(*review));
    lw::gui::ReviewPanel& panel = isoPanel ? review->isoPanel() : review->silhouettePanel();
    // Off the centre, so that no slice passes through the point before the click.
    const QPoint at = panel.rect().center() + QPoint(panel.height() / 20, -panel.height() / 20);
    const std::optional<glm::dvec3> picked = review->pickSurface(panel, at);
    QVERIFY(picked);
    shiftClick(panel, at);
    QVERIFY(review->slices().linkedPoint());
    const double voxel = 1.0; // the phantom's spacing
    for (SliceOrientation orientation : kOrientations) {
        const SliceView& view = review->slices().view(orientation);
        QVERIFY2(std::abs(view.geometry().positionOf(*picked) - view.position()) <= voxel,
                 lw::volume::sliceOrientationName(orientation).data());
        QVERIFY(view.marker());
        QVERIFY(glm::distance(*view.marker(), *picked) <= voxel);
        // The cross-hair on the slice is where the slice's pixels put the point.
        const std::optional<glm::dvec3> under = view.patientAt(view.widgetPointOf(*picked));
        QVERIFY(under && glm::distance(*under, *picked) <= voxel);
    }
    QVERIFY(waitSlices(*review));
    QVERIFY(review->isoPanel().crossHair());
}

// The demo is the GE head series with an 18.5° gantry tilt and uneven slice gaps (1.1-7.4 mm): a
// surface point Shift+clicked in 3D lies on the iso contour of each slice moved through it. Most
// points lie within 0.25 mm; one at the skull base 1.4-2.4 mm off in all three planes, where
// the surface's flat triangles cross a thick cell (so: the median within 0.5 mm, every point
// within half the mean slice gap). The surface is drawn with straight lines between the slices
// (the slices' own trilinear field); shape-based interpolation moves it between thick slices.
// The demo's 5.6 mm slices drawn both ways: shape-based (the default), where the 3D panels draw
// a resampled copy and the slices contour that copy, and straight lines between slices, where
// they contour the grey values. Either way a point picked on the surface lies on every slice's
// contour through it within 1 mm (the goal; 0.2 mm here).
void SliceViewTest::linkedCursorOnTheTiltedSeriesFollowsTheContours_data() {
    QTest::addColumn<lw::render::ThickSlices>("thickSlices");
    QTest::addColumn<bool>("drawnCopy");
    QTest::addColumn<double>("worstMm");
    QTest::addColumn<double>("medianMm");
    QTest::newRow("shape-based") << lw::render::ThickSlices::Smooth << true << 1.0 << 0.5;
    QTest::newRow("straight lines") << lw::render::ThickSlices::Linear << false << 1.0 << 0.5;
}

void SliceViewTest::linkedCursorOnTheTiltedSeriesFollowsTheContours() {
    QFETCH(lw::render::ThickSlices, thickSlices);
    QFETCH(bool, drawnCopy);
    QFETCH(double, worstMm);
    QFETCH(double, medianMm);
    const QString demo = lw::test::sourcePath() + "/resources/demo/ct_head_ge_tilt";
    lw::gui::ReviewSettings settings = settingsFor(3, lw::gui::Chunking::Off);
    settings.thickSlices = thickSlices;
    ReviewWidget review(phantomSource(demo, 400.0), settings);
    review.setLayoutChoice({ReviewLayout::SurfacesAndSlices, SliceOrientation::Axial});
    review.resize(1200, 900);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(settleAtView(review));
    lw::gui::ReviewPanel& panel = review.isoPanel();
    int clicked = 0;
    std::vector<double> distances; // mm, every click and plane
    for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
            const QPoint at =
                panel.rect().center() + QPoint(dx * panel.width() / 14, dy * panel.height() / 10);
            const std::optional<glm::dvec3> picked = review.pickSurface(panel, at);
            // On a smooth patch of surface only: at a depth edge (an orbit's rim, a hole in the
            // skull base) the depth buffer's pixel belongs to a neighbouring surface, and the
            // point lies up to a couple of millimetres off the one under the pointer (1.5 mm in
            // all three planes at one such point here, with neighbours 2-5 mm away).
            if (!picked || !smoothPatch(review, panel, at, *picked))
                continue;
            shiftClick(panel, at);
            QVERIFY(waitSlices(review));
            ++clicked;
            for (SliceOrientation orientation : kOrientations) {
                const SliceView& view = review.slices().view(orientation);
                const lw::gui::SliceResult& slice = *view.slice();
                QCOMPARE(slice.contourOfDrawnCopy, drawnCopy);
                const glm::dvec2 pixel = slice.image->geometry.pixelOf(*picked);
                double nearest = 1e9;
                for (const lw::volume::ContourSegment& segment : slice.contour) {
                    const glm::dvec2 along = segment.b - segment.a;
                    const double t = std::clamp(glm::dot(pixel - segment.a, along) /
                                                    std::max(glm::dot(along, along), 1e-12),
                                                0.0, 1.0);
                    nearest = std::min(nearest, glm::distance(pixel, segment.a + t * along));
                }
                const double mm = nearest * slice.image->geometry.pixelMm;
                distances.push_back(mm);
                QVERIFY2(mm <= worstMm,
                         qPrintable(QStringLiteral("%1 slice: %2 mm from the contour")
                                        .arg(lw::gui::sliceOrientationTitle(orientation))
                                        .arg(mm)));
            }
        }
    QVERIFY2(clicked >= 8, qPrintable(QString::number(clicked)));
    std::sort(distances.begin(), distances.end());
    QVERIFY2(distances[distances.size() / 2] <= medianMm,
             qPrintable(QStringLiteral("median %1 mm").arg(distances[distances.size() / 2])));
}

void SliceViewTest::shiftDragStillPans() {
    auto review = slicesReview("phantom:64:sphere", 0.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(lw::test::waitSettled(*review));
    lw::gui::ReviewPanel& panel = review->isoPanel();
    const QPointF start = QRectF(panel.rect()).center();
    const glm::dvec2 panBefore = review->camera().cameraSetup().pan;
    sendMouse(panel, QEvent::MouseButtonPress, start, Qt::LeftButton, Qt::LeftButton,
              Qt::ShiftModifier);
    sendMouse(panel, QEvent::MouseMove, start + QPointF(60, 0), Qt::NoButton, Qt::LeftButton,
              Qt::ShiftModifier);
    sendMouse(panel, QEvent::MouseButtonRelease, start + QPointF(60, 0), Qt::LeftButton,
              Qt::NoButton, Qt::ShiftModifier);
    QVERIFY(review->camera().cameraSetup().pan != panBefore);
    QVERIFY(!review->slices().linkedPoint()); // a drag, not a click
}

void SliceViewTest::shiftClickOnASliceShowsThe3dCrossHair() {
    auto review = slicesReview("phantom:64:sphere", 0.0);
    QVERIFY(QTest::qWaitForWindowExposed(review.get()));
    QVERIFY(lw::test::waitSettled(*review));
    QVERIFY(waitSlices(*review));
    SliceView& coronal = review->slices().view(SliceOrientation::Coronal);
    const QPointF at = QRectF(coronal.rect()).center() + QPointF(10, -8);
    const std::optional<glm::dvec3> point = coronal.patientAt(at);
    QVERIFY(point);
    shiftClick(coronal, at);
    for (lw::gui::ReviewPanel* panel : {&review->isoPanel(), &review->silhouettePanel()}) {
        QVERIFY(panel->crossHair());
        QVERIFY(glm::distance(*panel->crossHair(), *point) < 1e-9);
        const lw::render::ProjectedPoint projected = panel->viewCamera().project(*point);
        // grabImage paints the panel now, cross-hair included: nothing to wait for.
        QVERIFY2(cyanNear(panel->grabImage(), QPointF(projected.pixel.x, projected.pixel.y), 18),
                 "no cross-hair where the camera projects the point");
    }
    // The other slices moved through the point; the clicked one stays where it was.
    QCOMPARE(review->slices().view(SliceOrientation::Axial).position(), point->z);
    QCOMPARE(review->slices().view(SliceOrientation::Sagittal).position(), point->x);
}

void SliceViewTest::layoutIsRememberedByTheNextReview_data() {
    QTest::addColumn<ReviewLayoutChoice>("choice");
    QTest::addColumn<int>("chooserIndex");
    QTest::newRow("3D panels") << ReviewLayoutChoice{ReviewLayout::Surfaces,
                                                     SliceOrientation::Axial}
                               << 0;
    QTest::newRow("3D panels and slices")
        << ReviewLayoutChoice{ReviewLayout::SurfacesAndSlices, SliceOrientation::Axial} << 1;
    QTest::newRow("silhouette and coronal")
        << ReviewLayoutChoice{ReviewLayout::SilhouetteAndSlice, SliceOrientation::Coronal} << 3;
    QTest::newRow("silhouette and sagittal")
        << ReviewLayoutChoice{ReviewLayout::SilhouetteAndSlice, SliceOrientation::Sagittal} << 4;
}

void SliceViewTest::layoutIsRememberedByTheNextReview() {
    QFETCH(ReviewLayoutChoice, choice);
    QFETCH(int, chooserIndex);
    {
        ReviewWidget first(phantomSource("phantom:32", 300.0), settingsFor(3, {}));
        first.resize(900, 600);
        first.show();
        QVERIFY(QTest::qWaitForWindowExposed(&first));
        // The layouts' keys go through the review's shortcuts: Alt+1 ... Alt+5.
        QVERIFY(lw::test::makeActiveForKeys(first));
        first.isoPanel().setFocus();
        QTest::keyClick(&first.isoPanel(), Qt::Key(Qt::Key_1 + chooserIndex), Qt::AltModifier);
        QVERIFY(first.layoutChoice().layout == choice.layout);
        if (choice.layout == ReviewLayout::SilhouetteAndSlice)
            QCOMPARE(first.layoutChoice().largeSlice, choice.largeSlice);
        QVERIFY(layoutChecked(first, chooserIndex));
        QVERIFY(waitSlices(first));
    }
    ReviewWidget next(phantomSource("phantom:32", 300.0), settingsFor(3, {}));
    next.resize(900, 600);
    next.show();
    QVERIFY(QTest::qWaitForWindowExposed(&next));
    QVERIFY(next.layoutChoice().layout == choice.layout);
    QVERIFY(layoutChecked(next, chooserIndex));
    QCOMPARE(next.findChild<QComboBox*>("sliceWindow")->isVisible(),
             choice.layout != ReviewLayout::Surfaces);
    const bool row = choice.layout == ReviewLayout::SurfacesAndSlices;
    const bool large = choice.layout == ReviewLayout::SilhouetteAndSlice;
    QCOMPARE(next.isoPanel().isVisible(), !large);
    QVERIFY(next.silhouettePanel().isVisible());
    for (SliceOrientation orientation : kOrientations) {
        const bool shown = row || (large && orientation == choice.largeSlice);
        QCOMPARE(next.slices().view(orientation).isVisible(), shown);
        QCOMPARE(next.slices().isActive(orientation), shown);
    }
    QVERIFY(waitSlices(next));
    if (large) // the large slice beside the silhouette, as tall as it
        QCOMPARE(next.slices().view(choice.largeSlice).height(), next.silhouettePanel().height());
}

LW_GUI_TEST_MAIN(SliceViewTest)
#include "slice_view_test.moc"
