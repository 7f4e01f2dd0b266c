#pragma once

// The review of one volume: the shaded iso-surface left, its silhouette right, one camera for
// both, the iso-value control below and a status line with what each stage cost. Owns the
// render scheduler (worker thread); the UI thread only uploads, draws and reacts.

#include "lw/input/open_input.h"
#include "lw/render/aabb.h"
#include "lw/render/iso_surface.h"
#include "lw/render/review_frame.h"
#include "lw/volume/volume.h"
#include "review/camera_controller.h"
#include "review/panel_render_job.h"
#include "settings/review_layout.h"
#include "settings/review_settings.h"

#include <QImage>
#include <QStringList>
#include <QWidget>
#include <cstdint>
#include <memory>
#include <optional>

class QLabel;

namespace lw::gui {

class AnnotationActions;
class AnnotationDocument;
class AnnotationToolController;
class IsoControl;
class RenderScheduler;
class ReviewArrangement;
class ReviewPanel;
class SliceViews;
struct FrameResult;

// What a review needs of an opened volume; the loader computes the scans off the UI thread.
struct ReviewSource {
    std::shared_ptr<const volume::Volume> volume;
    QString title;                             // patient / series / dims, for the tab and reports
    QString seriesUid;                         // empty for non-DICOM input
    std::optional<input::DicomIdentity> dicom; // patient / study / series, DICOM only
    QString valueUnit;    // "HU" for CT, otherwise the stored units named (slice_views.h)
    QStringList warnings; // tilt, uneven gaps, missing slices, files that failed
    render::Aabb bounds;  // the surface at the initial iso-value (camera framing)
    volume::ValueRange range;
    volume::Histogram histogram;
    double initialIso = 400.0;
};

// Counts and times of what the panels show now, for the status line and tests.
struct ReviewStatus {
    std::size_t triangles = 0;
    std::size_t segments = 0;
    double isoShown = 0.0; // the iso-value of the mesh on screen
    double extractMs = 0.0;
    render::StageTimes silhouetteTimes;
    double isoPaintMs = 0.0;
    double silhouettePaintMs = 0.0;
    int brickCells = 0;
    glm::ivec3 refinement{1}; // the loaded volume's cells split this many times (oversampling)
    QString backend;
    std::uint64_t framesShown = 0; // results taken from the worker
    // The last result: its time on the worker, and from its request to the UI thread taking it.
    double workerMs = 0.0;
    double requestToTakenMs = 0.0;
    render::ReviewFrame::StageMs workerStageMs; // the engine's part of workerMs
};

class ReviewWidget : public QWidget {
    Q_OBJECT
public:
    ReviewWidget(ReviewSource source, const ReviewSettings& settings, QWidget* parent = nullptr);
    ~ReviewWidget() override;

    const ReviewSource& source() const { return m_source; }
    CameraController& camera() { return m_camera; }
    ReviewPanel& isoPanel() { return *m_isoPanel; }
    ReviewPanel& silhouettePanel() { return *m_silhouettePanel; }
    IsoControl& isoControl() { return *m_isoControl; }
    const ReviewSettings& settings() const { return m_settings; }
    const ReviewStatus& status() const { return m_status; }
    QString statusText() const;
    QString errorText() const;
    double iso() const { return m_iso; }
    AnnotationDocument& annotations() { return *m_annotations; }
    AnnotationToolController& annotationTools() { return *m_annotationTools; }
    AnnotationActions& annotationActions() { return *m_annotationActions; }
    // The iso-surface point under a widget position of either panel (LPS, mm): the iso panel
    // through its depth buffer, the silhouette panel by a ray against the mesh on screen.
    std::optional<glm::dvec3> pickSurface(ReviewPanel& panel, QPoint position);
    SliceViews& slices() { return *m_slices; }
    // The panels' layout (settings/review_layout.h); a new one is remembered in QSettings.
    ReviewLayoutChoice layoutChoice() const;
    void setLayoutChoice(ReviewLayoutChoice choice);
    // The linked cursor at a patient point: the slices move through it and every panel marks it.
    void linkCursorTo(glm::dvec3 patient);
    // True while the worker has work (tests wait for it to settle).
    bool isBusy() const;

    // Both panels re-rendered at `size` (not scaled), the silhouette with the chosen method on
    // the calling thread. Lines widen with the size (a 2x export has 2x wider lines, as printed
    // reports need). Throws core::Error when a renderer fails.
    std::pair<QImage, QImage> renderPanels(QSize size, PanelVectors* vectors = nullptr);
    // The two panels side by side at `panelSize` each (iso left, silhouette right).
    QImage renderSideBySide(QSize panelSize);
    // What an export at `size` needs, copied so renderPanelJob() can run on another thread;
    // valid only where rendersOnUiThread() is false (the panels' GL contexts are not needed).
    PanelRenderJob renderJob(QSize size) const;
    bool rendersOnUiThread() const;

public slots:
    void applySettings(const lw::gui::ReviewSettings& settings);
    void setIso(double iso);
    void setStandardView(lw::gui::StandardView view);
    void resetCamera();
    // A red bar of its own that stays until cleared with an empty text: what the study database
    // could not load or save (unlike render errors, a new frame does not make it go away).
    void setStorageProblem(const QString& problem);
    QString storageProblem() const;

signals:
    void statusChanged();
    void frameShown();

protected:
    bool eventFilter(QObject* watched, QEvent* event) override;

private:
    void buildLayout();
    void buildSlices();
    void connectParts();
    QWidget* makeViewBar();
    void requestFrame(bool newIso);
    void takeFrame(const std::shared_ptr<const FrameResult>& result);
    void showSilhouette(const FrameResult& result);
    void showSurfaceCounts(const FrameResult& result);
    void showError(const QString& message);
    void updateStatusLine();
    void setUpAnnotations();
    void addToolButtons(QLayout& layout);
    bool methodOneInPanel() const;
    bool drawsInPanels() const;
    int brickCells() const;

    ReviewSource m_source;
    ReviewSettings m_settings;
    std::uint64_t m_settingsGeneration = 1;
    double m_iso = 0.0;
    bool m_meshCurrent = false;   // the panels show the surface at m_iso
    bool m_drawsInPanels = false; // the pipeline the current settings generation was set up for
    // On CUDA with a real GPU's GL: the worker shades the iso panel from the device's mesh
    // (and method 1 runs there too); the panels draw what it made and never hold a mesh.
    bool m_isoOnDevice = false;
    std::shared_ptr<const render::Mesh> m_mesh; // the mesh on screen (export)
    CameraController m_camera;
    ReviewPanel* m_isoPanel = nullptr;
    ReviewPanel* m_silhouettePanel = nullptr;
    IsoControl* m_isoControl = nullptr;
    QLabel* m_statusLine = nullptr;
    QLabel* m_errorLine = nullptr;
    QLabel* m_warningLine = nullptr;
    QLabel* m_storageLine = nullptr;
    QLabel* m_cursorLine = nullptr; // the surface point under the mouse, in patient terms
    QLabel* m_hintLine = nullptr;   // how to use the mouse, or the annotation tool's next step
    SliceViews* m_slices = nullptr;
    ReviewArrangement* m_arrangement = nullptr;
    std::optional<QPoint> m_shiftPress; // a Shift+left press on a 3D panel: a click if it stays
    AnnotationDocument* m_annotations = nullptr;
    AnnotationToolController* m_annotationTools = nullptr;
    AnnotationActions* m_annotationActions = nullptr;
    std::unique_ptr<RenderScheduler> m_scheduler;
    ReviewStatus m_status;
};

} // namespace lw::gui
