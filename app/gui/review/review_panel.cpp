#include "review/review_panel.h"

#include "lw/core/error.h"
#include "lw/render/gl_context.h"
#include "lw/render/surface_picking.h"
#include "lw/render/visibility_tolerance.h"
#include "review/camera_controller.h"
#include "review/panel_render_job.h"
#include "review/qt_image.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLExtraFunctions>
#include <QOpenGLFunctions>
#include <QOpenGLWidget>
#include <QPainter>
#include <QStackedLayout>
#include <QSurfaceFormat>
#include <QTimer>
#include <QWheelEvent>
#include <cmath>
#include <cstring>

namespace lw::gui {

// The GL view: a QOpenGLWidget whose drawing is the panel's.
class PanelGlView final : public QOpenGLWidget {
public:
    explicit PanelGlView(ReviewPanel& panel) : QOpenGLWidget(&panel), m_panel(panel) {
        setAttribute(Qt::WA_TransparentForMouseEvents); // the panel handles the mouse
    }

protected:
    void initializeGL() override { m_panel.initializeGlView(); }
    void paintGL() override { m_panel.paintGlView(); }

private:
    ReviewPanel& m_panel;
};

// The image view: raster painting, no OpenGL in the window.
class PanelImageView final : public QWidget {
public:
    explicit PanelImageView(ReviewPanel& panel) : QWidget(&panel), m_panel(panel) {
        setAttribute(Qt::WA_OpaquePaintEvent);
        setAttribute(Qt::WA_TransparentForMouseEvents);
    }

protected:
    void paintEvent(QPaintEvent*) override {
        QPainter painter(this);
        m_panel.paintImageView(painter);
    }

private:
    ReviewPanel& m_panel;
};

namespace {

glm::vec4 toVec4(const QColor& colour) {
    return {float(colour.redF()), float(colour.greenF()), float(colour.blueF()), 1.0f};
}

GlInfo probeGl() {
    GlInfo info;
    QOpenGLContext context;
    QOffscreenSurface surface;
    surface.create();
    if (!context.create() || !context.makeCurrent(&surface))
        return info;
    const auto* renderer =
        reinterpret_cast<const char*>(context.functions()->glGetString(GL_RENDERER));
    info.available = true;
    info.renderer = QString::fromLatin1(renderer ? renderer : "unknown");
    // Software rasterizers do the vertex work on the CPU, inside the draw call.
    info.software = render::isSoftwareRenderer(info.renderer.toStdString());
    context.doneCurrent();
    return info;
}

} // namespace

const GlInfo& displayGlInfo() {
    static const GlInfo info = probeGl(); // a fact of the display, asked once
    return info;
}

void requestCoreProfileFormat() {
    // Every context shares Qt's global one: the render worker's context writes the silhouette
    // textures the panels' contexts draw (silhouette_textures.h).
    QCoreApplication::setAttribute(Qt::AA_ShareOpenGLContexts);
    QSurfaceFormat format;
    format.setRenderableType(QSurfaceFormat::OpenGL);
    format.setVersion(4, 5);
    format.setProfile(QSurfaceFormat::CoreProfile);
    format.setDepthBufferSize(24);
    QSurfaceFormat::setDefaultFormat(format);
}

render::SilhouetteGlOptions panelGlOptions(PanelKind kind, const ReviewSettings& settings,
                                           const render::Camera& camera,
                                           const render::Aabb& bounds) {
    render::SilhouetteGlOptions options;
    options.panel = kind == PanelKind::Iso ? render::GlPanel::Iso : render::GlPanel::Silhouette;
    options.visibility = settings.visibility;
    options.linesOnIso = kind == PanelKind::Iso && settings.silhouetteOnIso &&
                         settings.method == render::SilhouetteMethod::GeometryShader;
    options.lineWidth = float(settings.lineWidth);
    options.lineColour = toVec4(settings.lineColour);
    options.background = toVec4(settings.background);
    options.countSegments = kind == PanelKind::Silhouette;
    options.depthTolerance = render::windowDepthTolerance(camera, bounds);
    return options;
}

ReviewPanel::ReviewPanel(PanelKind kind, CameraController& camera, QWidget* parent)
    : QWidget(parent), m_kind(kind), m_camera(camera) {
    setObjectName(kind == PanelKind::Iso ? "isoPanel" : "silhouettePanel");
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(200, 200);
    m_stack = new QStackedLayout(this);
    m_stack->setContentsMargins(0, 0, 0, 0);
    m_imageView = new PanelImageView(*this);
    m_stack->addWidget(m_imageView);
    // A panel that draws its mesh itself follows the camera at once. One that shows the render
    // worker's picture is repainted when the picture of the new camera arrives: repainting the
    // old one first would cost a composition of the window (through the X server) for nothing,
    // and the overlay would run ahead of the picture under it.
    connect(&m_camera, &CameraController::changed, this, [this] {
        if (drawsGl())
            updateView();
    });
    setMouseTracking(true);
    m_hoverTimer = new QTimer(this);
    m_hoverTimer->setSingleShot(true);
    m_hoverTimer->setInterval(60);
    // The iso panel picks through its depth; the silhouette panel shares the camera, so the same
    // pixel of the iso panel is the same surface point.
    connect(m_hoverTimer, &QTimer::timeout, this, [this] {
        emit hovered(m_kind == PanelKind::Iso ? pickPatientPoint(m_lastMouse) : std::nullopt);
    });
}

ReviewPanel::~ReviewPanel() {
    releaseGl();
    // The GL view's context announces its end while ~QWidget deletes the children, when this is
    // no longer a ReviewPanel (UBSan: member call on a QWidget): nothing of ours may run then.
    if (m_glView && m_glView->context())
        disconnect(m_glView->context(), nullptr, this, nullptr);
}

void ReviewPanel::setGlView(bool glView) {
    if (glView && !m_glView) {
        m_glView = new PanelGlView(*this);
        m_stack->addWidget(m_glView);
    }
    m_glViewActive = glView;
    m_stack->setCurrentWidget(glView ? static_cast<QWidget*>(m_glView) : m_imageView);
    updateView();
}

void ReviewPanel::releaseGl() {
    // GL objects die with the context they were made in: release them while it still exists.
    if (!m_glView || !m_glView->context() || (!m_gl && !m_linesView))
        return;
    m_glView->makeCurrent();
    m_gl.reset();
    m_linesView.reset();
    m_glView->doneCurrent();
}

render::SilhouetteGlRenderer& ReviewPanel::glRenderer() {
    if (!m_gl)
        m_gl = std::make_unique<render::SilhouetteGlRenderer>();
    return *m_gl;
}

void ReviewPanel::initializeGlView() {
    connect(
        m_glView->context(), &QOpenGLContext::aboutToBeDestroyed, this, [this] { releaseGl(); },
        Qt::DirectConnection);
    m_meshUploaded = false; // a new context has none of the old buffers
}

void ReviewPanel::updateView() {
    if (m_glViewActive && m_glView)
        m_glView->update();
    else
        m_imageView->update();
}

void ReviewPanel::setMesh(std::shared_ptr<const render::Mesh> mesh) {
    m_mesh = std::move(mesh);
    m_meshUploaded = false;
    updateView();
}

void ReviewPanel::setUseGl(bool enabled) {
    m_useGl = enabled;
    updateView();
}

void ReviewPanel::setImage(const QImage& image) {
    m_image = image;
    updateView();
}

void ReviewPanel::setLinesTexture(std::shared_ptr<const LinesTexture> texture) {
    m_linesTexture = std::move(texture);
    updateView();
}

void ReviewPanel::setDepth(std::vector<float> depth, const render::Camera& camera) {
    m_depth = std::move(depth);
    m_depthCamera = camera;
}

void ReviewPanel::setOverlay(const QImage& overlay) {
    m_overlay = overlay;
    updateView();
}

void ReviewPanel::setAppearance(const ReviewSettings& settings) {
    m_appearance = settings;
    updateView();
}

void ReviewPanel::setMessage(const QString& message) {
    m_message = message;
    updateView();
}

void ReviewPanel::resizeEvent(QResizeEvent* event) {
    QWidget::resizeEvent(event);
    emit resized();
}

QSize ReviewPanel::renderSize() const {
    const qreal ratio = devicePixelRatioF();
    return {std::max(1, int(std::lround(width() * ratio))),
            std::max(1, int(std::lround(height() * ratio)))};
}

bool ReviewPanel::drawsGl() const {
    return !m_glBroken && m_mesh && usesGl();
}

void ReviewPanel::uploadPendingMesh() {
    if (m_meshUploaded || !m_mesh)
        return;
    glRenderer().uploadMesh(*m_mesh);
    m_meshUploaded = true;
}

void ReviewPanel::drawGl(const render::Camera& camera) {
    uploadPendingMesh();
    render::SilhouetteGlRenderer& gl = glRenderer();
    m_lastStats =
        gl.render(camera, panelGlOptions(m_kind, m_appearance, camera, m_camera.bounds()));
    // The engine draws into its own framebuffer object; copy it into the widget's.
    QOpenGLExtraFunctions* f = m_glView->context()->extraFunctions();
    f->glBindFramebuffer(GL_READ_FRAMEBUFFER, gl.framebuffer());
    f->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, m_glView->defaultFramebufferObject());
    f->glBlitFramebuffer(0, 0, camera.width(), camera.height(), 0, 0, camera.width(),
                         camera.height(), GL_COLOR_BUFFER_BIT, GL_NEAREST);
    f->glBindFramebuffer(GL_FRAMEBUFFER, m_glView->defaultFramebufferObject());
}

