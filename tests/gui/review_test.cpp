// The review window on real widgets: both panels draw, the iso slider re-extracts, method and
// chunking switch the right panel, the cameras are linked, export sizes and picking work, and a
// screenshot of the window matches its baseline.
#include "gui_test_support.h"
#include "lw/core/image_compare.h"
#include "lw/core/png_io.h"
#include "review/iso_control.h"
#include "review/qt_image.h"
#include "review/review_panel.h"
#include "review/review_widget.h"
#include "review/silhouette_textures.h"
#include "review/volume_loader.h"
#include "review_test_support.h"

#include <QDoubleSpinBox>
#include <QLabel>
#include <QOffscreenSurface>
#include <QOpenGLFunctions>
#include <QOpenGLWidget>
#include <QPainter>
#include <QScopeGuard>
#include <QSlider>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <future>
#include <memory>
#include <set>

using namespace lw::gui;

using lw::test::phantomSource;
using lw::test::settingsFor;
using lw::test::waitSettled;

class ReviewTest : public QObject {
    Q_OBJECT
private slots:
    void panelsDraw_data();
    void panelsDraw();
    void isoSliderChangesTheSurface();
    void newerIsoWinsOverOlder();
    void methodAndChunkingSwitchTheRightPanel();
    void camerasAreLinked();
    void suggestiveContoursAddLines();
    void oversamplingRefinesTheMesh();
    void panelsReRenderAtAnySize();
    void pickingFindsTheSphereSurface_data();
    void pickingFindsTheSphereSurface();
    void windowMatchesBaseline();
    void hoverShowsThePatientPosition();
    void linesTextureDrawsAsTheHostImage();
    void silhouetteTexturesAreNeverHandedOutTwice();
    void loaderReportsPhantomProgress_data();
    void loaderReportsPhantomProgress();
    void cancelEndsThePhantomLoadWithoutAVolume();
    void loaderWaitsForTheGpuProbe();
};

void ReviewTest::panelsDraw_data() {
    QTest::addColumn<int>("method");
    QTest::addColumn<int>("chunking");
    QTest::addColumn<int>("panelGl");
    for (auto [panelGl, where] : {std::pair{PanelGl::InPanels, "GL in panels"},
                                  std::pair{PanelGl::OnWorker, "GL on worker"}})
        for (int method = 1; method <= 3; ++method) {
            QTest::addRow("method %d S, %s", method, where)
                << method << int(Chunking::Off) << int(panelGl);
            QTest::addRow("method %d L, %s", method, where)
                << method << int(Chunking::Fixed) << int(panelGl);
        }
}

void ReviewTest::panelsDraw() {
    QFETCH(int, method);
    QFETCH(int, chunking);
    QFETCH(int, panelGl);
    ReviewWidget review(phantomSource("phantom:64", 300.5),
                        settingsFor(method, Chunking(chunking), PanelGl(panelGl)));
    review.resize(1000, 640);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    // grabImage paints each panel now; a GL failure in that paint shows in the error line.
    const QImage iso = review.isoPanel().grabImage();
    const QImage silhouette = review.silhouettePanel().grabImage();
    QVERIFY2(review.errorText().isEmpty(), qPrintable(review.errorText()));
    const int area = iso.width() * iso.height();
    const int surfacePixels = lw::test::pixelsDifferentFrom(iso, Qt::white);
    QVERIFY2(surfacePixels > area / 20, qPrintable(QString::number(surfacePixels)));
    const int linePixels = lw::test::pixelsDifferentFrom(silhouette, Qt::white, 100);
    QVERIFY2(linePixels > 300 && linePixels < area / 4, qPrintable(QString::number(linePixels)));
    QVERIFY(review.status().triangles > 1000);
    QVERIFY(review.statusText().contains(QString("Method %1").arg(method)));
    QCOMPARE(review.statusText().contains(" L ("), chunking == int(Chunking::Fixed));
    const bool inPanels = PanelGl(panelGl) == PanelGl::InPanels;
    QCOMPARE(review.isoPanel().usesGl(), inPanels);
    QCOMPARE(review.silhouettePanel().usesGl(),
             method == 1 && chunking == int(Chunking::Off) && inPanels);
}

