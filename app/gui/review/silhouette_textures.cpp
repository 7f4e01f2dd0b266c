#include "review/silhouette_textures.h"

#include "lw/core/error.h"
#include "lw/core/log.h"

#include <QOffscreenSurface>
#include <QOpenGLContext>
#include <QOpenGLFunctions>
#include <QOpenGLShaderProgram>
#include <QOpenGLVertexArrayObject>
#include <QVector2D>

namespace lw::gui {
namespace {

constexpr core::LogCategory kLog("lw.gui");

// One triangle covering the viewport, made from gl_VertexID (no vertex buffer).
constexpr const char* kVertexShader = R"(#version 330 core
void main() {
    vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

// The texel under the fragment (the mask stretched over the viewport, its row 0 at the top, GL's
// window rows counting from the bottom), coloured by the antialiased stroke of `lineWidth`
// through the line texels' centres that linesToImage() draws from the host mask
// (render::PixelMask::strokeCoverage): coverage = clamp(lineWidth / 2 + 0.5 - d, 0, 1), d the
// distance to the nearest line texel's centre.
constexpr const char* kFragmentShader = R"(#version 330 core
uniform sampler2D mask;
uniform float lineWidth;
uniform vec4 lineColour;
uniform vec4 background;
uniform vec4 viewport; // x, y, width, height
out vec4 colour;
void main() {
    ivec2 size = textureSize(mask, 0);
    vec2 position = gl_FragCoord.xy - viewport.xy;
    ivec2 texel = ivec2(int(position.x * float(size.x) / viewport.z),
                        int((viewport.w - position.y) * float(size.y) / viewport.w));
    texel = clamp(texel, ivec2(0), size - 1);
    float reach = max(lineWidth, 1.0) / 2.0 + 0.5;
    int radius = int(ceil(reach)) - 1;
    float coverage = 0.0;
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            ivec2 q = texel + ivec2(dx, dy);
            if (all(greaterThanEqual(q, ivec2(0))) && all(lessThan(q, size)) &&
                texelFetch(mask, q, 0).r > 0.0)
                coverage = max(coverage, clamp(reach - length(vec2(dx, dy)), 0.0, 1.0));
        }
    colour = mix(background, lineColour, coverage);
}
)";

} // namespace

SilhouetteTextures::SilhouetteTextures(QOffscreenSurface* surface) : m_surface(surface) {}

SilhouetteTextures::~SilhouetteTextures() {
    if (!m_context)
        return;
    m_context->makeCurrent(m_surface); // the targets' registrations and textures go with it
    for (Slot& slot : m_slots)
        slot = Slot();
    m_context->doneCurrent();
}

bool SilhouetteTextures::makeContext() {
    if (m_context)
        return true;
    QOpenGLContext* global = QOpenGLContext::globalShareContext();
    const char* missing = !m_surface || !m_surface->isValid() ? "no offscreen surface"
                          : !global ? "Qt has no global shared OpenGL context"
                                    : nullptr;
    if (!missing) {
        auto context = std::make_unique<QOpenGLContext>();
        context->setShareContext(global);
        context->setFormat(global->format());
        if (!context->create() || !context->shareContext())
            missing = "an OpenGL context sharing the panels' could not be made";
        else
            m_context = std::move(context);
    }
    if (missing) {
        kLog.warning(std::string("the silhouette panel's texture is not available (") + missing +
                     "); the silhouette goes through host memory");
        m_unavailable = true;
    }
    return m_context != nullptr;
}

render::GlFrameTarget* SilhouetteTextures::acquire(int width, int height,
                                                   std::shared_ptr<const LinesTexture>& token) {
    token.reset();
#if LINEWORK_GL
    if (m_unavailable || !makeContext() || !m_context->makeCurrent(m_surface))
        return nullptr;
    for (Slot& slot : m_slots) {
        // Held elsewhere: a result on its way to the panel, or the texture the panel shows.
        if (slot.token && slot.token.use_count() > 1)
            continue;
        try {
            if (!slot.target || slot.target->width() != width || slot.target->height() != height) {
                slot = Slot(); // nobody holds it: its registration and texture may go
                slot.target = std::make_unique<render::GlFrameTarget>(width, height);
                slot.token = std::make_shared<const LinesTexture>(
                    LinesTexture{slot.target->texture(), width, height});
            }
        } catch (const core::Error& error) {
            kLog.warning(std::string("the silhouette panel's texture could not be made (") +
                         error.what() + "); the silhouette goes through host memory");
            m_unavailable = true;
            break;
        }
        token = slot.token;
        return slot.target.get();
    }
    done(); // no texture this frame: the context is not needed
#else
    (void)width;
    (void)height;
#endif
    return nullptr;
}

void SilhouetteTextures::done() {
    if (m_context && QOpenGLContext::currentContext() == m_context.get()) {
        // The panel's context binds the textures next: the commands that wrote them must be done.
        m_context->functions()->glFinish();
        m_context->doneCurrent();
    }
}

void SilhouetteTextures::makeCurrent() {
    if (m_unavailable || !makeContext() || !m_context->makeCurrent(m_surface))
        throw core::Error("silhouette texture", "the worker's OpenGL context is not available");
}

LinesTextureView::LinesTextureView()
    : m_program(std::make_unique<QOpenGLShaderProgram>()),
      m_vertexArray(std::make_unique<QOpenGLVertexArrayObject>()) {
    if (!m_program->addShaderFromSourceCode(QOpenGLShader::Vertex, kVertexShader) ||
        !m_program->addShaderFromSourceCode(QOpenGLShader::Fragment, kFragmentShader) ||
        !m_program->link())
        throw core::Error("silhouette texture", m_program->log().toStdString());
    m_vertexArray->create(); // a core profile draws nothing without one bound
}

LinesTextureView::~LinesTextureView() = default;

void LinesTextureView::draw(const LinesTexture& lines, double lineWidth, QColor line,
                            QColor background) {
    QOpenGLFunctions* f = QOpenGLContext::currentContext()->functions();
    GLint viewport[4] = {0, 0, 1, 1};
    f->glGetIntegerv(GL_VIEWPORT, viewport);
    m_program->bind();
    m_program->setUniformValue("mask", 0);
    m_program->setUniformValue("lineWidth", float(lineWidth));
    m_program->setUniformValue("lineColour", line);
    m_program->setUniformValue("background", background);
    m_program->setUniformValue("viewport", float(viewport[0]), float(viewport[1]),
                               float(viewport[2]), float(viewport[3]));
    m_vertexArray->bind();
    f->glActiveTexture(GL_TEXTURE0);
    f->glBindTexture(GL_TEXTURE_2D, lines.texture);
    f->glDisable(GL_DEPTH_TEST);
    f->glDrawArrays(GL_TRIANGLES, 0, 3);
    // QPainter draws over it next and expects the state it left.
    f->glBindTexture(GL_TEXTURE_2D, 0);
    m_vertexArray->release(); // unbinds
    m_program->release();     // unbinds
}

} // namespace lw::gui