void ReviewPanel::paintGlView() {
    QElapsedTimer timer;
    timer.start();
    QOpenGLExtraFunctions* f = m_glView->context()->extraFunctions();
    const QColor background = m_appearance.background;
    f->glClearColor(float(background.redF()), float(background.greenF()), float(background.blueF()),
                    1.0f);
    f->glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (drawsGl()) {
        const QSize size = renderSize();
        try {
            drawGl(m_camera.camera(size.width(), size.height()));
        } catch (const core::Error& error) {
            m_glBroken = true;
            m_message = tr("OpenGL failed: %1").arg(error.what());
            emit glFailed(m_message);
        } catch (const std::bad_alloc&) {
            m_message = tr("Out of memory uploading the surface to OpenGL");
            m_mesh.reset();
        }
    } else if (m_linesTexture) {
        drawLinesTexture();
    }
    {
        QPainter painter(m_glView);
        drawImages(painter);
        drawOverlayPainter(painter);
        drawMessage(painter);
    } // the painter ends while the widget's context is current, before anyone hears of it
    reportPaint(double(timer.nsecsElapsed()) / 1e6);
}

void ReviewPanel::drawLinesTexture() {
    try {
        if (!m_linesView)
            m_linesView = std::make_unique<LinesTextureView>();
        m_linesView->draw(*m_linesTexture, m_appearance.lineWidth, m_appearance.lineColour,
                          m_appearance.background);
    } catch (const core::Error& error) {
        m_linesTexture.reset();
        m_message = tr("OpenGL failed: %1").arg(error.what());
    }
}