void ReviewTest::isoSliderChangesTheSurface() {
    ReviewWidget review(phantomSource("phantom:64", 300.5), settingsFor(3, Chunking::Off));
    review.resize(900, 600);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    const std::size_t before = review.status().triangles;
    auto* slider = review.findChild<QSlider*>("isoSlider");
    QVERIFY(slider);
    slider->setValue(-300); // soft tissue shell instead of bone
    QVERIFY(waitSettled(review, review.status().framesShown + 1));
    QCOMPARE(review.status().isoShown, -300.0);
    QVERIFY(review.status().triangles != before);
    QCOMPARE(review.findChild<QDoubleSpinBox*>("isoSpin")->value(), -300.0);
}

void ReviewTest::newerIsoWinsOverOlder() {
    ReviewWidget review(phantomSource("phantom:96", 300.5), settingsFor(3, Chunking::Off));
    review.resize(900, 600);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    // A drag: many values in a row, faster than frames. The first one's frame runs to the end
    // and is shown (the panels follow the drag), the ones between are replaced while they wait,
    // and the newest is shown last.
    QList<double> shown;
    connect(&review, &ReviewWidget::frameShown, &review,
            [&] { shown.append(review.status().isoShown); });
    for (int hu = 200; hu <= 700; hu += 50)
        review.setIso(hu);
    QVERIFY(waitSettled(review, review.status().framesShown + 2));
    QCOMPARE(shown, (QList<double>{200.0, 700.0}));
    QCOMPARE(review.status().isoShown, 700.0);
    QCOMPARE(review.iso(), 700.0);
}

void ReviewTest::methodAndChunkingSwitchTheRightPanel() {
    ReviewWidget review(phantomSource("phantom:64", 300.5), settingsFor(3, Chunking::Off));
    review.resize(900, 600);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    const QImage method3 = review.silhouettePanel().grabImage();

    review.applySettings(settingsFor(2, Chunking::Off));
    QVERIFY(waitSettled(review, review.status().framesShown + 1));
    QVERIFY(review.statusText().startsWith("Method 2"));
    const QImage method2 = review.silhouettePanel().grabImage();
    QVERIFY(method2 != method3); // another method draws other pixels

    review.applySettings(settingsFor(1, Chunking::Off, PanelGl::InPanels));
    QVERIFY(waitSettled(review, review.status().framesShown + 1));
    QVERIFY(review.silhouettePanel().usesGl());
    QVERIFY(lw::test::pixelsDifferentFrom(review.silhouettePanel().grabImage(), Qt::white, 100) >
            300);

    review.applySettings(settingsFor(1, Chunking::Fixed, PanelGl::InPanels));
    QVERIFY(waitSettled(review, review.status().framesShown + 1));
    QVERIFY(!review.silhouettePanel().usesGl()); // L runs on the worker's context
    QVERIFY(review.statusText().contains(" L (16-cell bricks)"));
}

void ReviewTest::camerasAreLinked() {
    ReviewWidget review(phantomSource("phantom:64", 300.5), settingsFor(3, Chunking::Off));
    review.resize(900, 600);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    const QImage isoBefore = review.isoPanel().grabImage();
    const QImage silhouetteBefore = review.silhouettePanel().grabImage();
    // Drag on the iso panel: the silhouette panel must follow.
    ReviewPanel& panel = review.isoPanel();
    const QPoint centre = panel.rect().center();
    QTest::mousePress(&panel, Qt::LeftButton, {}, centre);
    QMouseEvent move(QEvent::MouseMove, QPointF(centre + QPoint(120, 0)),
                     panel.mapToGlobal(QPointF(centre + QPoint(120, 0))), Qt::NoButton,
                     Qt::LeftButton, {});
    QApplication::sendEvent(&panel, &move);
    QTest::mouseRelease(&panel, Qt::LeftButton, {}, centre + QPoint(120, 0));
    QVERIFY(waitSettled(review, review.status().framesShown + 1));
    QVERIFY(review.camera().cameraSetup().azimuthDeg != 0.0);
    QVERIFY(review.isoPanel().grabImage() != isoBefore);
    QVERIFY(review.silhouettePanel().grabImage() != silhouetteBefore);

    review.setStandardView(StandardView::Left);
    QCOMPARE(review.camera().cameraSetup().azimuthDeg, 90.0);
}

