// linework-screenshots: the user guide's pictures of the real windows (browser, review, the
// review with annotations, settings), taken from the X server as displayed.
// scripts/user_guide_screenshots.sh runs it under Xvfb so they can be regenerated after a change.
//
//   linework-screenshots OUTDIR PATH...    (imports every PATH, reviews the first series)
#include "annotate/annotation_document.h"
#include "annotate/annotation_tool_controller.h"
#include "bench/bench_support.h"
#include "browser/study_browser.h"
#include "review/review_panel.h"
#include "review/review_widget.h"
#include "review/slice_view.h"
#include "review/slice_views.h"
#include "settings/settings_dialog.h"
#include "shell/main_window.h"

#include <QApplication>
#include <QDir>
#include <QElapsedTimer>
#include <QScreen>
#include <QTabWidget>
#include <QTemporaryDir>
#include <QTest>
#include <cmath>
#include <cstdio>
#include <functional>

using namespace lw::gui;

namespace {

// What the X server shows of `widget`'s window (GL panels included).
bool saveWindow(QWidget& widget, const QString& path) {
    QTest::qWait(300);
    const QPixmap shot = widget.screen()->grabWindow(widget.window()->winId());
    const bool saved = shot.save(path);
    std::printf("%s %s (%dx%d)\n", saved ? "wrote" : "could not write", qPrintable(path),
                shot.width(), shot.height());
    return saved;
}

// The point nearest `wanted` (within 40 pixels) under which the panel shows the surface, so the
// clicks land on any head CT; `wanted` itself when there is none.
QPoint onSurface(ReviewWidget& review, ReviewPanel& panel, QPoint wanted) {
    for (int radius = 0; radius <= 40; radius += 2)
        for (int dy = -radius; dy <= radius; dy += 2)
            for (int dx = -radius; dx <= radius; dx += 2)
                if (std::max(std::abs(dx), std::abs(dy)) == radius &&
                    review.pickSurface(panel, wanted + QPoint(dx, dy)))
                    return wanted + QPoint(dx, dy);
    return wanted;
}

// Annotates the review as a user does: each tool, then clicks on the iso panel at fractions of
// its size (chosen on the head CTs in the 30/15 view), the arrow's caption by F2. A click off the
// surface is refused, so the count says whether the picture shows them all.
bool annotate(ReviewWidget& review) {
    AnnotationToolController& tools = review.annotationTools();
    QStringList texts{"Frontal bone", "Slice gap"}; // the label's, then the arrow's caption
    tools.setTextPrompt([&](const QString&, const QString&) { return texts.takeFirst(); });
    ReviewPanel& panel = review.isoPanel();
    const auto clickAt = [&](double x, double y) {
        const QPoint wanted(int(x * panel.width()), int(y * panel.height()));
        QTest::mouseClick(&panel, Qt::LeftButton, {}, onSurface(review, panel, wanted));
    };
    const struct {
        AnnotationTool tool;
        std::vector<std::pair<double, double>> clicks;
    } steps[] = {
        {AnnotationTool::Ruler, {{0.284, 0.494}, {0.633, 0.468}}},
        {AnnotationTool::Label, {{0.350, 0.407}}},
        {AnnotationTool::Arrow, {{0.509, 0.329}, {0.448, 0.359}}},
        {AnnotationTool::Angle, {{0.422, 0.563}, {0.509, 0.624}, {0.597, 0.555}}},
    };
    for (const auto& step : steps) {
        tools.setTool(step.tool);
        for (const auto& [x, y] : step.clicks)
            clickAt(x, y);
        if (step.tool == AnnotationTool::Arrow)
            tools.editSelectedText();
    }
    tools.setTool(AnnotationTool::None);
    review.annotations().select(0); // the ruler, with its handles
    const int made = review.annotations().count();
    std::printf("annotations placed: %d of 4\n", made);
    return made == 4;
}

// The demo study (`path`, 5.6 mm slices on average) opened in the window, then shown smoothed
// across its thick slices (the default) and with straight lines between them (Settings:
// "Smooth across thick slices" off): the user guide's after and before. Then, smoothed again,
// with Settings -> "Hidden lines" on: the silhouette's hidden parts dashed under it.
bool saveThickSliceReviews(MainWindow& window, const QString& path, const QDir& out) {
    // The review of this path, not the one open before it.
    ReviewWidget* opened = nullptr;
    const QMetaObject::Connection connection = QObject::connect(
        &window, &MainWindow::reviewOpened, [&](ReviewWidget* review) { opened = review; });
    window.openPath(path);
    const bool open = bench::waitFor([&] { return opened != nullptr; });
    QObject::disconnect(connection);
    if (!open)
        return false;
    ReviewWidget& review = *opened;
    // Settled at a view: the camera's frame asked for and shown, the worker idle.
    const auto showAt = [&](const std::function<void()>& change) {
        const std::uint64_t shown = review.status().framesShown;
        change();
        return bench::waitFor(
            [&] { return review.status().framesShown > shown && !review.isBusy(); });
    };
    bool ok = bench::waitFor([&] { return review.status().framesShown > 0 && !review.isBusy(); });
    ok = showAt([&] { review.camera().setView(30.0, 15.0); }) && ok;
    ok = saveWindow(window, out.filePath("thick_slices_smooth.png")) && ok;
    ReviewSettings straight = review.settings();
    straight.thickSlices = lw::render::ThickSlices::Linear;
    ok = showAt([&] { review.applySettings(straight); }) && ok;
    ok = saveWindow(window, out.filePath("thick_slices_linear.png")) && ok;
    ReviewSettings hidden = straight;
    hidden.thickSlices = lw::render::ThickSlices::Smooth;
    hidden.hiddenLines = true;
    ok = showAt([&] { review.applySettings(hidden); }) && ok;
    return saveWindow(window, out.filePath("hidden_lines.png")) && ok;
}

// The slice panels on the demo (tilted gantry: resampled, never sheared): each layout, with the
// linked cursor at a surface point so the cross-hairs show on the slices and in 3D.
bool saveSliceLayouts(ReviewWidget& review, const QDir& out) {
    const auto slicesShown = [&] {
        return bench::waitFor([&] {
            if (review.isBusy() || review.slices().isBusy())
                return false;
            for (auto plane :
                 {lw::volume::SliceOrientation::Axial, lw::volume::SliceOrientation::Coronal,
                  lw::volume::SliceOrientation::Sagittal})
                if (review.slices().isActive(plane) && !review.slices().view(plane).slice())
                    return false;
            return true;
        });
    };
    review.annotations().reset({});      // the slices and the cursors, not the measurements
    review.window()->resize(1600, 1040); // room for the 3D panels above the slices
    review.setLayoutChoice({ReviewLayout::SurfacesAndSlices, lw::volume::SliceOrientation::Axial});
    bool ok = slicesShown();
    review.slices().applyPreset(WindowPreset::Brain);
    ReviewPanel& panel = review.isoPanel();
    const QPoint wanted(int(0.62 * panel.width()), int(0.38 * panel.height()));
    if (const auto point = review.pickSurface(panel, onSurface(review, panel, wanted)))
        review.linkCursorTo(*point);
    else
        ok = false;
    ok = slicesShown() && ok;
    ok = saveWindow(review, out.filePath("slices_layout_3d_and_slices.png")) && ok;
    review.slices().applyPreset(WindowPreset::Bone);
    review.setLayoutChoice(
        {ReviewLayout::SilhouetteAndSlice, lw::volume::SliceOrientation::Sagittal});
    ok = slicesShown() && ok;
    ok = saveWindow(review, out.filePath("slices_layout_silhouette_and_sagittal.png")) && ok;
    review.setLayoutChoice({ReviewLayout::Surfaces, lw::volume::SliceOrientation::Sagittal});
    ok = slicesShown() && ok;
    return saveWindow(review, out.filePath("slices_layout_3d_only.png")) && ok;
}

// Measuring on the slices of the demo: a ruler across the skull on the axial slice and an angle on
// the sagittal one, placed by clicks on the slice panels as a user places them (fractions of
// each view, chosen on the demo in its brain window).
bool saveSliceMeasurements(ReviewWidget& review, const QDir& out) {
    review.annotations().reset({});
    review.setLayoutChoice({ReviewLayout::SurfacesAndSlices, lw::volume::SliceOrientation::Axial});
    review.slices().applyPreset(WindowPreset::Brain);
    bool ok = bench::waitFor([&] { return !review.isBusy() && !review.slices().isBusy(); });
    AnnotationToolController& tools = review.annotationTools();
    const auto clickOn = [&](lw::volume::SliceOrientation plane, double x, double y) {
        SliceView& view = review.slices().view(plane);
        QTest::mouseClick(&view, Qt::LeftButton, {},
                          QPoint(int(x * view.width()), int(y * view.height())));
    };
    tools.setTool(AnnotationTool::Ruler);
    clickOn(lw::volume::SliceOrientation::Axial, 0.33, 0.52);
    clickOn(lw::volume::SliceOrientation::Axial, 0.67, 0.52);
    tools.setTool(AnnotationTool::Angle);
    clickOn(lw::volume::SliceOrientation::Sagittal, 0.35, 0.35);
    clickOn(lw::volume::SliceOrientation::Sagittal, 0.50, 0.55);
    clickOn(lw::volume::SliceOrientation::Sagittal, 0.68, 0.38);
    tools.setTool(AnnotationTool::None);
    const int made = review.annotations().count();
    std::printf("slice measurements placed: %d of 2\n", made);
    ok = made == 2 && ok;
    return saveWindow(review, out.filePath("slices_measurements.png")) && ok;
}

} // namespace