void ReviewPanel::paintImageView(QPainter& painter) {
    QElapsedTimer timer;
    timer.start();
    painter.fillRect(m_imageView->rect(), m_appearance.background);
    drawImages(painter);
    drawOverlayPainter(painter);
    drawMessage(painter);
    reportPaint(double(timer.nsecsElapsed()) / 1e6);
}

void ReviewPanel::reportPaint(double milliseconds) {
    m_lastPaintMs = milliseconds;
    emit painted(milliseconds);
}

void ReviewPanel::drawImages(QPainter& painter) {
    // An image rendered for the viewport at request time; until the next one arrives after a
    // resize, it is stretched rather than left misplaced.
    if (!usesGl() && !m_image.isNull())
        painter.drawImage(rect(), m_image);
    if (m_kind == PanelKind::Iso && !m_overlay.isNull())
        painter.drawImage(rect(), m_overlay);
}

void ReviewPanel::setOverlayPainter(OverlayPainter painter) {
    m_overlayPainter = std::move(painter);
    updateView();
}

void ReviewPanel::drawOverlayPainter(QPainter& painter) {
    if (!m_overlayPainter && !m_crossHair)
        return;
    painter.save();
    // The overlay draws in device pixels, as the camera projects.
    painter.scale(1.0 / devicePixelRatioF(), 1.0 / devicePixelRatioF());
    const render::Camera camera = viewCamera();
    if (m_overlayPainter)
        m_overlayPainter(painter, camera);
    drawCrossHair(painter, camera);
    painter.restore();
}

