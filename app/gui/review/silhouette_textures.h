#pragma once

// The silhouette panel's lines as GL textures that method 3 on CUDA writes on the render worker
// (CUDA-GL interop, issue 8): the mask never leaves the device and the panel uploads nothing.
//
//   worker   SilhouetteTextures: an OpenGL context of its own that shares Qt's global context
//            (Qt::AA_ShareOpenGLContexts, so every panel's context sees its textures), three
//            render::GlFrameTarget slots made and deleted there; acquire() hands out a slot no
//            one else holds, with the context current for the frame
//   result   LinesTexture: the texture a frame drew into, shared with the result; a slot is
//            written again only once the result and the panel have let go of it, so the panel
//            never shows a texture CUDA is writing
//   panel    LinesTextureView: draws a LinesTexture in the GL view as linesToImage() draws the
//            host mask (antialiased strokes of the line width, on the background)
//
// Where any of it is missing (no shared context, a software OpenGL, another back-end, interop
// refused) the frame takes the host mask as before; the reason is logged once.

#include "lw/render/gl_frame_target.h"

#include <QColor>
#include <array>
#include <memory>

class QOffscreenSurface;
class QOpenGLContext;
class QOpenGLShaderProgram;
class QOpenGLVertexArrayObject;

namespace lw::gui {

// A texture of the worker's context as render::GlFrameTarget makes it (GL_R8, one level, 0/1
// texels, row 0 at the top): what a frame drew.
struct LinesTexture {
    unsigned texture = 0;
    int width = 0, height = 0;
};

class SilhouetteTextures {
public:
    // `surface`: made on the UI thread (Qt requires it), outliving this; null: no textures.
    explicit SilhouetteTextures(QOffscreenSurface* surface);
    // Deletes the targets (their registrations, then their textures) with the worker's context
    // current, then the context: destroy it on the worker thread, before it stops.
    ~SilhouetteTextures();
    SilhouetteTextures(const SilhouetteTextures&) = delete;
    SilhouetteTextures& operator=(const SilhouetteTextures&) = delete;

    // On the worker thread: a target of this size that neither a result nor the panel holds,
    // with the worker's context current until done(); `token` is what a result hands on. Null
    // where there is none (no shared context: logged once; every slot held).
    render::GlFrameTarget* acquire(int width, int height,
                                   std::shared_ptr<const LinesTexture>& token);
    // After the frame: the context is no longer needed on this thread.
    void done();
    // The textures' context current on this thread (made at first need; after done(), for the
    // frame that draws into an acquired target, or the engine's own GL work in the context the
    // panels share); throws core::Error where it cannot be.
    void makeCurrent();

private:
    bool makeContext();

    struct Slot {
        std::unique_ptr<render::GlFrameTarget> target;
        std::shared_ptr<const LinesTexture> token;
    };
    QOffscreenSurface* m_surface = nullptr;
    std::unique_ptr<QOpenGLContext> m_context;
    std::array<Slot, 3> m_slots; // shown, delivered, being written: never more at once
    bool m_unavailable = false;
};

// The panel's side, in the GL view's context: made, drawn and destroyed with it current.
class LinesTextureView {
public:
    // Compiles the program; throws core::Error with the log when it does not link.
    LinesTextureView();
    ~LinesTextureView();
    LinesTextureView(const LinesTextureView&) = delete;
    LinesTextureView& operator=(const LinesTextureView&) = delete;

    // Fills the current viewport: `lines` stretched over it, drawn as antialiased strokes
    // `lineWidth` texels wide in `line` over `background` (as render::PixelMask::strokeCoverage).
    void draw(const LinesTexture& lines, double lineWidth, QColor line, QColor background);

private:
    std::unique_ptr<QOpenGLShaderProgram> m_program;
    std::unique_ptr<QOpenGLVertexArrayObject> m_vertexArray;
};

} // namespace lw::gui
