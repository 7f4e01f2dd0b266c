#pragma once

// One of the review's two panels, a QOpenGLWidget. The iso panel shades the mesh with the
// engine's GL pipeline (SilhouetteGlRenderer, the same shading as method 1's iso panel) in this
// widget's own context; the silhouette panel either runs method 1 in its own context the same
// way, or shows the image a CPU method rendered on the worker thread. Both follow one
// CameraController (linked cameras) and turn mouse and keys into camera moves.
//
// For export and annotation: renderImage() re-renders the GL content at any size (not scaled)
// and pickPatientPoint() turns a pixel into the surface point under it (LPS, mm) through the
// depth buffer and the camera.

#include "lw/render/iso_surface.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "settings/review_settings.h"

#include <QImage>
#include <QOpenGLWidget>
#include <QString>
#include <memory>
#include <optional>
#include <vector>

namespace lw::gui {

class CameraController;

enum class PanelKind { Iso, Silhouette };

// The engine's GL options for a panel under these settings (the panel and the render worker
// draw with the same ones).
render::SilhouetteGlOptions panelGlOptions(PanelKind kind, const ReviewSettings& settings);

class ReviewPanel : public QOpenGLWidget {
    Q_OBJECT
public:
    ReviewPanel(PanelKind kind, CameraController& camera, QWidget* parent = nullptr);
    ~ReviewPanel() override;

    PanelKind kind() const { return m_kind; }
    // The mesh to draw with GL (iso panel always; silhouette panel for method 1 S). Uploaded at
    // the next paint, in this widget's context.
    void setMesh(std::shared_ptr<const render::Mesh> mesh);
    bool hasMesh() const { return m_mesh != nullptr; }
    // Draw the mesh with GL in this widget's context (iso panel; silhouette panel for method 1
    // S), or show the image the worker rendered.
    void setUseGl(bool enabled);
    bool usesGl() const { return m_useGl; }
    void setImage(const QImage& image);
    // The worker's iso image comes with its depth buffer and camera, for picking.
    void setDepth(std::vector<float> depth, const render::Camera& camera);
    // The panel's GL context is a software rasterizer (llvmpipe, softpipe): known after the
    // first show (glKnown()).
    bool glKnown() const { return m_glKnown; }
    bool softwareGl() const { return m_softwareGl; }
    QString glRenderer() const { return m_glRenderer; }
    // Lines drawn over the iso panel by a CPU method (transparent elsewhere); null for none.
    void setOverlay(const QImage& overlay);
    void setAppearance(const ReviewSettings& settings);
    // A message drawn in the panel instead of (or over) the picture, e.g. an error.
    void setMessage(const QString& message);
    QString message() const { return m_message; }

    // The GL content rendered offscreen at `size` (iso panel, method 1 silhouette panel); a
    // null image when this panel shows a CPU image (the caller renders that itself).
    QImage renderImage(QSize size);
    // The surface point under widget pixel `position`, or nullopt where there is none.
    std::optional<glm::dvec3> pickPatientPoint(QPoint position);
    // What the last paint drew (for tests and the status line).
    double lastPaintMs() const { return m_lastPaintMs; }
    std::size_t uploadedTriangles() const { return m_gl.triangleCount(); }
    // Segments the geometry shader emitted in the last paint (method 1 silhouette panel).
    std::size_t lastSegmentCount() const { return m_lastStats.segments; }
    QSize renderSize() const; // the viewport in device pixels

signals:
    void painted(double milliseconds);
    void resized();
    void glReady();
    void glFailed(const QString& reason);

protected:
    void initializeGL() override;
    void paintGL() override;
    void resizeGL(int width, int height) override;
    void mousePressEvent(QMouseEvent* event) override;
    void mouseMoveEvent(QMouseEvent* event) override;
    void wheelEvent(QWheelEvent* event) override;
    void keyPressEvent(QKeyEvent* event) override;

private:
    bool drawsGl() const;
    void uploadPendingMesh();
    void drawGl(const render::Camera& camera);
    void drawImages();
    void drawMessage();
    void releaseGl();

    PanelKind m_kind;
    CameraController& m_camera;
    render::SilhouetteGlRenderer m_gl;
    std::shared_ptr<const render::Mesh> m_mesh;
    bool m_meshUploaded = false;
    bool m_useGl = false;
    bool m_glBroken = false;
    bool m_glKnown = false;
    bool m_softwareGl = false;
    QString m_glRenderer;
    QImage m_image;
    std::vector<float> m_depth;
    render::Camera m_depthCamera;
    QImage m_overlay;
    ReviewSettings m_appearance;
    QString m_message;
    QPoint m_lastMouse;
    double m_lastPaintMs = 0.0;
    render::SilhouetteGlStats m_lastStats;
};

} // namespace lw::gui
