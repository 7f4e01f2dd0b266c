// The report's lines in the live panel: the silhouette panel on the screen and the exported PNG
// of the same view and size agree line pixel for line pixel, within a pixel, both ways (issue
// 26's measure: a line pixel differs from the background by more than 64 grey levels; >= 95 %
// of each side's line pixels have one of the other's within 1 px). The panel draws its mask as
// antialiased strokes of the line width (render::PixelMask::strokeCoverage), the export strokes
// the visible polylines: for every method, thin and wide lines, and with suggestive contours.
// With hidden lines both draw the hidden polylines the same way (thin, dashed, grey) under them.
#include "gui_test_support.h"
#include "lw/core/png_io.h"
#include "lw/evaluation/contour_score.h"
#include "lw/report/export_image.h"
#include "review/panel_render_job.h"
#include "review/qt_image.h"
#include "review/review_panel.h"
#include "review/review_widget.h"
#include "review_test_support.h"

#include <QtTest>
#include <cstdlib>
#include <filesystem>

using namespace lw::gui;
using lw::test::phantomSource;
using lw::test::settingsFor;
using lw::test::waitSettled;

namespace {

// Pixels that differ from `background` by more than 64 grey levels.
lw::render::PixelMask linePixels(const QImage& image, QColor background) {
    const QImage rgb = image.convertToFormat(QImage::Format_RGB32);
    const int backgroundGrey = qGray(background.rgb());
    lw::render::PixelMask mask(rgb.width(), rgb.height());
    for (int y = 0; y < rgb.height(); ++y)
        for (int x = 0; x < rgb.width(); ++x)
            mask.set(x, y, std::abs(qGray(rgb.pixel(x, y)) - backgroundGrey) > 64);
    return mask;
}

} // namespace

class LiveLinesTest : public QObject {
    Q_OBJECT
private slots:
    void panelAgreesWithTheExport_data();
    void panelAgreesWithTheExport();
};

void LiveLinesTest::panelAgreesWithTheExport_data() {
    QTest::addColumn<int>("method");
    QTest::addColumn<double>("lineWidth");
    QTest::addColumn<bool>("suggestive");
    QTest::addColumn<PanelGl>("panelGl");
    QTest::addColumn<bool>("hidden");
    const PanelGl worker = PanelGl::OnWorker, panels = PanelGl::InPanels;
    QTest::newRow("method 3, 2 px") << 3 << 2.0 << false << worker << false;
    QTest::newRow("method 3, 1 px") << 3 << 1.0 << false << worker << false;
    QTest::newRow("method 3, 3 px") << 3 << 3.0 << false << worker << false;
    QTest::newRow("method 2, 2 px") << 2 << 2.0 << false << worker << false;
    QTest::newRow("method 1, 2 px") << 1 << 2.0 << false << worker << false;
    QTest::newRow("method 3, 2 px, suggestive") << 3 << 2.0 << true << worker << false;
    QTest::newRow("method 3, 2 px, hidden lines") << 3 << 2.0 << false << worker << true;
    QTest::newRow("method 2, 1 px, hidden lines") << 2 << 1.0 << false << worker << true;
    QTest::newRow("method 1, 3 px, hidden lines") << 1 << 3.0 << false << worker << true;
    // Method 1 drawn by the panel's own GL (a GPU without CUDA): its resolve pass strokes.
    QTest::newRow("method 1 in the panel GL, 2 px") << 1 << 2.0 << false << panels << false;
    QTest::newRow("method 1 in the panel GL, 3 px") << 1 << 3.0 << false << panels << false;
}

void LiveLinesTest::panelAgreesWithTheExport() {
    QFETCH(int, method);
    QFETCH(double, lineWidth);
    QFETCH(bool, suggestive);
    QFETCH(PanelGl, panelGl);
    QFETCH(bool, hidden);
    ReviewSettings settings = settingsFor(method, Chunking::Off, panelGl);
    settings.lineWidth = lineWidth;
    settings.suggestiveContours = suggestive;
    settings.hiddenLines = hidden;
    ReviewWidget review(phantomSource("phantom:64", 300.5), settings);
    review.resize(900, 560);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));

    ReviewPanel& panel = review.silhouettePanel();
    const QImage shown = panel.grabImage();
    const QSize size = panel.renderSize();
    QCOMPARE(shown.size(), size);
    // The export of the silhouette panel alone at the panel's own size: the same camera, drawn
    // where File > Export draws it (the panels' own GL contexts, or a job off the UI thread).
    const PanelRenderJob job = review.renderJob(size);
    PanelVectors vectors;
    const auto [iso, silhouette] = review.rendersOnUiThread() ? review.renderPanels(size, &vectors)
                                                              : renderPanelJob(job, &vectors);
    lw::report::RenderedPanels panels{iso, silhouette, job.camera};
    panels.silhouetteLines = std::move(vectors.lines);
    panels.hiddenLines = std::move(vectors.hidden);
    QVERIFY2(panels.hiddenLines.empty() != hidden, "hidden lines exactly where switched on");
    panels.silhouetteLineWidth = job.appearance.lineWidth;
    panels.silhouetteLineColour = job.appearance.lineColour;
    QVERIFY2(!panels.silhouetteLines.empty(), "the export strokes polylines");
    const QImage exported = lw::report::composeExportImage(
        panels, {}, lw::report::PanelLayout::SilhouettePanel, settings.background);
    QCOMPARE(exported.size(), size);

    const lw::render::PixelMask onScreen = linePixels(shown, settings.background);
    const lw::render::PixelMask inExport = linePixels(exported, settings.background);
    QVERIFY2(onScreen.count() > std::size_t(size.width()), "the panel shows lines");
    const lw::evaluation::ContourScore score = lw::evaluation::scoreContours(onScreen, inExport, 1);
    const QString tag = QString::fromLatin1(QTest::currentDataTag()).replace(' ', '_');
    qInfo("%s: %zu line pixels on the screen, %zu in the export; %.4f of the screen's near the "
          "export's, %.4f of the export's near the screen's",
          qPrintable(tag), onScreen.count(), inExport.count(), score.precision, score.recall);
    if (score.precision < 0.95 || score.recall < 0.95) {
        const std::filesystem::path diff =
            std::filesystem::current_path() / ("live_lines_" + tag.toStdString() + ".diff.png");
        lw::core::writePng(diff, lw::evaluation::contourDiffImage(onScreen, inExport, 1));
        qWarning("diff image (red: only on the screen, blue: only in the export): %s",
                 diff.c_str());
    }
    QVERIFY2(score.precision >= 0.95, "the screen's line pixels lie on the export's");
    QVERIFY2(score.recall >= 0.95, "the export's line pixels lie on the screen's");
}

QTEST_MAIN(LiveLinesTest)
#include "live_lines_test.moc"
