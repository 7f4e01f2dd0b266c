// The settings page and what it stores, and the linked camera's conversions: settings round-trip
// through QSettings (isolated in a temporary folder), the page reports every change at once and
// keeps CUDA greyed out with the reason where it is missing; the trackball orientation converts
// to the engine's azimuth/elevation/roll exactly, poles included.
#include "gui_test_support.h"
#include "review/camera_controller.h"
#include "settings/review_settings.h"
#include "settings/settings_dialog.h"

#include <QCheckBox>
#include <QComboBox>
#include <QRadioButton>
#include <QSettings>
#include <QSignalSpy>
#include <QSpinBox>
#include <QtTest>

using namespace lw::gui;

class SettingsTest : public QObject {
    Q_OBJECT
private slots:
    void roundTripThroughQSettings_data();
    void roundTripThroughQSettings();
    void brokenValuesFallBackToDefaults();
    void dialogReportsChangesAndStoresThem();
    void cudaIsGreyedOutWithTheReason();
    void autoChunkingFollowsTheBudget();
    void cameraViewsConvertExactly_data();
    void cameraViewsConvertExactly();
    void dragRotatesAboutTheScreenAxes();
};

void SettingsTest::roundTripThroughQSettings_data() {
    QTest::addColumn<int>("method");
    QTest::addColumn<int>("chunking");
    QTest::addColumn<bool>("modeB");
    QTest::addColumn<bool>("ortho");
    QTest::addColumn<int>("panelGl");
    QTest::addRow("defaults") << 3 << int(Chunking::Auto) << false << false << int(PanelGl::Auto);
    QTest::addRow("method 1 L b ortho")
        << 1 << int(Chunking::Fixed) << true << true << int(PanelGl::InPanels);
    QTest::addRow("method 2 S worker")
        << 2 << int(Chunking::Off) << false << false << int(PanelGl::OnWorker);
}

void SettingsTest::roundTripThroughQSettings() {
    QFETCH(int, method);
    QFETCH(int, chunking);
    QFETCH(bool, modeB);
    QFETCH(bool, ortho);
    QFETCH(int, panelGl);
    ReviewSettings settings;
    settings.method = lw::render::SilhouetteMethod(method);
    settings.chunking = Chunking(chunking);
    settings.fixedBrickCells = 48;
    settings.gpuMemoryBudgetMiB = method * 256; // 0 (automatic) is the default: another value
    settings.minStrokePixels = method * 4;
    settings.suggestiveContours = method != 2; // off is the default: both values round-trip
    settings.hiddenLines = method == 3;
    settings.gradientStencil =
        method == 1 ? lw::render::GradientStencil::Smoothed : lw::render::GradientStencil::Central;
    // Auto is the default: both values round-trip.
    settings.oversampling =
        method == 2 ? lw::render::Oversampling::Off : lw::render::Oversampling::Auto;
    // Smooth is the default: both values round-trip.
    settings.thickSlices =
        method == 3 ? lw::render::ThickSlices::Linear : lw::render::ThickSlices::Smooth;
    settings.mode =
        modeB ? lw::render::ExtractionMode::EveryFrameB : lw::render::ExtractionMode::CachedA;
    settings.projection =
        ortho ? lw::render::Projection::Orthographic : lw::render::Projection::Perspective;
    settings.panelGl = PanelGl(panelGl);
    settings.lineColour = QColor(200, 10, 20);
    settings.lineWidth = 2.5;
    settings.presets = {{"Bone", 350.0}, {"Contrast", 150.0}};
    QTemporaryDir dir;
    QSettings store(dir.filePath("settings.ini"), QSettings::IniFormat);
    settings.save(store);
    store.sync();
    QSettings reread(dir.filePath("settings.ini"), QSettings::IniFormat);
    QCOMPARE(ReviewSettings::load(reread), settings);
}

void SettingsTest::brokenValuesFallBackToDefaults() {
    QTemporaryDir dir;
    QSettings store(dir.filePath("settings.ini"), QSettings::IniFormat);
    store.setValue("review/method", 7);
    store.setValue("review/lineColour", "not a colour");
    store.setValue("review/brickCells", "many");
    store.setValue("review/gpuMemoryBudgetMiB", -5);
    const ReviewSettings loaded = ReviewSettings::load(store);
    const ReviewSettings defaults;
    QCOMPARE(int(loaded.method), 3);        // no method 7: the default
    QCOMPARE(loaded.gpuMemoryBudgetMiB, 0); // clamped: automatic
    QCOMPARE(loaded.lineColour, defaults.lineColour);
    QCOMPARE(loaded.fixedBrickCells, defaults.fixedBrickCells);
    QCOMPARE(loaded.presets, ReviewSettings::defaultPresets());
}