// The settings' "Finer triangles" (Auto) splits a coarse grid's cells: the 24^3 phantom's
// mesh comes back finer (each axis split 4 times: some 16 times the triangles) and both panels
// still draw it; switching it off brings the grid's own mesh back.
void ReviewTest::oversamplingRefinesTheMesh() {
    ReviewWidget review(phantomSource("phantom:24", 300.5), settingsFor(3, Chunking::Off));
    review.resize(900, 600);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    const std::size_t asLoaded = review.status().triangles;
    QVERIFY(asLoaded > 100);
    ReviewSettings settings = settingsFor(3, Chunking::Off);
    settings.oversampling = lw::render::Oversampling::Auto;
    review.applySettings(settings);
    QVERIFY(waitSettled(review, review.status().framesShown + 1));
    QVERIFY2(review.errorText().isEmpty(), qPrintable(review.errorText()));
    QVERIFY2(review.status().triangles > 8 * asLoaded,
             qPrintable(QString("%1 vs %2").arg(review.status().triangles).arg(asLoaded)));
    QCOMPARE(review.status().refinement, glm::ivec3(4)); // 23 cells of 39.8 / 128 -> 4 each
    QVERIFY(review.statusText().contains(QString::fromUtf8("voxels split 4×4×4")));
    const QImage silhouette = review.silhouettePanel().grabImage();
    QVERIFY(lw::test::pixelsDifferentFrom(silhouette, Qt::white, 100) > 300);
    review.applySettings(settingsFor(3, Chunking::Off));
    QVERIFY(waitSettled(review, review.status().framesShown + 1));
    QCOMPARE(review.status().triangles, asLoaded);
    QVERIFY(!review.statusText().contains("split"));
}

// The settings' "Suggestive contours" adds the CT phantom's suggestive contours to the
// silhouette panel (drawn on the worker with method 3) and keeps the silhouette's lines.
void ReviewTest::suggestiveContoursAddLines() {
    ReviewWidget review(phantomSource("phantom:64", 300.5), settingsFor(3, Chunking::Off));
    review.resize(900, 600);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    const QImage plain = review.silhouettePanel().grabImage();
    ReviewSettings settings = settingsFor(3, Chunking::Off);
    settings.suggestiveContours = true;
    review.applySettings(settings);
    QVERIFY(waitSettled(review, review.status().framesShown + 1));
    const QImage with = review.silhouettePanel().grabImage();
    QCOMPARE(with.size(), plain.size());
    int kept = 0, lines = 0, added = 0;
    for (int y = 0; y < plain.height(); ++y)
        for (int x = 0; x < plain.width(); ++x) {
            const bool inPlain = qGray(plain.pixel(x, y)) < 128;
            const bool inWith = qGray(with.pixel(x, y)) < 128;
            lines += inPlain;
            kept += inPlain && inWith;
            added += inWith && !inPlain;
        }
    QVERIFY(lines > 300);
    QCOMPARE(kept, lines);
    QVERIFY2(added > 100, qPrintable(QString::number(added)));
}

void ReviewTest::panelsReRenderAtAnySize() {
    for (auto [method, panelGl] :
         {std::pair{1, PanelGl::InPanels}, std::pair{3, PanelGl::InPanels},
          std::pair{1, PanelGl::OnWorker}, std::pair{3, PanelGl::OnWorker}}) {
        ReviewWidget review(phantomSource("phantom:64", 300.5),
                            settingsFor(method, Chunking::Off, panelGl));
        review.resize(800, 500);
        review.show();
        QVERIFY(QTest::qWaitForWindowExposed(&review));
        QVERIFY(waitSettled(review));
        QImage iso, silhouette;
        try {
            std::tie(iso, silhouette) = review.renderPanels(QSize(1234, 567));
        } catch (const std::exception& error) {
            QFAIL(error.what());
        }
        QCOMPARE(iso.size(), QSize(1234, 567));
        QCOMPARE(silhouette.size(), QSize(1234, 567));
        QVERIFY(lw::test::pixelsDifferentFrom(iso, Qt::white) > 1234 * 567 / 50);
        QVERIFY(lw::test::pixelsDifferentFrom(silhouette, Qt::white, 100) > 500);
    }
}

