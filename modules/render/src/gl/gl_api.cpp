#include "gl_api.h"

#include "lw/core/error.h"

namespace lw::render::gl {

const char* glErrorName(GLenum error) {
    switch (error) {
    case GL_NO_ERROR:
        return "GL_NO_ERROR";
    case GL_INVALID_ENUM:
        return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
        return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
        return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
        return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY:
        return "GL_OUT_OF_MEMORY";
    case GL_STACK_UNDERFLOW:
        return "GL_STACK_UNDERFLOW";
    case GL_STACK_OVERFLOW:
        return "GL_STACK_OVERFLOW";
    default:
        return "unknown GL error";
    }
}

void checkGlError(const char* what) {
    std::string errors;
    // Bounded: a lost context can report GL_CONTEXT_LOST forever.
    for (int i = 0; i < 16; ++i) {
        const GLenum error = glGetError();
        if (error == GL_NO_ERROR)
            break;
        if (!errors.empty())
            errors += ", ";
        errors += glErrorName(error);
    }
    if (!errors.empty())
        throw core::Error("OpenGL", std::string(what) + ": " + errors);
}

} // namespace lw::render::gl