void SettingsTest::dialogReportsChangesAndStoresThem() {
    QSettings().clear();
    SettingsDialog dialog{ReviewSettings{}};
    dialog.show();
    QVERIFY(QTest::qWaitForWindowExposed(&dialog));
    QSignalSpy changed(&dialog, &SettingsDialog::settingsChanged);
    auto* method1 = dialog.findChild<QRadioButton*>("method1");
    QVERIFY(method1);
    method1->click();
    QCOMPARE(changed.size(), 1);
    QCOMPARE(int(dialog.settings().method), 1);
    dialog.findChild<QComboBox*>("chunking")->setCurrentIndex(int(Chunking::Fixed));
    QCOMPARE(changed.size(), 2);
    QCOMPARE(dialog.settings().chunking, Chunking::Fixed);
    auto* gpuBudget = dialog.findChild<QSpinBox*>("gpuMemoryBudget");
    QVERIFY(gpuBudget);
    QCOMPARE(gpuBudget->text(), QString("Automatic (free memory less a margin)")); // 0
    gpuBudget->setValue(512);
    QCOMPARE(changed.size(), 3);
    QCOMPARE(dialog.settings().gpuMemoryBudgetMiB, 512);
    auto* minStroke = dialog.findChild<QSpinBox*>("minStroke");
    QVERIFY(minStroke);
    QCOMPARE(minStroke->value(), lw::render::kDefaultMinStrokePixels);
    minStroke->setValue(0);
    QCOMPARE(minStroke->text(), QString("Keep every line pixel"));
    QCOMPARE(dialog.settings().minStrokePixels, 0);
    auto* suggestive = dialog.findChild<QCheckBox*>("suggestive");
    QVERIFY(suggestive);
    QVERIFY(!suggestive->isChecked()); // off by default
    suggestive->click();
    QVERIFY(dialog.settings().suggestiveContours);
    auto* smoothNormals = dialog.findChild<QCheckBox*>("smoothNormals");
    QVERIFY(smoothNormals);
    QVERIFY(!smoothNormals->isChecked()); // central differences by default
    smoothNormals->click();
    QCOMPARE(dialog.settings().gradientStencil, lw::render::GradientStencil::Smoothed);
    auto* oversample = dialog.findChild<QCheckBox*>("oversample");
    QVERIFY(oversample);
    QVERIFY(oversample->isChecked()); // coarse axes split by default
    oversample->click();
    QCOMPARE(dialog.settings().oversampling, lw::render::Oversampling::Off);
    auto* smoothThickSlices = dialog.findChild<QCheckBox*>("smoothThickSlices");
    QVERIFY(smoothThickSlices);
    QVERIFY(smoothThickSlices->isChecked()); // shape-based across thick slices by default
    smoothThickSlices->click();
    QCOMPARE(dialog.settings().thickSlices, lw::render::ThickSlices::Linear);
    auto* hiddenLines = dialog.findChild<QCheckBox*>("hiddenLines");
    QVERIFY(hiddenLines);
    QVERIFY(!hiddenLines->isChecked()); // off by default
    hiddenLines->click();
    QVERIFY(dialog.settings().hiddenLines);
    // Applied live and kept for the next start.
    QSettings store;
    const ReviewSettings stored = ReviewSettings::load(store);
    QCOMPARE(int(stored.method), 1);
    QCOMPARE(stored.chunking, Chunking::Fixed);
    QCOMPARE(stored.gpuMemoryBudgetMiB, 512);
    QCOMPARE(stored.minStrokePixels, 0);
    QVERIFY(stored.suggestiveContours);
    QCOMPARE(stored.gradientStencil, lw::render::GradientStencil::Smoothed);
    QCOMPARE(stored.oversampling, lw::render::Oversampling::Off);
    QCOMPARE(stored.thickSlices, lw::render::ThickSlices::Linear);
    QVERIFY(stored.hiddenLines);
}