void ReviewTest::pickingFindsTheSphereSurface_data() {
    QTest::addColumn<int>("panelGl");
    QTest::addRow("GL in panels") << int(PanelGl::InPanels);
    QTest::addRow("GL on worker") << int(PanelGl::OnWorker);
}

void ReviewTest::pickingFindsTheSphereSurface() {
    // The sphere phantom: iso 0 HU at 0.6 of the half-extent, 1 mm voxels around the origin.
    const int n = 64;
    const double radius = 0.6 * (n - 1) / 2.0;
    QFETCH(int, panelGl);
    ReviewWidget review(phantomSource(QString("phantom:%1:sphere").arg(n), 0.0),
                        settingsFor(3, Chunking::Off, PanelGl(panelGl)));
    review.resize(800, 500);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    ReviewPanel& panel = review.isoPanel();
    const QPoint centre = panel.rect().center();
    for (QPoint offset : {QPoint(0, 0), QPoint(40, -30), QPoint(-30, 15)}) {
        const auto point = panel.pickPatientPoint(centre + offset);
        QVERIFY(point.has_value());
        QVERIFY2(std::abs(glm::length(*point) - radius) < 0.3,
                 qPrintable(QString::number(glm::length(*point))));
        QVERIFY(point->y < 0.0); // the anterior half faces the viewer
    }
    QVERIFY(!panel.pickPatientPoint(QPoint(2, 2)).has_value()); // background
}

void ReviewTest::windowMatchesBaseline() {
    ReviewWidget review(phantomSource("phantom:64", 300.5), settingsFor(3, Chunking::Off));
    review.resize(1000, 640);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    review.setStandardView(StandardView::Anterior);
    QVERIFY(waitSettled(review, review.status().framesShown + 1));
    // The frame's status text may have asked for a new layout: apply it, as the screen would
    // before showing the frame (grab paints the widgets where they are now).
    QCoreApplication::sendPostedEvents(nullptr, QEvent::LayoutRequest);
    // The whole review as the user sees it; the status line's timings change from run to run,
    // so its text is blanked out before comparing.
    QImage shot = review.grab().toImage().convertToFormat(QImage::Format_RGB32);
    auto* status = review.findChild<QLabel*>("reviewStatus");
    QVERIFY(status);
    QPainter painter(&shot);
    painter.fillRect(QRect(status->mapTo(&review, QPoint(0, 0)), status->size()), Qt::white);
    // QWidget::grab misses what a QOpenGLWidget paints with QPainter over GL; take each panel's
    // framebuffer as the screen shows it.
    for (ReviewPanel* panel : {&review.isoPanel(), &review.silhouettePanel()})
        painter.drawImage(panel->mapTo(&review, QPoint(0, 0)), panel->grabImage());
    painter.end();
    QCOMPARE(shot.size(), QSize(1000, 640));

    const std::filesystem::path baseline =
        std::filesystem::path(lw::test::sourcePath().toStdString()) /
        "tests/gui/baselines/review_phantom64_method3.png";
    const std::filesystem::path diff =
        std::filesystem::current_path() / "review_phantom64_method3.diff.png";
    QVERIFY(lw::test::pixelsDifferentFrom(shot, Qt::white) > shot.width() * shot.height() / 20);
    // Tolerance relative to the content (what is not the window's background): 1.2 % of it may
    // differ by more than 24 levels (llvmpipe rasterises a shared edge either way depending on
    // thread tiling), and half of it must be there.
    const lw::core::ContentTolerance tolerance{24, 0.012, 0.5};
    const auto comparison =
        lw::core::compareWithBaseline(lw::gui::toCoreImage(shot), baseline, tolerance, diff);
    QVERIFY2(comparison.matches, comparison.describe().c_str());
    if (comparison.baselineWritten)
        QSKIP(comparison.describe().c_str());
}

