#pragma once

// GL function access for the GL sources of lw_render.
//
// We call the core-profile entry points directly (GL_GLEXT_PROTOTYPES + glcorearb.h) and link
// glvnd's libOpenGL instead of loading pointers through eglGetProcAddress: libOpenGL exports every
// core function and dispatches to the vendor of whatever context is current on the thread (Mesa or
// NVIDIA under EGL, or the GUI's QOpenGLWidget context through libGLX), so the same code serves
// every GlContext without a loader, a function table to keep in sync, or per-context state.

#ifndef GL_GLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES 1
#endif
#include <GL/glcorearb.h>
#include <string>

namespace lw::render::gl {

// "GL_INVALID_OPERATION" etc.
const char* glErrorName(GLenum error);

// Throws core::Error("OpenGL", "<what>: <error names>") when glGetError reports anything;
// drains the whole error queue so one failure is not reported again by the next check.
void checkGlError(const char* what);

} // namespace lw::render::gl