void ReviewPanel::setCrossHair(std::optional<glm::dvec3> patient) {
    m_crossHair = patient;
    updateView();
}

// The linked cursor's colour, as on the slices (slice_view.cpp): cyan shows on the grey surface,
// the white background and black lines alike.
void ReviewPanel::drawCrossHair(QPainter& painter, const render::Camera& camera) const {
    if (!m_crossHair)
        return;
    const render::ProjectedPoint point = camera.project(*m_crossHair);
    if (!camera.isOrthographic() && point.depth <= 0.0)
        return; // behind the eye
    const QPointF at(point.pixel.x, point.pixel.y);
    const double scale = devicePixelRatioF();
    const double gap = 4.0 * scale, arm = 16.0 * scale;
    painter.save();
    painter.setRenderHint(QPainter::Antialiasing);
    painter.setPen(QPen(QColor(0, 200, 255), 2.0 * scale));
    painter.drawLine(at + QPointF(-arm, 0), at + QPointF(-gap, 0));
    painter.drawLine(at + QPointF(gap, 0), at + QPointF(arm, 0));
    painter.drawLine(at + QPointF(0, -arm), at + QPointF(0, -gap));
    painter.drawLine(at + QPointF(0, gap), at + QPointF(0, arm));
    painter.restore();
}

render::Camera ReviewPanel::viewCamera() const {
    const QSize size = renderSize();
    return m_camera.camera(size.width(), size.height());
}

glm::dvec2 ReviewPanel::cameraPixel(QPointF position) const {
    const qreal ratio = devicePixelRatioF();
    return {position.x() * ratio, position.y() * ratio};
}

void ReviewPanel::drawMessage(QPainter& painter) {
    if (m_message.isEmpty())
        return;
    painter.setPen(m_appearance.background.lightness() < 128 ? Qt::white : Qt::black);
    painter.drawText(rect().adjusted(20, 20, -20, -20), Qt::AlignCenter | Qt::TextWordWrap,
                     m_message);
}

QImage ReviewPanel::grabImage() {
    if (hasGlView())
        return m_glView->grabFramebuffer();
    return m_imageView->grab().toImage();
}

void ReviewPanel::drawOffscreen(const std::function<void()>& draw) {
    m_glView->makeCurrent();
    try {
        uploadPendingMesh();
        draw();
    } catch (const core::Error& error) {
        m_message = tr("OpenGL failed: %1").arg(error.what());
    }
    m_glView->doneCurrent();
    updateView(); // the framebuffer object now has the export's size; the next paint restores it
}

QImage ReviewPanel::renderImage(QSize size, const ReviewSettings* appearance) {
    if (!drawsGl() || size.isEmpty())
        return {};
    const render::Camera camera = m_camera.camera(size.width(), size.height());
    QImage image;
    drawOffscreen([&] {
        image = toQImage(glRenderer().renderImage(
            camera, panelGlOptions(m_kind, appearance ? *appearance : m_appearance, camera,
                                   m_camera.bounds())));
    });
    return image;
}

render::PolylineSplit ReviewPanel::renderPolylines(QSize size, const ReviewSettings& appearance,
                                                   const render::PolylineOptions& options,
                                                   bool withHidden) {
    if (!drawsGl() || size.isEmpty())
        return {};
    const render::Camera camera = m_camera.camera(size.width(), size.height());
    render::PixelMask lines(size.width(), size.height());
    drawOffscreen([&] {
        // One-pixel black lines on white: the mask the polylines are cut by, whatever the colours.
        render::SilhouetteGlOptions gl =
            panelGlOptions(m_kind, appearance, camera, m_camera.bounds());
        gl.lineWidth = 1.0f;
        gl.lineColour = {0.0f, 0.0f, 0.0f, 1.0f};
        gl.background = {1.0f, 1.0f, 1.0f, 1.0f};
        glRenderer().render(camera, gl);
        glRenderer().readRedMask(255, lines.pixels());
    });
    if (!m_mesh)
        return {};
    return render::splitPolylines(*m_mesh, camera, lines, options, withHidden);
}