void ReviewTest::hoverShowsThePatientPosition() {
    // The sphere phantom seen from the front (anterior): the point under the centre of the iso
    // panel lies on the sphere's front, at y = -radius (anterior) and x, z near 0.
    ReviewWidget review(phantomSource("phantom:64:sphere", 0.0), settingsFor(3, Chunking::Off));
    review.resize(800, 500);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    auto* cursor = review.findChild<QLabel*>("cursorPosition");
    QVERIFY(cursor);
    // Synthetic moves, not QTest::mouseMove: that warps the real pointer, which another test's
    // window on the same X server may be under when tests run in parallel.
    const auto hover = [&](QPoint at) {
        QMouseEvent move(QEvent::MouseMove, QPointF(at), review.isoPanel().mapToGlobal(QPointF(at)),
                         Qt::NoButton, Qt::NoButton, {});
        QApplication::sendEvent(&review.isoPanel(), &move);
    };
    hover(review.isoPanel().rect().center());
    QTRY_VERIFY_WITH_TIMEOUT(!cursor->text().isEmpty(), 3000);
    QVERIFY2(cursor->text().contains("A 18.") || cursor->text().contains("A 19."),
             qPrintable(cursor->text()));
    hover(QPoint(3, 3)); // background: no surface there
    QTRY_VERIFY_WITH_TIMEOUT(cursor->text().isEmpty(), 3000);
}

// The silhouette panel's GL view draws a lines texture (what method 3 on CUDA writes on the
// GPU machine) as it draws the host mask's image: flipped right, antialiased strokes of the line
// width, in the line and background colours. Here the texture comes from the test.
void ReviewTest::linesTextureDrawsAsTheHostImage() {
    ReviewSettings settings = settingsFor(3, Chunking::Off, PanelGl::InPanels);
    settings.lineWidth = 3.0;
    settings.lineColour = QColor(200, 30, 60);
    settings.background = QColor(20, 40, 90);
    ReviewWidget review(phantomSource("phantom:48", 300.5), settings);
    review.resize(700, 420);
    review.show();
    QVERIFY(QTest::qWaitForWindowExposed(&review));
    QVERIFY(waitSettled(review));
    ReviewPanel& panel = review.silhouettePanel();
    QVERIFY(panel.hasGlView());
    auto* view = panel.findChild<QOpenGLWidget*>();
    QVERIFY(view);
    const QSize size = panel.renderSize();
    lw::render::PixelMask mask(size.width(), size.height());
    for (int x = 0; x < size.width(); ++x) // a diagonal, a row near the top, the corners
        mask.set(x, std::min(size.height() - 1, x * size.height() / size.width()));
    for (int x = 10; x < size.width() - 10; ++x)
        mask.set(x, 3);
    mask.set(0, 0);
    mask.set(size.width() - 1, size.height() - 1);

    view->makeCurrent(); // the panel's context shares its textures with the worker's
    QOpenGLFunctions* f = view->context()->functions();
    GLuint texture = 0;
    f->glGenTextures(1, &texture);
    f->glBindTexture(GL_TEXTURE_2D, texture);
    f->glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    f->glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, size.width(), size.height(), 0, GL_RED,
                    GL_UNSIGNED_BYTE, mask.pixels().data());
    f->glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    // One level, as render::GlFrameTarget makes it: without mipmaps the default filter would
    // leave the texture incomplete.
    f->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    f->glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    f->glBindTexture(GL_TEXTURE_2D, 0);
    view->doneCurrent();
    panel.setImage({});
    panel.setLinesTexture(
        std::make_shared<const LinesTexture>(LinesTexture{texture, size.width(), size.height()}));
    QVERIFY(panel.showsLinesTexture());
    const QImage shown = panel.grabImage().convertToFormat(QImage::Format_RGB32);
    const QImage expected = linesToImage(mask, settings, false, settings.lineWidth)
                                .convertToFormat(QImage::Format_RGB32);
    panel.setLinesTexture(nullptr);
    view->makeCurrent();
    f->glDeleteTextures(1, &texture);
    view->doneCurrent();
    QCOMPARE(shown.size(), expected.size());
    // The shader blends in float, the host in bytes: a level of rounding apart at most.
    int differing = 0, blended = 0;
    for (int y = 0; y < shown.height(); ++y)
        for (int x = 0; x < shown.width(); ++x) {
            const QRgb a = shown.pixel(x, y), b = expected.pixel(x, y);
            differing += std::abs(qRed(a) - qRed(b)) > 1 || std::abs(qGreen(a) - qGreen(b)) > 1 ||
                         std::abs(qBlue(a) - qBlue(b)) > 1;
            blended += b != settings.lineColour.rgb() && b != settings.background.rgb();
        }
    QCOMPARE(differing, 0);
    QVERIFY2(blended > size.width(), "a 3-pixel stroke has antialiased edges");
}

