#include "review/review_widget.h"

#include "annotate/annotation_actions.h"
#include "annotate/annotation_document.h"
#include "annotate/annotation_tool_controller.h"
#include "lw/core/error.h"
#include "lw/render/gl_context.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/silhouette_methods.h"
#include "lw/render/surface_picking.h"
#include "lw/volume/oversampling.h"
#include "review/iso_control.h"
#include "review/panel_render_job.h"
#include "review/render_scheduler.h"
#include "review/review_arrangement.h"
#include "review/review_panel.h"
#include "review/slice_image.h"
#include "review/slice_views.h"

#include <QApplication>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLocale>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QPainter>
#include <QSettings>
#include <QSignalBlocker>
#include <QToolButton>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>
#include <cstring>

namespace lw::gui {
namespace {

QString patientPositionText(glm::dvec3 p) {
    return QObject::tr("Surface at %1").arg(patientPointText(p));
}

const char* const kErrorStyle = "QLabel { background: #f8d7da; color: #721c24; padding: 4px; }";

QString navigationHint() {
    return QObject::tr("Drag: rotate · Shift/middle drag: pan · wheel/right drag: zoom · "
                       "Ctrl drag: roll · Shift+click: linked cursor");
}

QString count(std::size_t value) {
    return QLocale().toString(qulonglong(value));
}

QString ms(double value) {
    return QString::number(value, 'f', value < 10.0 ? 1 : 0);
}

} // namespace

ReviewWidget::ReviewWidget(ReviewSource source, const ReviewSettings& settings, QWidget* parent)
    : QWidget(parent), m_source(std::move(source)), m_settings(settings) {
    setObjectName("reviewWidget");
    displayGlInfo(); // probe the display's GL now, not from inside a panel's paint
    m_camera.setBounds(m_source.bounds);
    m_camera.setProjection(settings.projection);
    setUpAnnotations();
    buildSlices();
    buildLayout();
    m_scheduler = std::make_unique<RenderScheduler>(m_source.volume);
    connectParts();
    m_isoControl->setVolumeRange(m_source.range, m_source.histogram);
    m_isoControl->setPresets(settings.presets);
    {
        // The first frame is requested once, by applySettings, at the initial iso-value.
        const QSignalBlocker blocker(m_isoControl);
        m_isoControl->setIso(m_source.initialIso);
    }
    m_iso = m_isoControl->iso();
    m_slices->setIso(m_iso);
    applySettings(settings);
}

void ReviewWidget::setUpAnnotations() {
    m_isoPanel = new ReviewPanel(PanelKind::Iso, m_camera);
    m_silhouettePanel = new ReviewPanel(PanelKind::Silhouette, m_camera);
    m_annotations = new AnnotationDocument(this);
    m_annotationTools = new AnnotationToolController(
        *m_annotations,
        [this](ReviewPanel& panel, QPoint position) { return pickSurface(panel, position); }, this);
    m_annotationTools->attach(*m_isoPanel);
    m_annotationTools->attach(*m_silhouettePanel);
    m_annotationActions = new AnnotationActions(*m_annotationTools, *this);
}

std::optional<glm::dvec3> ReviewWidget::pickSurface(ReviewPanel& panel, QPoint position) {
    if (&panel == m_isoPanel)
        return m_isoPanel->pickPatientPoint(position);
    // The silhouette panel keeps no depth of its own. The iso pass's depth at the same camera
    // where the panels are of one size (the device path holds no host mesh), else a ray against
    // the mesh both panels show.
    if (!m_mesh && m_isoPanel->renderSize() == panel.renderSize())
        return m_isoPanel->pickPatientPoint(position);
    if (!m_mesh || !m_meshCurrent)
        return std::nullopt;
    return render::pickMeshSurface(*m_mesh, panel.viewCamera(),
                                   panel.cameraPixel(QPointF(position) + QPointF(0.5, 0.5)));
}

void ReviewWidget::buildSlices() {
    QString unit = m_source.valueUnit;
    if (unit.isEmpty())
        unit = valueUnit(
            m_source.dicom ? QString::fromStdString(m_source.dicom->modality) : QString(), false);
    m_slices = new SliceViews(m_source.volume, unit, this);
    m_slices->setIso(m_source.initialIso);
    for (const volume::SliceOrientation orientation :
         {volume::SliceOrientation::Axial, volume::SliceOrientation::Coronal,
          volume::SliceOrientation::Sagittal})
        m_annotationTools->attach(m_slices->view(orientation));
    m_arrangement = new ReviewArrangement(*m_isoPanel, *m_silhouettePanel, *m_slices, this);
    QSettings store;
    m_arrangement->apply(ReviewLayoutChoice::load(store));
    connect(m_arrangement, &ReviewArrangement::changed, this, [](ReviewLayoutChoice choice) {
        QSettings store;
        choice.save(store);
    });
    connect(m_slices, &SliceViews::linkRequested, this, &ReviewWidget::linkCursorTo);
    for (ReviewPanel* panel : {m_isoPanel, m_silhouettePanel})
        panel->installEventFilter(this);
}

ReviewLayoutChoice ReviewWidget::layoutChoice() const {
    return m_arrangement->choice();
}

void ReviewWidget::setLayoutChoice(ReviewLayoutChoice choice) {
    m_arrangement->apply(choice);
}

void ReviewWidget::linkCursorTo(glm::dvec3 patient) {
    m_slices->linkTo(patient);
    m_isoPanel->setCrossHair(patient);
    m_silhouettePanel->setCrossHair(patient);
    m_cursorLine->setText(tr("Linked cursor at %1").arg(patientPointText(patient)));
}

// Shift+click (press and release in place) on a 3D panel: the linked cursor at the surface
// point. The press and the moves still reach the panel, so Shift+drag pans as before.
bool ReviewWidget::eventFilter(QObject* watched, QEvent* event) {
    auto* panel = qobject_cast<ReviewPanel*>(watched);
    if (!panel ||
        (event->type() != QEvent::MouseButtonPress && event->type() != QEvent::MouseButtonRelease))
        return QWidget::eventFilter(watched, event);
    const auto& mouse = static_cast<QMouseEvent&>(*event);
    const QPoint position = mouse.position().toPoint();
    if (event->type() == QEvent::MouseButtonPress) {
        const bool shiftClick =
            mouse.button() == Qt::LeftButton && mouse.modifiers() == Qt::ShiftModifier;
        m_shiftPress = shiftClick ? std::optional(position) : std::nullopt;
        return false;
    }
    if (mouse.button() == Qt::LeftButton && m_shiftPress &&
        (position - *m_shiftPress).manhattanLength() < QApplication::startDragDistance()) {
        if (const std::optional<glm::dvec3> point = pickSurface(*panel, position))
            linkCursorTo(*point);
        else
            m_hintLine->setText(tr("No surface under the pointer: Shift+click on the surface"));
    }
    m_shiftPress.reset();
    return false;
}

void ReviewWidget::buildLayout() {
    m_isoControl = new IsoControl;
    m_isoControl->setObjectName("isoControl");
    m_statusLine = new QLabel;
    m_statusLine->setObjectName("reviewStatus");
    m_statusLine->setTextInteractionFlags(Qt::TextSelectableByMouse);
    // A long status must not widen the window: it is cut at the window's edge instead.
    m_statusLine->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    m_errorLine = new QLabel;
    m_errorLine->setObjectName("reviewError");
    m_errorLine->setWordWrap(true);
    m_errorLine->setStyleSheet(kErrorStyle);
    m_errorLine->hide();
    m_storageLine = new QLabel;
    m_storageLine->setObjectName("reviewStorageProblem");
    m_storageLine->setWordWrap(true);
    m_storageLine->setStyleSheet(kErrorStyle);
    m_storageLine->hide();
    m_warningLine = new QLabel(m_source.warnings.join(QStringLiteral(" · ")));
    m_warningLine->setObjectName("reviewWarnings");
    m_warningLine->setWordWrap(true);
    m_warningLine->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    m_warningLine->setStyleSheet("QLabel { background: #fff3cd; color: #856404; padding: 4px; }");
    m_warningLine->setVisible(!m_source.warnings.isEmpty());

    auto* layout = new QVBoxLayout(this);
    layout->addWidget(makeViewBar());
    layout->addWidget(m_warningLine);
    layout->addWidget(m_errorLine);
    layout->addWidget(m_storageLine);
    layout->addWidget(m_arrangement->widget(), 1);
    layout->addWidget(m_isoControl);
    layout->addWidget(m_statusLine);
}

void ReviewWidget::connectParts() {
    connect(m_scheduler.get(), &RenderScheduler::frameReady, this, &ReviewWidget::takeFrame);
    // Until the first picture for an iso-value or settings arrives the panels say what is coming
    // rather than stay blank (a 512^3 volume takes seconds on the CPU).
    connect(m_scheduler.get(), &RenderScheduler::busyChanged, this, [this](bool busy) {
        if (busy && !m_meshCurrent) {
            const QString working = tr("Rendering the surface at %1 HU…").arg(m_iso);
            if (!m_isoPanel->hasMesh())
                m_isoPanel->setMessage(working);
            if (!m_silhouettePanel->hasMesh())
                m_silhouettePanel->setMessage(working);
        }
    });
    connect(&m_camera, &CameraController::changed, this, [this] { requestFrame(false); });
    connect(m_isoControl, &IsoControl::isoChanged, this, &ReviewWidget::setIso);
    for (ReviewPanel* panel : {m_isoPanel, m_silhouettePanel}) {
        connect(panel, &ReviewPanel::glFailed, this, &ReviewWidget::showError);
        connect(panel, &ReviewPanel::resized, this, [this] { requestFrame(false); });
        connect(panel, &ReviewPanel::hovered, this, [this](std::optional<glm::dvec3> point) {
            m_cursorLine->setText(point ? patientPositionText(*point) : QString());
        });
        connect(panel, &ReviewPanel::painted, this, [this, panel](double milliseconds) {
            if (!m_drawsInPanels || (panel == m_isoPanel && m_isoOnDevice))
                return; // the worker's GL time is what counts, and it came with the result
            (panel == m_isoPanel ? m_status.isoPaintMs : m_status.silhouettePaintMs) = milliseconds;
            if (panel == m_silhouettePanel && methodOneInPanel())
                m_status.segments = panel->lastSegmentCount();
            updateStatusLine();
        });
    }
}

ReviewWidget::~ReviewWidget() = default;

QWidget* ReviewWidget::makeViewBar() {
    auto* bar = new QWidget;
    auto* layout = new QHBoxLayout(bar);
    layout->setContentsMargins(0, 0, 0, 0);
    const std::pair<StandardView, QString> views[] = {
        {StandardView::Anterior, tr("A")}, {StandardView::Posterior, tr("P")},
        {StandardView::Left, tr("L")},     {StandardView::Right, tr("R")},
        {StandardView::Superior, tr("S")}, {StandardView::Inferior, tr("I")}};
    const QStringList names{tr("Anterior"), tr("Posterior"), tr("Left"),
                            tr("Right"),    tr("Superior"),  tr("Inferior")};
    for (const auto& [view, label] : views) {
        auto* button = new QToolButton;
        button->setText(label);
        button->setToolTip(tr("%1 view").arg(names[int(view)]));
        button->setObjectName("view" + names[int(view)]);
        connect(button, &QToolButton::clicked, this,
                [this, view = view] { setStandardView(view); });
        layout->addWidget(button);
    }
    auto* reset = new QToolButton;
    reset->setText(tr("Reset"));
    reset->setToolTip(tr("Reset the camera (Home)"));
    connect(reset, &QToolButton::clicked, this, &ReviewWidget::resetCamera);
    layout->addWidget(reset);
    addToolButtons(*layout);
    layout->addItem(new QSpacerItem(16, 1));
    layout->addWidget(m_arrangement->makeLayoutButton(*this));
    layout->addWidget(m_arrangement->makeWindowChooser());
    m_cursorLine = new QLabel;
    m_cursorLine->setObjectName("cursorPosition");
    m_cursorLine->setMinimumWidth(260);
    layout->addWidget(m_cursorLine);
    m_hintLine = new QLabel(navigationHint());
    m_hintLine->setObjectName("reviewHint");
    m_hintLine->setEnabled(false);
    // Like the status line: a long hint is cut at the window's edge rather than widen it.
    m_hintLine->setSizePolicy(QSizePolicy::Ignored, QSizePolicy::Preferred);
    layout->addWidget(m_hintLine, 1);
    // With a tool the line says what to click next; a refused click says why.
    connect(m_annotationTools, &AnnotationToolController::promptChanged, this,
            [this](const QString& prompt) {
                m_hintLine->setText(prompt.isEmpty() ? navigationHint() : prompt);
                m_hintLine->setEnabled(!prompt.isEmpty());
            });
    connect(m_annotationTools, &AnnotationToolController::refused, this,
            [this](const QString& reason) {
                m_hintLine->setText(reason);
                m_hintLine->setEnabled(true);
            });
    return bar;
}

void ReviewWidget::addToolButtons(QLayout& layout) {
    layout.addItem(new QSpacerItem(16, 1));
    for (QAction* action : m_annotationActions->toolActions()) {
        auto* button = new QToolButton;
        button->setDefaultAction(action);
        button->setObjectName(action->objectName() + "Button");
        layout.addWidget(button);
    }
}

bool ReviewWidget::drawsInPanels() const {
    switch (m_settings.panelGl) {
    case PanelGl::InPanels:
        return true;
    case PanelGl::OnWorker:
        return false;
    case PanelGl::Auto:
        break;
    }
    // Where CUDA draws both panels (the iso panel shaded from the device's surface, the lines
    // as a host image), the panels need no GL of their own: a window without a QOpenGLWidget
    // repaints only the panels' rectangles, where one with it composes and flushes the whole
    // window through GL on every update (7-15 ms a flush through Xvfb or a remote desktop,
    // 1 ms without). Method 1 then runs on the worker's own headless context.
    if (m_settings.cudaShadesIsoPanel && render::reviewIsoOnDevice(m_settings.backend))
        return false;
    return !displayGlInfo().prefersCpu();
}

bool ReviewWidget::methodOneInPanel() const {
    return m_settings.method == render::SilhouetteMethod::GeometryShader && brickCells() == 0 &&
           m_drawsInPanels && !m_isoOnDevice;
}

// Of the volume the worker draws: the oversampled copy where the settings make one.
int ReviewWidget::brickCells() const {
    const volume::Volume& loaded = *m_source.volume;
    const glm::ivec3 drawn = volume::oversampledDims(
        loaded.dims(),
        render::samplingPlan(loaded.dims(), loaded.geometry(), m_settings.volumeSampling())
            .factors);
    const std::size_t bytes = std::size_t(drawn.x) * std::size_t(drawn.y) * std::size_t(drawn.z) *
                              volume::voxelSize(loaded.voxelType());
    return m_settings.brickCellsFor(drawn, bytes);
}

bool ReviewWidget::isBusy() const {
    return m_scheduler->isBusy();
}

void ReviewWidget::applySettings(const ReviewSettings& settings) {
    m_settings = settings;
    ++m_settingsGeneration;
    m_camera.setProjection(settings.projection);
    m_isoPanel->setAppearance(settings);
    m_silhouettePanel->setAppearance(settings);
    m_drawsInPanels = drawsInPanels();
    // The worker shades the iso panel from the device's surface on CUDA: by CUDA's rasterizer
    // whatever the display's GL (a GPU server seen through a software-GL remote desktop too), or
    // with the worker's GL where that is a real GPU's.
    m_isoOnDevice =
        render::reviewIsoOnDevice(settings.backend) &&
        (m_drawsInPanels || settings.cudaShadesIsoPanel || !displayGlInfo().prefersCpu());
    m_isoPanel->setGlView(m_drawsInPanels);
    m_silhouettePanel->setGlView(m_drawsInPanels);
    m_isoPanel->setUseGl(m_drawsInPanels && !m_isoOnDevice);
    m_isoPanel->setMesh(nullptr);
    m_silhouettePanel->setMesh(nullptr);
    m_mesh.reset();
    m_silhouettePanel->setUseGl(methodOneInPanel());
    m_silhouettePanel->setImage({});
    m_silhouettePanel->setLinesTexture(nullptr);
    m_isoPanel->setOverlay({});
    m_isoControl->setPresets(settings.presets);
    m_slices->setContourColour(settings.contourColour);
    m_meshCurrent = false; // the new settings' first frame brings the mesh again
    requestFrame(true);
}

void ReviewWidget::setIso(double iso) {
    if (m_isoControl->iso() != iso) {
        m_isoControl->setIso(iso); // comes back through isoChanged
        return;
    }
    m_iso = iso;
    m_meshCurrent = false;
    m_slices->setIso(iso); // every value of a drag: a slice's contour is cheap
    requestFrame(true);
}

void ReviewWidget::setStandardView(StandardView view) {
    m_camera.setStandardView(view);
}

void ReviewWidget::resetCamera() {
    m_camera.reset();
}

void ReviewWidget::requestFrame(bool newIso) {
    if (!m_scheduler)
        return;
    FrameRequest request;
    request.settingsGeneration = m_settingsGeneration;
    render::ReviewFrameRequest& frame = request.frame;
    frame.iso = m_iso;
    frame.method = m_settings.method;
    frame.backend = m_settings.backend;
    frame.settings = m_settings.silhouetteSettings(brickCells(), m_iso);
    frame.sampling = m_settings.volumeSampling();
    frame.wantSilhouette = !methodOneInPanel();
    // Drawn on the worker with the silhouette (CPU); method 1 in the panel's own GL has none yet.
    frame.suggestive = m_settings.suggestiveContours && frame.wantSilhouette;
    // The hidden lines as the exports draw them: the polylines the mask hides, stroked thin,
    // dashed and grey under the visible lines (on the worker, from the host surface).
    const bool hiddenLines =
        m_settings.hiddenLines && m_settings.visibility && frame.wantSilhouette;
    if (hiddenLines) {
        frame.wantPolylines = true;
        frame.hiddenLines = true;
        frame.polylineOptions.minLengthPx = double(m_settings.minStrokePixels);
    }
    // The GL panel draws a texture the worker's CUDA writes; the iso panel's overlay, the
    // suggestive contours (added to the mask on the host) and the hidden lines still need the
    // mask on the host.
    request.silhouetteToTexture = m_drawsInPanels && !m_settings.silhouetteOnIso &&
                                  !frame.suggestive && !hiddenLines &&
                                  render::silhouetteMethodInfo(m_settings.method).drawsToTexture;
    request.sharedGl = m_drawsInPanels;
    request.appearance = m_settings;
    const bool modeB = m_settings.mode == render::ExtractionMode::EveryFrameB;
    // A panel that draws the mesh with its own GL needs it on the host.
    const bool panelsDrawMesh = m_drawsInPanels && !m_isoOnDevice;
    frame.wantMesh = panelsDrawMesh && (newIso || !m_meshCurrent || (modeB && methodOneInPanel()));
    frame.forceExtract = modeB && methodOneInPanel() && !newIso;
    if (!panelsDrawMesh) {
        // The worker draws the iso panel too: every new view and iso-value needs an image.
        frame.wantIsoImage = true;
        const QSize isoSize = m_isoPanel->renderSize();
        frame.isoCamera = m_camera.camera(isoSize.width(), isoSize.height());
        frame.isoOptions =
            panelGlOptions(PanelKind::Iso, m_settings, frame.isoCamera, m_camera.bounds());
        frame.isoOnCpu = displayGlInfo().prefersCpu();
        frame.isoShadedByCuda = m_settings.cudaShadesIsoPanel;
    }
    if (!frame.wantMesh && !frame.wantSilhouette && !frame.wantIsoImage)
        return; // method 1 S in mode a: the panels redraw the cached mesh themselves
    const QSize size = m_silhouettePanel->renderSize();
    frame.camera = m_camera.camera(size.width(), size.height());
    m_scheduler->request(std::move(request));
}

void ReviewWidget::takeFrame(const std::shared_ptr<const FrameResult>& result) {
    // A result for settings already moved on is stale: drop it. One for an older iso-value (the
    // slider dragged on while it ran) or an older camera is still the best picture there is
    // until the newer one arrives: shown, the newest value's frame follows.
    if (result->settingsGeneration != m_settingsGeneration)
        return;
    if (!result->error.isEmpty()) {
        showError(result->error);
        m_isoPanel->setMessage(result->error);
        m_silhouettePanel->setMessage(result->error);
        // A worker that failed may have released its textures (out of memory).
        m_silhouettePanel->setLinesTexture(nullptr);
        return;
    }
    m_errorLine->hide();
    m_status.backend = result->backend.isEmpty() ? QStringLiteral("gl") : result->backend;
    m_status.brickCells = result->brickCells;
    m_status.refinement = result->refinement;
    // The slices contour the surface the panels show: the resampled copy where there is one.
    m_slices->setDrawnSurface(
        result->drawnVolume == m_source.volume ? nullptr : result->drawnVolume, result->iso);
    ++m_status.framesShown;
    m_status.workerMs = result->workerMs;
    m_status.workerStageMs = result->stageMs;
    m_status.requestToTakenMs = std::chrono::duration<double, std::milli>(
                                    std::chrono::steady_clock::now() - result->requested)
                                    .count();
    if (!result->isoImage.isNull()) {
        m_isoPanel->setImage(result->isoImage);
        m_isoPanel->setDepth(result->isoDepth, result->isoCamera);
        m_status.isoPaintMs = result->isoRenderMs;
    }
    if (result->mesh) {
        m_mesh = result->mesh;
        m_isoPanel->setMesh(m_isoOnDevice ? nullptr : result->mesh);
        m_silhouettePanel->setMesh(methodOneInPanel() ? result->mesh : nullptr);
    }
    if (result->surfaceTriangles)
        showSurfaceCounts(*result);
    if (result->silhouette)
        showSilhouette(*result);
    updateStatusLine();
    emit frameShown();
}

// The surface's triangle count (the device's on the device path) and "no surface" where there
// is none.
void ReviewWidget::showSurfaceCounts(const FrameResult& result) {
    if (!result.mesh && m_isoOnDevice)
        m_mesh.reset(); // an older iso-value's host mesh is not what the panels show now
    m_meshCurrent = result.iso == m_iso;
    m_status.triangles = *result.surfaceTriangles;
    m_status.isoShown = result.iso;
    if (result.meshMs > 0.0 || !result.silhouette)
        m_status.extractMs = result.meshMs;
    const bool empty = *result.surfaceTriangles == 0;
    const QString none = tr("No surface at %1 HU").arg(result.iso);
    m_isoPanel->setMessage(empty ? none : QString());
    m_silhouettePanel->setMessage(empty ? none : QString());
}

void ReviewWidget::showSilhouette(const FrameResult& result) {
    const render::SilhouetteFrame& frame = *result.silhouette;
    m_status.segments = frame.segments;
    m_status.silhouetteTimes = frame.times;
    if (!result.surfaceTriangles)
        m_status.triangles = std::max(m_status.triangles, frame.triangles);
    if (result.linesTexture && m_silhouettePanel->hasGlView()) {
        // Method 3 on CUDA wrote the lines into a texture the panel draws: nothing to upload.
        // Such frames are asked for only without the overlay on the iso panel.
        m_silhouettePanel->setLinesTexture(result.linesTexture);
        m_silhouettePanel->setImage({});
        m_isoPanel->setOverlay({});
        return;
    }
    m_silhouettePanel->setLinesTexture(nullptr);
    m_silhouettePanel->setImage(result.silhouetteImage); // drawn on the worker
    m_isoPanel->setOverlay(result.isoOverlay);
}

void ReviewWidget::showError(const QString& message) {
    m_errorLine->setText(message);
    m_errorLine->show();
}

void ReviewWidget::setStorageProblem(const QString& problem) {
    m_storageLine->setText(problem);
    m_storageLine->setVisible(!problem.isEmpty());
}

QString ReviewWidget::storageProblem() const {
    return m_storageLine->isHidden() ? QString() : m_storageLine->text();
}

QString ReviewWidget::errorText() const {
    return m_errorLine->isVisible() ? m_errorLine->text() : QString();
}

QString ReviewWidget::statusText() const {
    const bool chunked = m_status.brickCells > 0;
    const render::StageTimes& t = m_status.silhouetteTimes;
    QString text = tr("Method %1 · %2 · mode %3 · %4")
                       .arg(int(m_settings.method))
                       .arg(chunked ? tr("L (%1-cell bricks)").arg(m_status.brickCells) : tr("S"))
                       .arg(m_settings.mode == render::ExtractionMode::CachedA ? "a" : "b")
                       .arg(m_status.backend.toUpper());
    text += tr(" · marching cubes %1 ms").arg(ms(m_status.extractMs));
    if (methodOneInPanel()) {
        text += tr(" · GL iso %1 ms, silhouette %2 ms")
                    .arg(ms(m_status.isoPaintMs), ms(m_status.silhouettePaintMs));
    } else {
        text += tr(" · silhouette: extract %1, segments %2, visibility %3, draw %4 ms")
                    .arg(ms(t.extractMs), ms(t.silhouetteMs), ms(t.visibilityMs), ms(t.drawMs));
        const bool cpu = displayGlInfo().prefersCpu();
        text += (m_isoOnDevice     ? tr(" · iso shaded from the device's mesh %1 ms")
                 : m_drawsInPanels ? tr(" · GL iso %1 ms")
                 : cpu             ? tr(" · iso shaded on the CPU %1 ms")
                                   : tr(" · GL iso on the worker %1 ms"))
                    .arg(ms(m_status.isoPaintMs));
    }
    text += tr(" · %1 triangles · %2 segments")
                .arg(count(m_status.triangles), count(m_status.segments));
    const glm::ivec3 split = m_status.refinement;
    if (split != glm::ivec3(1))
        text += tr(" · voxels split %1×%2×%3").arg(split.x).arg(split.y).arg(split.z);
    return text;
}

void ReviewWidget::updateStatusLine() {
    m_statusLine->setText(statusText());
    emit statusChanged();
}

namespace {

void releaseQtContext() {
    if (QOpenGLContext* current = QOpenGLContext::currentContext())
        current->doneCurrent();
}

} // namespace

PanelRenderJob ReviewWidget::renderJob(QSize size) const {
    PanelRenderJob job;
    job.volume = m_source.volume;
    job.camera = m_camera.camera(size.width(), size.height());
    job.bounds = m_camera.bounds();
    // Lines keep their width relative to the picture: scaled from the panel on screen.
    job.appearance = m_settings;
    const double scale = double(size.height()) / double(m_silhouettePanel->renderSize().height());
    job.appearance.lineWidth = std::max(1.0, m_settings.lineWidth * scale);
    // A stroke's pixel count grows with the picture's size: the same strokes go as on screen.
    job.appearance.minStrokePixels = int(std::lround(m_settings.minStrokePixels * scale));
    job.iso = m_iso;
    job.brickCells = brickCells();
    job.isoOnCpu = displayGlInfo().prefersCpu();
    if (m_isoOnDevice) // the surface is on the device, in the worker's GL: render it there
        job.renderOnWorker = m_scheduler->panelRenderer();
    return job;
}

bool ReviewWidget::rendersOnUiThread() const {
    return m_drawsInPanels && !m_isoOnDevice;
}

std::pair<QImage, QImage> ReviewWidget::renderPanels(QSize size, PanelVectors* vectors) {
    const PanelRenderJob job = renderJob(size);
    if (!rendersOnUiThread()) {
        releaseQtContext(); // the job may make an EGL context on this thread
        return renderPanelJob(job, vectors);
    }
    // A GPU: the panels' own contexts draw the GL parts; a CPU method renders its lines here.
    // Method 1 in the panel's context: its raster, and its lines as vectors cut by its mask.
    QImage iso = m_isoPanel->renderImage(size, &job.appearance);
    if (methodOneInPanel()) {
        if (vectors) {
            const render::ReviewFrameRequest request = panelFrameRequest(job, true);
            render::PolylineSplit lines = m_silhouettePanel->renderPolylines(
                size, job.appearance, request.polylineOptions,
                request.hiddenLines && request.settings.visibility);
            vectors->lines = std::move(lines.visible);
            vectors->hidden = std::move(lines.hidden);
        }
        return {iso, m_silhouettePanel->renderImage(size, &job.appearance)};
    }
    releaseQtContext();
    auto [unused, silhouette] = renderPanelJob(job, vectors);
    return {iso, silhouette};
}

QImage ReviewWidget::renderSideBySide(QSize panelSize) {
    const auto [iso, silhouette] = renderPanels(panelSize);
    return sideBySide(iso, silhouette, m_settings.background);
}

} // namespace lw::gui
