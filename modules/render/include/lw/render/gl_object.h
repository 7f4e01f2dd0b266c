#pragma once

// One owner for each OpenGL object: a GlObject holds one name (a program, buffer, vertex array,
// texture, framebuffer or query) and deletes it when it is destroyed or reset. GL objects belong
// to the context that made them (or one sharing with it), so whoever owns a GlObject destroys it
// while that context is current: the GUI when the panel's context announces aboutToBeDestroyed,
// a headless renderer before its EGL context goes. There is no release() to keep in step with the
// code that creates the objects: an object that was never made deletes nothing, and an exception
// half-way through a set-up frees what was made so far.
// Public header without GL types: names are `unsigned` (GLuint), shader types GLenum values.
// Only for builds with the GL pipeline (LINEWORK_GL=1); the definitions are in src/gl/.

#include <utility>

namespace lw::render {

enum class GlObjectType { Shader, Program, Buffer, VertexArray, Texture, Framebuffer, Query };

namespace detail {
// glCreateShader(shaderType) / glCreateProgram / glGen*; throws core::Error when GL gives no name.
unsigned createGlObject(GlObjectType type, unsigned shaderType);
void deleteGlObject(GlObjectType type, unsigned name) noexcept;
} // namespace detail

template <GlObjectType Type> class GlObject {
public:
    GlObject() = default;
    // Takes over `name` (0: none).
    explicit GlObject(unsigned name) noexcept : m_name(name) {}
    // A new object in the current context; `shaderType` (GL_VERTEX_SHADER ...) only for shaders.
    static GlObject create(unsigned shaderType = 0) {
        return GlObject(detail::createGlObject(Type, shaderType));
    }
    ~GlObject() { reset(); }
    GlObject(GlObject&& other) noexcept : m_name(std::exchange(other.m_name, 0u)) {}
    GlObject& operator=(GlObject&& other) noexcept {
        if (this != &other) {
            reset();
            m_name = std::exchange(other.m_name, 0u);
        }
        return *this;
    }
    GlObject(const GlObject&) = delete;
    GlObject& operator=(const GlObject&) = delete;

    unsigned get() const noexcept { return m_name; }
    explicit operator bool() const noexcept { return m_name != 0; }
    // Deletes the object now (the context current); the wrapper then holds none.
    void reset() noexcept {
        if (m_name != 0)
            detail::deleteGlObject(Type, m_name);
        m_name = 0;
    }

private:
    unsigned m_name = 0;
};

using GlShader = GlObject<GlObjectType::Shader>;
using GlProgram = GlObject<GlObjectType::Program>;
using GlBuffer = GlObject<GlObjectType::Buffer>;
using GlVertexArray = GlObject<GlObjectType::VertexArray>;
using GlTexture = GlObject<GlObjectType::Texture>;
using GlFramebuffer = GlObject<GlObjectType::Framebuffer>;
using GlQuery = GlObject<GlObjectType::Query>;

} // namespace lw::render
