#include "review/review_panel.h"

#include "lw/core/error.h"
#include "review/camera_controller.h"

#include <QElapsedTimer>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QOpenGLContext>
#include <QOpenGLExtraFunctions>
#include <QOpenGLFunctions>
#include <QPainter>
#include <QWheelEvent>
#include <cmath>
#include <cstring>

namespace lw::gui {
namespace {

glm::vec4 toVec4(const QColor& colour) {
    return {float(colour.redF()), float(colour.greenF()), float(colour.blueF()), 1.0f};
}

QImage toQImage(const core::ImageRgba8& image) {
    QImage result(image.width(), image.height(), QImage::Format_RGBA8888);
    for (int y = 0; y < image.height(); ++y)
        std::memcpy(result.scanLine(y), image.row(y), std::size_t(image.width()) * 4);
    return result;
}

} // namespace

ReviewPanel::ReviewPanel(PanelKind kind, CameraController& camera, QWidget* parent)
    : QOpenGLWidget(parent), m_kind(kind), m_camera(camera) {
    setObjectName(kind == PanelKind::Iso ? "isoPanel" : "silhouettePanel");
    setFocusPolicy(Qt::StrongFocus);
    setMinimumSize(200, 200);
    connect(&m_camera, &CameraController::changed, this, qOverload<>(&QWidget::update));
}

ReviewPanel::~ReviewPanel() {
    releaseGl();
}

void ReviewPanel::releaseGl() {
    // GL objects die with the context they were made in: release them while it still exists.
    if (!context() || !m_gl.isInitialized())
        return;
    makeCurrent();
    m_gl.release();
    doneCurrent();
}

void ReviewPanel::initializeGL() {
    connect(
        context(), &QOpenGLContext::aboutToBeDestroyed, this, [this] { releaseGl(); },
        Qt::DirectConnection);
    m_meshUploaded = false;
    const auto* renderer =
        reinterpret_cast<const char*>(context()->functions()->glGetString(GL_RENDERER));
    m_glRenderer = QString::fromLatin1(renderer ? renderer : "unknown");
    // Software rasterizers do the vertex work on the CPU, inside the draw call on this thread.
    m_softwareGl = m_glRenderer.contains("llvmpipe", Qt::CaseInsensitive) ||
                   m_glRenderer.contains("softpipe", Qt::CaseInsensitive) ||
                   m_glRenderer.contains("software", Qt::CaseInsensitive) ||
                   m_glRenderer.contains("swr", Qt::CaseInsensitive);
    m_glKnown = true;
    // The engine's shaders are compiled at the first GL draw (not at all when the worker draws:
    // on llvmpipe that compile alone holds the UI thread for ~100 ms).
    emit glReady();
}

void ReviewPanel::setMesh(std::shared_ptr<const render::Mesh> mesh) {
    m_mesh = std::move(mesh);
    m_meshUploaded = false;
    update();
}

void ReviewPanel::setUseGl(bool enabled) {
    m_useGl = enabled;
    update();
}

void ReviewPanel::setDepth(std::vector<float> depth, const render::Camera& camera) {
    m_depth = std::move(depth);
    m_depthCamera = camera;
}

void ReviewPanel::resizeGL(int, int) {
    emit resized();
}

void ReviewPanel::setImage(const QImage& image) {
    m_image = image;
    update();
}

void ReviewPanel::setOverlay(const QImage& overlay) {
    m_overlay = overlay;
    update();
}

void ReviewPanel::setAppearance(const ReviewSettings& settings) {
    m_appearance = settings;
    update();
}

void ReviewPanel::setMessage(const QString& message) {
    m_message = message;
    update();
}

QSize ReviewPanel::renderSize() const {
    const qreal ratio = devicePixelRatioF();
    return {std::max(1, int(std::lround(width() * ratio))),
            std::max(1, int(std::lround(height() * ratio)))};
}

bool ReviewPanel::drawsGl() const {
    return !m_glBroken && m_mesh && m_useGl;
}

render::SilhouetteGlOptions panelGlOptions(PanelKind kind, const ReviewSettings& settings) {
    render::SilhouetteGlOptions options;
    options.panel = kind == PanelKind::Iso ? render::GlPanel::Iso : render::GlPanel::Silhouette;
    options.visibility = settings.visibility;
    options.linesOnIso = kind == PanelKind::Iso && settings.silhouetteOnIso &&
                         settings.method == render::SilhouetteMethod::GeometryShader;
    options.lineWidth = float(settings.lineWidth);
    options.lineColour = toVec4(settings.lineColour);
    options.background = toVec4(settings.background);
    options.countSegments = kind == PanelKind::Silhouette;
    if (kind == PanelKind::Iso && !options.linesOnIso) {
        // No lines to win the depth test: keep the depth exact for picking.
        options.polygonOffsetFactor = 0.0f;
        options.polygonOffsetUnits = 0.0f;
    }
    return options;
}

void ReviewPanel::uploadPendingMesh() {
    if (m_meshUploaded || !m_mesh)
        return;
    m_gl.uploadMesh(*m_mesh);
    m_meshUploaded = true;
}

void ReviewPanel::drawGl(const render::Camera& camera) {
    uploadPendingMesh();
    m_lastStats = m_gl.render(camera, panelGlOptions(m_kind, m_appearance));
    // The engine draws into its own framebuffer object; copy it into the widget's.
    QOpenGLExtraFunctions* f = context()->extraFunctions();
    f->glBindFramebuffer(GL_READ_FRAMEBUFFER, m_gl.framebuffer());
    f->glBindFramebuffer(GL_DRAW_FRAMEBUFFER, defaultFramebufferObject());
    f->glBlitFramebuffer(0, 0, camera.width(), camera.height(), 0, 0, camera.width(),
                         camera.height(), GL_COLOR_BUFFER_BIT, GL_NEAREST);
    f->glBindFramebuffer(GL_FRAMEBUFFER, defaultFramebufferObject());
}

void ReviewPanel::paintGL() {
    QElapsedTimer timer;
    timer.start();
    QOpenGLExtraFunctions* f = context()->extraFunctions();
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
    }
    drawImages();
    drawMessage();
    m_lastPaintMs = double(timer.nsecsElapsed()) / 1e6;
    emit painted(m_lastPaintMs);
}

