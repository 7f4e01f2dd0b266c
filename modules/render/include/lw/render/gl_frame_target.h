#pragma once

// A GL texture a silhouette renderer may draw its lines into instead of host memory: the GUI's
// silhouette panel draws the texture itself, so a frame of method 3 on CUDA never leaves the
// device (SilhouetteSettings::frameTarget; SilhouetteFrame::drewToTarget says whether it did).
// The texture is GL_TEXTURE_2D, GL_R8, of a fixed size; texel (x, y) is mask pixel (x, y), row 0
// at the top as in PixelMask, 0 off and 1 on.
//
// It belongs to the GL context current when it was made (or one sharing with it): that context
// must be current whenever a renderer draws into it and when it is destroyed. What a back-end
// keeps of the texture (CUDA: its interop registration) is an Attachment owned here, so that it
// goes before the texture does. Public header: no GL or CUDA types.

#include "lw/render/gl_object.h"
#include "lw/render/pixel_mask.h"

#include <memory>
#include <utility>

namespace lw::render {

class GlFrameTarget {
public:
    // Makes the texture in the current context (all texels off); throws core::Error on failure.
    GlFrameTarget(int width, int height);
    // Drops the attachment, then deletes the texture (the context current).
    ~GlFrameTarget();
    GlFrameTarget(const GlFrameTarget&) = delete;
    GlFrameTarget& operator=(const GlFrameTarget&) = delete;

    unsigned texture() const { return m_texture.get(); }
    int width() const { return m_width; }
    int height() const { return m_height; }
    // The texels as a mask (read back from GL; for tests and checks, not per frame).
    PixelMask read() const;

    class Attachment {
    public:
        virtual ~Attachment() = default;
    };
    Attachment* attachment() const { return m_attachment.get(); }
    void setAttachment(std::unique_ptr<Attachment> attachment) {
        m_attachment = std::move(attachment);
    }

private:
    GlTexture m_texture;
    int m_width = 0, m_height = 0;
    std::unique_ptr<Attachment> m_attachment; // after the texture: destroyed before it
};

} // namespace lw::render
