#pragma once

// Compiling and linking GLSL programs for lw_render's GL sources (private to src/gl).

#include "lw/render/gl_object.h"

#include <string>
#include <vector>

namespace lw::render::gl {

struct ShaderSource {
    unsigned type; // GL_VERTEX_SHADER, GL_COMPUTE_SHADER, ...
    std::string text;
    const char* name; // the file it came from, for the error message
};

// Compiles every source and links them into one program. Throws core::Error naming the shader
// (with the compiler's log) or the program (with the linker's), having made nothing.
GlProgram linkProgram(const std::vector<ShaderSource>& sources, const char* name);

// `text` with `inserted` after its #version line, which must stay first (how the shared GLSL
// pieces, e.g. silhouette_segment.glsl, go into the shaders that use them).
std::string afterVersionLine(const char* text, const std::string& inserted);

} // namespace lw::render::gl
