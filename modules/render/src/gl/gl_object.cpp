#include "lw/render/gl_object.h"

#include "gl_api.h"
#include "lw/core/error.h"

namespace lw::render::detail {

unsigned createGlObject(GlObjectType type, unsigned shaderType) {
    GLuint name = 0;
    switch (type) {
    case GlObjectType::Shader:
        name = glCreateShader(GLenum(shaderType));
        break;
    case GlObjectType::Program:
        name = glCreateProgram();
        break;
    case GlObjectType::Buffer:
        glGenBuffers(1, &name);
        break;
    case GlObjectType::VertexArray:
        glGenVertexArrays(1, &name);
        break;
    case GlObjectType::Texture:
        glGenTextures(1, &name);
        break;
    case GlObjectType::Framebuffer:
        glGenFramebuffers(1, &name);
        break;
    case GlObjectType::Query:
        glGenQueries(1, &name);
        break;
    }
    // No name means no current context or a lost one; every later call would fail quietly.
    if (name == 0)
        throw core::Error("OpenGL", "no object name was given (is a context current?)");
    return name;
}

void deleteGlObject(GlObjectType type, unsigned name) noexcept {
    switch (type) {
    case GlObjectType::Shader:
        glDeleteShader(name);
        break;
    case GlObjectType::Program:
        glDeleteProgram(name);
        break;
    case GlObjectType::Buffer:
        glDeleteBuffers(1, &name);
        break;
    case GlObjectType::VertexArray:
        glDeleteVertexArrays(1, &name);
        break;
    case GlObjectType::Texture:
        glDeleteTextures(1, &name);
        break;
    case GlObjectType::Framebuffer:
        glDeleteFramebuffers(1, &name);
        break;
    case GlObjectType::Query:
        glDeleteQueries(1, &name);
        break;
    }
}

} // namespace lw::render::detail