std::optional<glm::dvec3> ReviewPanel::pickFromDepthImage(QPoint position) const {
    // The worker's depth buffer of the image on screen (stretched to the widget, as drawn).
    const int w = m_depthCamera.width(), h = m_depthCamera.height();
    if (width() <= 0 || height() <= 0)
        return std::nullopt;
    return render::pickFromDepthBuffer(
        m_depth, m_depthCamera,
        {(position.x() + 0.5) * w / width(), (position.y() + 0.5) * h / height()});
}

std::optional<glm::dvec3> ReviewPanel::pickPatientPoint(QPoint position) {
    if (m_kind != PanelKind::Iso)
        return std::nullopt;
    if (!usesGl())
        return pickFromDepthImage(position);
    if (!drawsGl())
        return std::nullopt;
    const QSize size = renderSize();
    const render::Camera camera = m_camera.camera(size.width(), size.height());
    const qreal ratio = devicePixelRatioF();
    const int x = int(position.x() * ratio);
    const int y = int(position.y() * ratio);
    if (x < 0 || y < 0 || x >= size.width() || y >= size.height())
        return std::nullopt;
    m_glView->makeCurrent();
    float depth = 1.0f;
    try {
        uploadPendingMesh();
        render::SilhouetteGlRenderer& gl = glRenderer();
        gl.render(camera, panelGlOptions(m_kind, m_appearance, camera, m_camera.bounds()));
        depth = gl.readDepthAt(x, y);
    } catch (const core::Error&) {
        depth = 1.0f;
    }
    m_glView->doneCurrent();
    if (depth >= 1.0f)
        return std::nullopt;
    return camera.unproject({x + 0.5, y + 0.5}, 2.0 * double(depth) - 1.0);
}

void ReviewPanel::mousePressEvent(QMouseEvent* event) {
    m_lastMouse = event->position().toPoint();
    setFocus();
}

void ReviewPanel::mouseMoveEvent(QMouseEvent* event) {
    const QPoint position = event->position().toPoint();
    const QPointF delta = position - m_lastMouse;
    m_lastMouse = position;
    const Qt::MouseButtons buttons = event->buttons();
    if (buttons == Qt::NoButton) {
        m_hoverTimer->start();
        return;
    }
    const bool shift = event->modifiers() & Qt::ShiftModifier;
    if (buttons & Qt::MiddleButton || (buttons & Qt::LeftButton && shift))
        m_camera.panByDrag(delta, size());
    else if (buttons & Qt::RightButton)
        m_camera.zoomBy(std::exp(-delta.y() / 200.0));
    else if (buttons & Qt::LeftButton && event->modifiers() & Qt::ControlModifier)
        m_camera.rollBy(delta.x() * 0.5);
    else if (buttons & Qt::LeftButton)
        m_camera.rotateByDrag(delta, size());
}

void ReviewPanel::wheelEvent(QWheelEvent* event) {
    // One notch (120 units) zooms by 10 %.
    m_camera.zoomBy(std::pow(1.1, event->angleDelta().y() / 120.0));
    event->accept();
}

void ReviewPanel::keyPressEvent(QKeyEvent* event) {
    const bool shift = event->modifiers() & Qt::ShiftModifier;
    const double step = 0.05 * height();
    QPointF delta;
    switch (event->key()) {
    case Qt::Key_Left:
        delta = {-step, 0};
        break;
    case Qt::Key_Right:
        delta = {step, 0};
        break;
    case Qt::Key_Up:
        delta = {0, -step};
        break;
    case Qt::Key_Down:
        delta = {0, step};
        break;
    case Qt::Key_Plus:
    case Qt::Key_Equal:
        return m_camera.zoomBy(1.1);
    case Qt::Key_Minus:
        return m_camera.zoomBy(1.0 / 1.1);
    case Qt::Key_Home:
        return m_camera.reset();
    default:
        return QWidget::keyPressEvent(event);
    }
    if (shift)
        m_camera.panByDrag(delta, size());
    else
        m_camera.rotateByDrag(delta, size());
}

} // namespace lw::gui
