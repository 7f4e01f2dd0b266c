#pragma once

// One of the review's two panels. The iso panel shades the mesh with the engine's GL pipeline
// (SilhouetteGlRenderer, the same shading as method 1's iso panel); the silhouette panel either
// runs method 1 the same way or shows the image a CPU method rendered on the worker thread. Both
// follow one CameraController (linked cameras) and turn mouse and keys into camera moves.
//
// Where the GL runs decides what the panel is made of (setGlView):
//   GL view     a QOpenGLWidget: the engine draws in the panel's own context (a GPU without
//               CUDA);
//   image view  a plain raster QWidget showing the worker's images: with a software OpenGL
//               (llvmpipe) both the draw calls and Qt's GL composition of a window that holds a
//               QOpenGLWidget would run on the UI thread, so the window holds none; with CUDA
//               the worker draws both panels, and a window without GL flushes only what
//               changed.
//
// For export and annotation: renderImage() re-renders the GL content at any size (not scaled)
// and pickPatientPoint() turns a pixel into the surface point under it (LPS, mm) through the
// depth buffer and the camera.

#include "lw/render/iso_surface.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/visible_polylines.h"
#include "review/silhouette_textures.h"
#include "settings/review_settings.h"

#include <QImage>
#include <QString>
#include <QWidget>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

class QStackedLayout;
class QTimer;

namespace lw::gui {

class CameraController;
class PanelGlView;
class PanelImageView;

enum class PanelKind { Iso, Silhouette };

// The engine's GL options for a panel under these settings (the panel and the render worker
// draw with the same ones).
render::SilhouetteGlOptions panelGlOptions(PanelKind kind, const ReviewSettings& settings,
                                           const render::Camera& camera,
                                           const render::Aabb& bounds);

// The OpenGL the windows get on this display: a throw-away context asked once per process.
struct GlInfo {
    bool available = false;
    bool software = false; // llvmpipe, softpipe, swrast
    QString renderer;      // GL_RENDERER, for the settings page
    // Draw on the CPU rather than through this OpenGL (none, or a software rasterizer).
    bool prefersCpu() const { return !available || software; }
};
const GlInfo& displayGlInfo();

// The OpenGL 4.5 core profile the engine's pipeline needs (geometry shaders), as the default
// format of every window and context, all sharing Qt's global context (the render worker's
// silhouette textures); call before QApplication is made.
void requestCoreProfileFormat();

class ReviewPanel : public QWidget {
    Q_OBJECT
public:
    ReviewPanel(PanelKind kind, CameraController& camera, QWidget* parent = nullptr);
    ~ReviewPanel() override;

    PanelKind kind() const { return m_kind; }
    // true: a QOpenGLWidget that can draw the mesh itself; false: a raster image view.
    void setGlView(bool glView);
    bool hasGlView() const { return m_glView != nullptr && m_glViewActive; }
    // The mesh to draw with GL (uploaded at the next paint of the GL view).
    void setMesh(std::shared_ptr<const render::Mesh> mesh);
    bool hasMesh() const { return m_mesh != nullptr; }
    // Draw the mesh with GL (GL view only) or show the image the worker rendered.
    void setUseGl(bool enabled);
    bool usesGl() const { return m_useGl && hasGlView(); }
    void setImage(const QImage& image);
    // The silhouette as a texture the render worker's CUDA wrote (GL view): drawn as setImage()
    // draws the host mask's image, with nothing uploaded; null: the image again.
    void setLinesTexture(std::shared_ptr<const LinesTexture> texture);
    bool showsLinesTexture() const { return m_linesTexture && hasGlView(); }
    // The worker's iso image comes with its depth buffer and camera, for picking.
    void setDepth(std::vector<float> depth, const render::Camera& camera);
    // Lines drawn over the iso panel by a CPU method (transparent elsewhere); null for none.
    void setOverlay(const QImage& overlay);
    void setAppearance(const ReviewSettings& settings);
    // A message drawn in the panel instead of (or over) the picture, e.g. an error.
    void setMessage(const QString& message);
    QString message() const { return m_message; }