void SettingsTest::cudaIsGreyedOutWithTheReason() {
    SettingsDialog dialog{ReviewSettings{}};
    bool cudaBuilt = true;
    try {
        lw::render::resolveBackend(lw::render::Backend::Cuda);
    } catch (const std::exception&) {
        cudaBuilt = false;
    }
    const QList<QRadioButton*> buttons = dialog.findChildren<QRadioButton*>();
    const auto cuda = std::find_if(buttons.begin(), buttons.end(),
                                   [](QRadioButton* b) { return b->text() == "CUDA"; });
    QVERIFY(cuda != buttons.end());
    QCOMPARE((*cuda)->isEnabled(), cudaBuilt);
    if (!cudaBuilt)
        QVERIFY(!(*cuda)->toolTip().isEmpty());
}

void SettingsTest::autoChunkingFollowsTheBudget() {
    ReviewSettings settings;
    settings.chunking = Chunking::Auto;
    settings.memoryBudgetMiB = 256;
    const glm::ivec3 dims(512, 512, 140);
    const std::size_t bytes = std::size_t(512) * 512 * 140 * 2; // 70 MiB
    QCOMPARE(settings.brickCellsFor(dims, bytes), 0);           // fits: whole volume
    settings.memoryBudgetMiB = 100;
    QVERIFY(settings.brickCellsFor(dims, bytes) > 0); // does not: chunked
    settings.chunking = Chunking::Off;
    QCOMPARE(settings.brickCellsFor(dims, bytes), 0);
    settings.chunking = Chunking::Fixed;
    settings.fixedBrickCells = 32;
    QCOMPARE(settings.brickCellsFor(dims, bytes), 32);
}

void SettingsTest::cameraViewsConvertExactly_data() {
    QTest::addColumn<double>("azimuth");
    QTest::addColumn<double>("elevation");
    QTest::addColumn<double>("roll");
    QTest::addRow("anterior") << 0.0 << 0.0 << 0.0;
    QTest::addRow("oblique") << 30.0 << 20.0 << 0.0;
    QTest::addRow("rolled") << -120.0 << -35.0 << 25.0;
    QTest::addRow("superior pole") << 0.0 << 90.0 << 0.0;
    QTest::addRow("inferior pole") << 45.0 << -90.0 << 0.0;
}

void SettingsTest::cameraViewsConvertExactly() {
    QFETCH(double, azimuth);
    QFETCH(double, elevation);
    QFETCH(double, roll);
    CameraController controller;
    controller.setView(azimuth, elevation, roll);
    const lw::render::Camera expected(
        [&] {
            lw::render::CameraSetup setup;
            setup.azimuthDeg = azimuth;
            setup.elevationDeg = elevation;
            setup.rollDeg = roll;
            return setup;
        }(),
        400, 300);
    const lw::render::Camera actual = controller.camera(400, 300);
    for (int i = 0; i < 3; ++i) {
        QVERIFY(std::abs(actual.forward()[i] - expected.forward()[i]) < 1e-9);
        QVERIFY(std::abs(actual.up()[i] - expected.up()[i]) < 1e-9);
    }
}

void SettingsTest::dragRotatesAboutTheScreenAxes() {
    CameraController controller;
    QSignalSpy changed(&controller, &CameraController::changed);
    controller.reset();
    // Dragging right by half the viewport height turns the surface a quarter turn: the camera
    // moves to the patient's right (az -90).
    controller.rotateByDrag(QPointF(150.0, 0.0), QSize(400, 300));
    const lw::render::CameraSetup setup = controller.cameraSetup();
    QVERIFY(std::abs(setup.azimuthDeg + 90.0) < 1e-9);
    QVERIFY(std::abs(setup.elevationDeg) < 1e-9);
    QVERIFY(changed.size() >= 2);
    controller.setStandardView(StandardView::Superior);
    QVERIFY(std::abs(controller.cameraSetup().elevationDeg - 90.0) < 1e-9);
    controller.zoomBy(2.0);
    controller.panByDrag(QPointF(150.0, 0.0), QSize(400, 300));
    QCOMPARE(controller.zoom(), 2.0);
    QVERIFY(std::abs(controller.pan().x + 1.0) < 1e-12);
}

LW_GUI_TEST_MAIN(SettingsTest)
#include "settings_test.moc"