// The worker's texture slots: a slot held by a result or the panel is never written again until
// let go; a size change makes a new texture; with every slot held the frame gets none (it then
// takes the host path). The textures live in Qt's share group, so the panels' contexts see them,
// and they are gone once the slots are destroyed.
void ReviewTest::silhouetteTexturesAreNeverHandedOutTwice() {
    QOpenGLContext* global = QOpenGLContext::globalShareContext();
    QVERIFY2(global, "requestCoreProfileFormat() shares every context with Qt's global one");
    QOffscreenSurface surface;
    surface.setFormat(global->format());
    surface.create();
    auto owned = std::make_unique<SilhouetteTextures>(&surface);
    SilhouetteTextures& textures = *owned;
    std::shared_ptr<const LinesTexture> held[3];
    lw::render::GlFrameTarget* targets[3] = {};
    for (int i = 0; i < 3; ++i) {
        targets[i] = textures.acquire(64, 48, held[i]);
        QVERIFY(targets[i]);
        QVERIFY(held[i]);
        QCOMPARE(held[i]->texture, targets[i]->texture());
        QCOMPARE(targets[i]->width(), 64);
        for (int j = 0; j < i; ++j)
            QVERIFY(held[j]->texture != held[i]->texture);
    }
    std::shared_ptr<const LinesTexture> none;
    QVERIFY(!textures.acquire(64, 48, none));
    QVERIFY(!none);
    const unsigned second = held[1]->texture;
    held[1].reset(); // the panel let go of it
    std::shared_ptr<const LinesTexture> again;
    QCOMPARE(textures.acquire(64, 48, again), targets[1]);
    QCOMPARE(again->texture, second);
    textures.done();
    again.reset();
    std::shared_ptr<const LinesTexture> resized;
    lw::render::GlFrameTarget* bigger = textures.acquire(80, 60, resized);
    QVERIFY(bigger);
    QCOMPARE(bigger->width(), 80);
    QCOMPARE(resized->height, 60);
    const unsigned name = resized->texture;
    textures.done();
    QOpenGLContext other; // e.g. a panel's
    other.setShareContext(global);
    other.setFormat(global->format());
    QVERIFY(other.create());
    QVERIFY(other.makeCurrent(&surface));
    QVERIFY(other.functions()->glIsTexture(name));
    other.doneCurrent();
    owned.reset();
    QVERIFY(other.makeCurrent(&surface));
    QVERIFY(!other.functions()->glIsTexture(name));
    other.doneCurrent();
}

void ReviewTest::loaderReportsPhantomProgress_data() {
    QTest::addColumn<QString>("path");
    QTest::addColumn<int>("slices");
    QTest::addRow("ct, 96 slices") << "phantom:64x64x96" << 96;
    QTest::addRow("sphere, 300 slices") << "phantom:40x48x300:sphere" << 300;
}

