#include "lw/render/pixel_mask.h"

#include "lw/core/error.h"

#include <algorithm>
#include <string>

namespace lw::render {

PixelMask::PixelMask(int width, int height) {
    if (width < 0 || height < 0)
        throw core::Error("pixel mask",
                          "invalid size " + std::to_string(width) + "x" + std::to_string(height));
    m_width = width;
    m_height = height;
    m_pixels.assign(std::size_t(width) * std::size_t(height), 0);
}

std::size_t PixelMask::count() const {
    return std::size_t(
        std::count_if(m_pixels.begin(), m_pixels.end(), [](std::uint8_t v) { return v != 0; }));
}

PixelMask PixelMask::dilated(int radius) const {
    if (radius <= 0)
        return *this;
    // Separable: a square max filter is a row pass followed by a column pass.
    PixelMask rows(m_width, m_height);
    for (int y = 0; y < m_height; ++y)
        for (int x = 0; x < m_width; ++x) {
            if (!get(x, y))
                continue;
            for (int dx = std::max(0, x - radius); dx <= std::min(m_width - 1, x + radius); ++dx)
                rows.set(dx, y);
        }
    PixelMask out(m_width, m_height);
    for (int y = 0; y < m_height; ++y)
        for (int x = 0; x < m_width; ++x) {
            if (!rows.get(x, y))
                continue;
            for (int dy = std::max(0, y - radius); dy <= std::min(m_height - 1, y + radius); ++dy)
                out.set(x, dy);
        }
    return out;
}

core::ImageRgba8 PixelMask::toImage(core::Rgba8 on, core::Rgba8 off) const {
    core::ImageRgba8 image(m_width, m_height);
    for (std::size_t i = 0; i < m_pixels.size(); ++i)
        image.pixels()[i] = m_pixels[i] ? on : off;
    return image;
}

PixelMask PixelMask::fromImage(const core::ImageRgba8& image, core::Rgba8 background) {
    PixelMask mask(image.width(), image.height());
    for (std::size_t i = 0; i < image.pixels().size(); ++i) {
        const core::Rgba8 p = image.pixels()[i];
        mask.m_pixels[i] =
            (p.r != background.r || p.g != background.g || p.b != background.b) ? 1 : 0;
    }
    return mask;
}

} // namespace lw::render