    // What the panel shows now, as the screen shows it.
    QImage grabImage();
    // The GL content rendered offscreen at `size` (GL view drawing the mesh); a null image
    // otherwise (the caller renders it elsewhere).
    // `appearance` (optional) replaces the panel's own, e.g. with lines widened for an export.
    QImage renderImage(QSize size, const ReviewSettings* appearance = nullptr);
    // The silhouette this panel's own GL draws (method 1 in the panel) as the exports' vector
    // lines at `size`: its one-pixel mask cut into the host mesh's polylines
    // (render::splitPolylines), with the hidden runs when `withHidden`. Empty without a mesh.
    render::PolylineSplit renderPolylines(QSize size, const ReviewSettings& appearance,
                                          const render::PolylineOptions& options, bool withHidden);
    // The surface point under widget pixel `position`, or nullopt where there is none.
    std::optional<glm::dvec3> pickPatientPoint(QPoint position);
    double lastPaintMs() const { return m_lastPaintMs; }
    // Segments the geometry shader emitted in the last GL paint (method 1 silhouette panel).
    std::size_t lastSegmentCount() const { return m_lastStats.segments; }
    QSize renderSize() const; // the viewport in device pixels
    // The camera of what the panel shows now, at renderSize().
    render::Camera viewCamera() const;
    // A widget position in the camera's continuous pixel coordinates (device pixels).
    glm::dvec2 cameraPixel(QPointF position) const;

    // Drawn over the picture at every paint, in viewCamera()'s pixels (the annotations): the
    // panel knows nothing of what it draws. An empty function draws nothing.
    using OverlayPainter = std::function<void(QPainter& painter, const render::Camera& camera)>;
    void setOverlayPainter(OverlayPainter painter);
    // The linked cursor: a cross-hair at a patient point (LPS, mm), drawn over the picture where
    // the camera projects it; nothing for none.
    void setCrossHair(std::optional<glm::dvec3> patient);
    std::optional<glm::dvec3> crossHair() const { return m_crossHair; }
    // The overlay changed (the picture did not): paint again.
    void repaintOverlay() { updateView(); }

    // For the views: the drawing itself.
    void initializeGlView();
    void paintGlView();
    void paintImageView(QPainter& painter);

signals:
    void painted(double milliseconds);
    void resized();
    void glFailed(const QString& reason);
    // The mouse rests over the panel (no button): the surface point under it, or none.
    void hovered(std::optional<glm::dvec3> patientPoint);

protected:
    void resizeEvent(QResizeEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;

private:
    bool drawsGl() const;
    void uploadPendingMesh();
    // Runs `draw` with the GL view's context current and its pending mesh uploaded, for a frame at
    // another size than the panel's (an export); a GL error goes to the panel's message. The
    // next paint restores the panel's own size.
    void drawOffscreen(const std::function<void()>& draw);
    void drawGl(const render::Camera& camera);
    void drawImages(QPainter& painter);
    void drawLinesTexture();
    void drawMessage(QPainter& painter);
    void drawOverlayPainter(QPainter& painter);
    void drawCrossHair(QPainter& painter, const render::Camera& camera) const;
    void releaseGl();
    // The renderer of the view's context (made on first use; the context current).
    render::SilhouetteGlRenderer& glRenderer();
    void updateView();
    void reportPaint(double milliseconds);
    std::optional<glm::dvec3> pickFromDepthImage(QPoint position) const;

    PanelKind m_kind;
    CameraController& m_camera;
    QStackedLayout* m_stack = nullptr;
    PanelGlView* m_glView = nullptr; // created on first need
    PanelImageView* m_imageView = nullptr;
    bool m_glViewActive = false;
    // The GL objects of the view's context, made there on first need and destroyed with it
    // current (releaseGl, on the context's aboutToBeDestroyed and in the destructor).
    std::unique_ptr<render::SilhouetteGlRenderer> m_gl;
    std::shared_ptr<const render::Mesh> m_mesh;
    bool m_meshUploaded = false;
    bool m_useGl = false;
    bool m_glBroken = false;
    QImage m_image;
    std::shared_ptr<const LinesTexture> m_linesTexture; // held while shown: not written meanwhile
    std::unique_ptr<LinesTextureView> m_linesView;
    QImage m_overlay;
    std::vector<float> m_depth;
    render::Camera m_depthCamera;
    ReviewSettings m_appearance;
    QString m_message;
    QPoint m_lastMouse;
    QTimer* m_hoverTimer = nullptr; // picks once the mouse rests, not on every move
    OverlayPainter m_overlayPainter;
    std::optional<glm::dvec3> m_crossHair;
    double m_lastPaintMs = 0.0;
    render::SilhouetteGlStats m_lastStats;
};

} // namespace lw::gui