int main(int argc, char* argv[]) {
    requestCoreProfileFormat();
    QTemporaryDir home;
    bench::isolateUserFolders(home);
    QApplication app(argc, argv);
    const QStringList args = QApplication::arguments().mid(1);
    if (args.size() < 2) {
        std::fprintf(stderr, "usage: linework-screenshots OUTDIR PATH...\n");
        return 2;
    }
    const QDir out(args.front());
    QDir().mkpath(out.path());

    MainWindowOptions options;
    options.databasePath = home.path() + "/studies.sqlite";
    MainWindow window(options);
    window.resize(1400, 860);
    window.show();
    if (!QTest::qWaitForWindowExposed(&window))
        return 1;

    int imports = 0;
    QObject::connect(&window.browser(), &StudyBrowser::importFinished, [&] { ++imports; });
    for (const QString& path : args.mid(1))
        window.browser().importPath(path);
    if (!bench::waitFor([&] { return imports == args.size() - 1; })) {
        std::fprintf(stderr, "linework-screenshots: the import did not finish\n");
        return 1;
    }
    // The series with the most slices: the diagnostic volume, not a scout.
    QStringList series;
    int mostSlices = 0;
    for (const auto& patient : window.browser().database().patients())
        for (const auto& study : patient.studies)
            for (const auto& record : study.series)
                if (record.sliceCount > mostSlices) {
                    mostSlices = record.sliceCount;
                    series = QStringList{record.uid};
                }
    if (series.isEmpty()) {
        std::fprintf(stderr, "linework-screenshots: nothing was imported\n");
        return 1;
    }
    window.browser().selectSeries(series.front());
    bool ok = saveWindow(window, out.filePath("browser.png"));

    window.openSeries(series.front());
    if (!bench::waitFor([&] {
            ReviewWidget* review = window.currentReview();
            return review && review->status().framesShown > 0 && !review->isBusy();
        })) {
        std::fprintf(stderr, "linework-screenshots: the review did not open: %s\n",
                     qPrintable(window.lastError()));
        return 1;
    }
    window.currentReview()->camera().setView(30.0, 15.0);
    bench::waitFor([&] { return !window.currentReview()->isBusy(); });
    ok = saveWindow(window, out.filePath("review.png")) && ok;
    ok = annotate(*window.currentReview()) && ok;
    ok = saveWindow(window, out.filePath("review_annotations.png")) && ok;

    window.showSettings();
    auto* settings = window.findChild<SettingsDialog*>();
    if (!settings || !QTest::qWaitForWindowExposed(settings))
        return 1;
    ok = saveWindow(*settings, out.filePath("settings.png")) && ok;
    // The appearance page: line width and colour, the hidden lines of exports.
    if (auto* tabs = settings->findChild<QTabWidget*>()) {
        tabs->setCurrentIndex(1);
        QTest::qWait(200);
        ok = saveWindow(*settings, out.filePath("settings_appearance.png")) && ok;
    }
    settings->close();
    ok = saveThickSliceReviews(window, args.at(1), out) && ok;
    window.currentReview()->applySettings(window.settings()); // smooth again
    ok = saveSliceLayouts(*window.currentReview(), out) && ok;
    ok = saveSliceMeasurements(*window.currentReview(), out) && ok;
    return ok ? 0 : 1;
}
