#include "gl_program.h"

#include "gl_api.h"
#include "lw/core/error.h"

#include <algorithm>

namespace lw::render::gl {

namespace {

// A shader's or program's info log: getParameter is glGetShaderiv or glGetProgramiv, getLog the
// matching glGet*InfoLog.
template <typename GetParameter, typename GetLog>
std::string infoLog(GLuint object, GetParameter getParameter, GetLog getLog) {
    GLint length = 0;
    getParameter(object, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    getLog(object, GLsizei(log.size()), nullptr, log.data());
    return log.c_str();
}

GlShader compileShader(GLenum type, const std::string& source, const char* name) {
    GlShader shader = GlShader::create(type);
    const char* text = source.c_str();
    glShaderSource(shader.get(), 1, &text, nullptr);
    glCompileShader(shader.get());
    GLint ok = GL_FALSE;
    glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &ok);
    if (!ok)
        throw core::Error(std::string("shader ") + name,
                          "compile failed: " +
                              infoLog(shader.get(), glGetShaderiv, glGetShaderInfoLog));
    return shader;
}

} // namespace

GlProgram linkProgram(const std::vector<ShaderSource>& sources, const char* name) {
    std::vector<GlShader> shaders;
    for (const ShaderSource& source : sources)
        shaders.push_back(compileShader(source.type, source.text, source.name));
    GlProgram program = GlProgram::create();
    for (const GlShader& shader : shaders)
        glAttachShader(program.get(), shader.get());
    glLinkProgram(program.get());
    // The program keeps the compiled code; the shader objects go when `shaders` does.
    for (const GlShader& shader : shaders)
        glDetachShader(program.get(), shader.get());
    GLint ok = GL_FALSE;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &ok);
    if (!ok)
        throw core::Error(std::string("GL program ") + name,
                          "link failed: " +
                              infoLog(program.get(), glGetProgramiv, glGetProgramInfoLog));
    gl::checkGlError(name);
    return program;
}

std::string afterVersionLine(const char* text, const std::string& inserted) {
    std::string result(text);
    const std::size_t lineEnd = result.find('\n');
    result.insert(lineEnd == std::string::npos ? result.size() : lineEnd + 1, inserted);
    return result;
}

} // namespace lw::render::gl
