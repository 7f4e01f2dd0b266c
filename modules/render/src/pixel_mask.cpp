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

namespace {

// Visits the groups of on pixels of `pixels` (width x height) whose members lie within
// Chebyshev distance `reach` of each other (1: 8-connected): fn(group) with the pixel indices of
// each group. `seen` is scratch of the same size.
template <typename Fn>
void forEachComponent(const std::vector<std::uint8_t>& pixels, int width, int height, int reach,
                      Fn&& fn) {
    std::vector<std::uint8_t> seen(pixels.size(), 0);
    std::vector<std::size_t> group, stack;
    for (std::size_t start = 0; start < pixels.size(); ++start) {
        if (!pixels[start] || seen[start])
            continue;
        group.clear();
        stack.assign(1, start);
        seen[start] = 1;
        while (!stack.empty()) {
            const std::size_t i = stack.back();
            stack.pop_back();
            group.push_back(i);
            const int x = int(i % std::size_t(width)), y = int(i / std::size_t(width));
            for (int dy = -reach; dy <= reach; ++dy)
                for (int dx = -reach; dx <= reach; ++dx) {
                    const int nx = x + dx, ny = y + dy;
                    if (nx < 0 || ny < 0 || nx >= width || ny >= height)
                        continue;
                    const std::size_t n = std::size_t(ny) * std::size_t(width) + std::size_t(nx);
                    if (pixels[n] && !seen[n]) {
                        seen[n] = 1;
                        stack.push_back(n);
                    }
                }
        }
        fn(group);
    }
}

} // namespace

std::size_t PixelMask::removeComponentsSmallerThan(int minPixels, int gapPixels) {
    std::size_t removed = 0;
    if (minPixels <= 1)
        return removed;
    const int reach = 1 + std::max(0, gapPixels);
    forEachComponent(m_pixels, m_width, m_height, reach,
                     [&](const std::vector<std::size_t>& group) {
                         if (group.size() >= std::size_t(minPixels))
                             return;
                         for (const std::size_t i : group)
                             m_pixels[i] = 0;
                         removed += group.size();
                     });
    return removed;
}

std::vector<std::size_t> PixelMask::componentSizes(int gapPixels) const {
    std::vector<std::size_t> sizes;
    forEachComponent(m_pixels, m_width, m_height, 1 + std::max(0, gapPixels),
                     [&](const std::vector<std::size_t>& group) { sizes.push_back(group.size()); });
    return sizes;
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