void ReviewPanel::drawImages() {
    const bool showImage = !m_useGl && !m_image.isNull();
    const bool showOverlay = m_kind == PanelKind::Iso && !m_overlay.isNull();
    if (!showImage && !showOverlay)
        return;
    QPainter painter(this);
    // The image was rendered for the viewport at request time; until the next one arrives after
    // a resize, it is stretched rather than left misplaced.
    painter.setRenderHint(QPainter::SmoothPixmapTransform, false);
    if (showImage)
        painter.drawImage(rect(), m_image);
    if (showOverlay)
        painter.drawImage(rect(), m_overlay);
}

void ReviewPanel::drawMessage() {
    if (m_message.isEmpty())
        return;
    QPainter painter(this);
    QRect box = rect().adjusted(20, 20, -20, -20);
    painter.setPen(m_appearance.background.lightness() < 128 ? Qt::white : Qt::black);
    painter.drawText(box, Qt::AlignCenter | Qt::TextWordWrap, m_message);
}

QImage ReviewPanel::renderImage(QSize size) {
    if (!drawsGl() || size.isEmpty())
        return {};
    makeCurrent();
    QImage image;
    try {
        uploadPendingMesh();
        const render::Camera camera = m_camera.camera(size.width(), size.height());
        image = toQImage(m_gl.renderImage(camera, panelGlOptions(m_kind, m_appearance)));
    } catch (const core::Error& error) {
        m_message = tr("OpenGL failed: %1").arg(error.what());
    }
    doneCurrent();
    update(); // the framebuffer object now has the export's size; the next paint restores it
    return image;
}

std::optional<glm::dvec3> ReviewPanel::pickPatientPoint(QPoint position) {
    if (m_kind != PanelKind::Iso)
        return std::nullopt;
    if (!m_useGl) {
        // The worker's depth buffer of the image on screen (stretched to the widget, as drawn).
        const int w = m_depthCamera.width(), h = m_depthCamera.height();
        if (m_depth.size() != std::size_t(w) * std::size_t(h) || width() <= 0 || height() <= 0)
            return std::nullopt;
        const double x = (position.x() + 0.5) * w / width();
        const double y = (position.y() + 0.5) * h / height();
        if (x < 0 || y < 0 || x >= w || y >= h)
            return std::nullopt;
        const float depth = m_depth[std::size_t(y) * std::size_t(w) + std::size_t(x)];
        if (depth >= 1.0f)
            return std::nullopt;
        return m_depthCamera.unproject({std::floor(x) + 0.5, std::floor(y) + 0.5},
                                       2.0 * double(depth) - 1.0);
    }
    if (!drawsGl())
        return std::nullopt;
    const QSize size = renderSize();
    const render::Camera camera = m_camera.camera(size.width(), size.height());
    const qreal ratio = devicePixelRatioF();
    const int x = int(position.x() * ratio);
    const int y = int(position.y() * ratio);
    if (x < 0 || y < 0 || x >= size.width() || y >= size.height())
        return std::nullopt;
    makeCurrent();
    float depth = 1.0f;
    try {
        uploadPendingMesh();
        m_gl.render(camera, panelGlOptions(m_kind, m_appearance));
        QOpenGLExtraFunctions* f = context()->extraFunctions();
        f->glBindFramebuffer(GL_READ_FRAMEBUFFER, m_gl.framebuffer());
        f->glReadPixels(x, size.height() - 1 - y, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT, &depth);
        f->glBindFramebuffer(GL_FRAMEBUFFER, defaultFramebufferObject());
    } catch (const core::Error&) {
        depth = 1.0f;
    }
    doneCurrent();
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
    switch (event->key()) {
    case Qt::Key_Left:
        return shift ? m_camera.panByDrag({-step, 0}, size())
                     : m_camera.rotateByDrag({-step, 0}, size());
    case Qt::Key_Right:
        return shift ? m_camera.panByDrag({step, 0}, size())
                     : m_camera.rotateByDrag({step, 0}, size());
    case Qt::Key_Up:
        return shift ? m_camera.panByDrag({0, -step}, size())
                     : m_camera.rotateByDrag({0, -step}, size());
    case Qt::Key_Down:
        return shift ? m_camera.panByDrag({0, step}, size())
                     : m_camera.rotateByDrag({0, step}, size());
    case Qt::Key_Plus:
    case Qt::Key_Equal:
        return m_camera.zoomBy(1.1);
    case Qt::Key_Minus:
        return m_camera.zoomBy(1.0 / 1.1);
    case Qt::Key_Home:
        return m_camera.reset();
    default:
        QOpenGLWidget::keyPressEvent(event);
    }
}

} // namespace lw::gui