// The progress bar moves between 0 and 1 while the phantom is generated, never backwards.
void ReviewTest::loaderReportsPhantomProgress() {
    QFETCH(QString, path);
    QFETCH(int, slices);
    VolumeLoader loader;
    QList<double> fractions;
    std::shared_ptr<ReviewSource> source;
    connect(&loader, &VolumeLoader::progress, &loader,
            [&](double fraction, const QString&) { fractions.append(fraction); });
    connect(&loader, &VolumeLoader::loaded, &loader,
            [&](std::shared_ptr<ReviewSource> loaded) { source = std::move(loaded); });
    loader.start({path, {}, {}, 300.5});
    QTRY_VERIFY_WITH_TIMEOUT(source != nullptr, 60000);
    QVERIFY(!loader.isRunning());
    QCOMPARE(source->volume->dims().z, slices);
    QVERIFY(std::is_sorted(fractions.begin(), fractions.end()));
    // The phantom steps once per slice; the loader passes on each new whole percent.
    std::set<int> percents;
    for (int slice = 1; slice < slices; ++slice)
        percents.insert(int(double(slice) / double(slices) * 100.0));
    const auto between = std::count_if(fractions.begin(), fractions.end(),
                                       [](double f) { return f > 0.0 && f < 1.0; });
    QCOMPARE(int(between), int(percents.size()));
    QCOMPARE(fractions.last(), 1.0);
}

// Cancel at the first step: the load ends with `cancelled` and `discarded`, never with a volume
// or an error.
void ReviewTest::cancelEndsThePhantomLoadWithoutAVolume() {
    VolumeLoader loader;
    int cancelled = 0, loaded = 0, failed = 0, discarded = 0;
    connect(&loader, &VolumeLoader::progress, &loader, [&](double fraction, const QString&) {
        if (fraction > 0.0 && loader.isRunning())
            loader.cancel();
    });
    connect(&loader, &VolumeLoader::cancelled, &loader, [&] { ++cancelled; });
    connect(&loader, &VolumeLoader::loaded, &loader, [&] { ++loaded; });
    connect(&loader, &VolumeLoader::failed, &loader, [&] { ++failed; });
    connect(&loader, &VolumeLoader::discarded, &loader, [&] { ++discarded; });
    loader.start({"phantom:128x128x512", {}, {}, 300.5});
    QTRY_COMPARE_WITH_TIMEOUT(discarded, 1, 60000);
    QCOMPARE(cancelled, 1);
    QCOMPARE(loaded, 0);
    QCOMPARE(failed, 0);
    QVERIFY(!loader.isRunning());
}

// A load hands its volume over only once the window's GPU probe (LoadRequest::gpuProbe) has
// ended, and says that it waits: the review asks for the device on the UI thread at once, where
// the probe's CUDA context would block it.
void ReviewTest::loaderWaitsForTheGpuProbe() {
    VolumeLoader loader;
    std::promise<void> probe;
    bool probeEnded = false;
    const auto endProbe = qScopeGuard([&] { // a failed check must not leave the loader waiting
        if (!probeEnded)
            probe.set_value();
    });
    LoadRequest request{"phantom:24", {}, {}, 300.5};
    request.gpuProbe = probe.get_future().share();
    bool waiting = false;
    std::shared_ptr<ReviewSource> source;
    connect(&loader, &VolumeLoader::progress, &loader, [&](double, const QString& message) {
        waiting = waiting || message == QLatin1String(kWaitingForGpu);
    });
    connect(&loader, &VolumeLoader::loaded, &loader,
            [&](std::shared_ptr<ReviewSource> loaded) { source = std::move(loaded); });
    loader.start(request);
    QTRY_VERIFY_WITH_TIMEOUT(waiting, 60000);
    QVERIFY(source == nullptr); // posted only after the wait, which has not ended
    QVERIFY(loader.isRunning());
    probe.set_value();
    probeEnded = true;
    QTRY_VERIFY_WITH_TIMEOUT(source != nullptr, 60000);
    QCOMPARE(source->volume->dims().z, 24);
}

LW_GUI_TEST_MAIN(ReviewTest)
#include "review_test.moc"
