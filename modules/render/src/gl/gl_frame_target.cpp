#include "lw/render/gl_frame_target.h"

#include "gl_api.h"
#include "lw/core/error.h"

#include <string>
#include <vector>

namespace lw::render {

GlFrameTarget::GlFrameTarget(int width, int height) : m_width(width), m_height(height) {
    if (width <= 0 || height <= 0)
        throw core::Error("GL frame target",
                          "empty size " + std::to_string(width) + " x " + std::to_string(height));
    gl::checkGlError("before GlFrameTarget"); // someone else's error is not ours
    GLint bound = 0;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    m_texture = GlTexture::create();
    glBindTexture(GL_TEXTURE_2D, m_texture.get());
    // Immutable storage: CUDA registers the texture once, and nothing may reallocate it after.
    glTexStorage2D(GL_TEXTURE_2D, 1, GL_R8, width, height);
    // A mask is sampled texel for texel: no filtering may blend a line into its neighbours.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    const std::vector<std::uint8_t> off(std::size_t(width) * std::size_t(height), 0);
    GLint alignment = 4;
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RED, GL_UNSIGNED_BYTE, off.data());
    glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
    glBindTexture(GL_TEXTURE_2D, GLuint(bound));
    gl::checkGlError("GlFrameTarget"); // a throw here deletes the texture with m_texture
}

// A CUDA registration must not outlive the texture: m_attachment, declared after m_texture, is
// destroyed first.
GlFrameTarget::~GlFrameTarget() = default;

PixelMask GlFrameTarget::read() const {
    PixelMask mask(m_width, m_height);
    GLint bound = 0, alignment = 4;
    glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
    glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    glPixelStorei(GL_PACK_ALIGNMENT, 1); // rows of any width, tightly packed like the mask
    glBindTexture(GL_TEXTURE_2D, m_texture.get());
    glGetTexImage(GL_TEXTURE_2D, 0, GL_RED, GL_UNSIGNED_BYTE, mask.pixels().data());
    glBindTexture(GL_TEXTURE_2D, GLuint(bound));
    glPixelStorei(GL_PACK_ALIGNMENT, alignment);
    gl::checkGlError("GlFrameTarget::read");
    return mask;
}

} // namespace lw::render
