#include "lw/render/pixel_mask.h"

#include "lw/core/error.h"
#include "lw/kernels/stroke_components.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

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

// The groups of on pixels whose members lie within Chebyshev distance `reach` of each other (1:
// 8-connected), found by flood fill over a copy framed by `reach` empty pixels, so that no
// neighbour needs a bounds check and a pixel's neighbours are fixed index offsets. Stroke
// pruning runs on every frame after the methods have drawn, over every line pixel: with
// visibility off that is some 10^5 pixels a frame, and this is what keeps it a few ms.
class ComponentFinder {
public:
    ComponentFinder(const std::vector<std::uint8_t>& pixels, int width, int height, int reach)
        : m_reach(reach), m_width(width), m_framedWidth(std::size_t(width) + 2 * reach),
          m_framed(m_framedWidth * (std::size_t(height) + 2 * reach), 0) {
        for (int y = 0; y < height; ++y) {
            const std::uint8_t* row = pixels.data() + std::size_t(y) * std::size_t(width);
            std::uint8_t* out = m_framed.data() + framedIndex(0, y);
            for (int x = 0; x < width; ++x)
                out[x] = row[x] != 0 ? kUnvisited : 0;
        }
        for (int dy = -reach; dy <= reach; ++dy)
            for (int dx = -reach; dx <= reach; ++dx)
                if (dx != 0 || dy != 0)
                    m_offsets.push_back(std::ptrdiff_t(dy) * std::ptrdiff_t(m_framedWidth) + dx);
    }

    // fn(group): the framed indices of each group's pixels (originalIndex() maps them back).
    template <typename Fn> void forEach(Fn&& fn) {
        std::vector<std::size_t> group;
        const std::uint8_t* begin = m_framed.data();
        const std::size_t size = m_framed.size();
        for (std::size_t start = 0; start < size; ++start) {
            // Line pixels are a few percent of the image: memchr skips the rest fast.
            const void* found = std::memchr(begin + start, kUnvisited, size - start);
            if (!found)
                break;
            start = std::size_t(static_cast<const std::uint8_t*>(found) - begin);
            group.assign(1, start);
            m_framed[start] = kVisited;
            // The group itself is the work list: members are appended as they are found.
            for (std::size_t next = 0; next < group.size(); ++next) {
                const std::size_t i = group[next];
                for (const std::ptrdiff_t offset : m_offsets) {
                    const std::size_t n = std::size_t(std::ptrdiff_t(i) + offset);
                    if (m_framed[n] == kUnvisited) {
                        m_framed[n] = kVisited;
                        group.push_back(n);
                    }
                }
            }
            fn(group);
        }
    }

    std::size_t originalIndex(std::size_t framed) const {
        const std::size_t x = framed % m_framedWidth - std::size_t(m_reach);
        const std::size_t y = framed / m_framedWidth - std::size_t(m_reach);
        return y * std::size_t(m_width) + x;
    }

private:
    static constexpr std::uint8_t kUnvisited = 1, kVisited = 2;
    std::size_t framedIndex(int x, int y) const {
        return (std::size_t(y) + std::size_t(m_reach)) * m_framedWidth + std::size_t(x) +
               std::size_t(m_reach);
    }

    int m_reach;
    int m_width;
    std::size_t m_framedWidth;
    std::vector<std::uint8_t> m_framed;
    std::vector<std::ptrdiff_t> m_offsets;
};

} // namespace

std::size_t PixelMask::removeComponentsSmallerThan(int minPixels, int gapPixels) {
    std::size_t removed = 0;
    if (minPixels <= 1 || m_pixels.empty())
        return removed;
    ComponentFinder finder(m_pixels, m_width, m_height, 1 + std::max(0, gapPixels));
    finder.forEach([&](const std::vector<std::size_t>& group) {
        if (group.size() >= std::size_t(minPixels))
            return;
        for (const std::size_t i : group)
            m_pixels[finder.originalIndex(i)] = 0;
        removed += group.size();
    });
    return removed;
}

namespace {

// The line pixels of a mask row by row, skipping eight off pixels at a time: a line drawing is
// mostly empty, and the bridges are looked for on every frame.
template <typename Visit>
void forEachLinePixel(const std::vector<std::uint8_t>& pixels, int width, int height,
                      Visit&& visit) {
    for (int y = 0; y < height; ++y) {
        const std::uint8_t* rowStart = pixels.data() + std::size_t(y) * std::size_t(width);
        int x = 0;
        while (x < width) {
            if (x + 8 <= width) {
                std::uint64_t word;
                std::memcpy(&word, rowStart + x, sizeof word);
                if (word == 0) {
                    x += 8;
                    continue;
                }
            }
            if (rowStart[x])
                visit(x, y);
            ++x;
        }
    }
}

} // namespace

std::size_t PixelMask::bridgeStrokeEnds() {
    // A bridge lies beside a stroke end, so only the ends' neighbours are tried; all are found
    // before any is drawn, as on the device.
    std::vector<std::size_t> bridges;
    const std::uint8_t* mask = m_pixels.data();
    forEachLinePixel(m_pixels, m_width, m_height, [&](int x, int y) {
        if (kernels::lineNeighbourCount(mask, m_width, m_height, x, y) > 1)
            return;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (kernels::bridgesStrokeEnds(mask, m_width, m_height, x + dx, y + dy))
                    bridges.push_back(index(x + dx, y + dy));
    });
    std::size_t drawn = 0;
    for (const std::size_t i : bridges)
        if (!m_pixels[i]) {
            m_pixels[i] = 1;
            ++drawn;
        }
    return drawn;
}

std::size_t PixelMask::pruneStrokes(int minPixels, int gapPixels) {
    if (minPixels <= 1)
        return 0;
    const std::size_t removed = removeComponentsSmallerThan(minPixels, gapPixels);
    if (gapPixels >= 1)
        bridgeStrokeEnds();
    return removed;
}

std::vector<std::size_t> PixelMask::componentSizes(int gapPixels) const {
    std::vector<std::size_t> sizes;
    if (m_pixels.empty())
        return sizes;
    ComponentFinder finder(m_pixels, m_width, m_height, 1 + std::max(0, gapPixels));
    finder.forEach([&](const std::vector<std::size_t>& group) { sizes.push_back(group.size()); });
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
