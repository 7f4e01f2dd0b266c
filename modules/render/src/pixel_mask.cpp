#include "lw/render/pixel_mask.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/stroke_components.h"

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstring>
#include <memory>
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
    // `pixels`: `height` rows of `width` bytes (a whole mask, or a band of its rows).
    ComponentFinder(const std::uint8_t* pixels, int width, int height, int reach)
        : m_reach(reach), m_width(width), m_framedWidth(std::size_t(width) + 2 * reach),
          m_framed(m_framedWidth * (std::size_t(height) + 2 * reach), 0) {
        for (int y = 0; y < height; ++y) {
            const std::uint8_t* row = pixels + std::size_t(y) * std::size_t(width);
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
    ComponentFinder finder(m_pixels.data(), m_width, m_height, 1 + std::max(0, gapPixels));
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

// fn(i, x, y) for each on pixel of rows [firstRow, endRow), skipping empty runs eight bytes at a
// time (line pixels are a few percent of a frame).
template <typename Fn>
void forEachOnPixel(const std::uint8_t* pixels, int width, int firstRow, int endRow, Fn&& fn) {
    const std::size_t end = std::size_t(endRow) * std::size_t(width);
    for (std::size_t i = std::size_t(firstRow) * std::size_t(width); i < end;) {
        if (i + 8 <= end) {
            std::uint64_t word = 0;
            std::memcpy(&word, pixels + i, 8);
            if (word == 0) {
                i += 8;
                continue;
            }
        }
        if (pixels[i])
            fn(i, int(i % std::size_t(width)), int(i / std::size_t(width)));
        ++i;
    }
}

// Bands of at least this many rows (more than any stroke gap's reach), one per thread at most.
constexpr int kMinBandRows = 64;

} // namespace

// Bands of rows in parallel, each grouped by the flood fill above (every pixel's label is its
// band group's first pixel, the group's size kept there); one thread then joins the groups that
// meet across band edges by union-find over those labels (kernels/common/stroke_components.h)
// and adds their sizes at the joined roots; the short groups are cleared in parallel, reading
// labels only.
std::size_t PixelMask::removeComponentsSmallerThan(int minPixels, int gapPixels, unsigned threads) {
    const unsigned workers = threads == 0 ? core::workerCount() : threads;
    const int bands = std::min(int(workers), m_height / kMinBandRows);
    if (minPixels <= 1 || m_pixels.empty() || bands < 2 ||
        m_pixels.size() >= std::size_t(kernels::kNotAStrokePixel))
        return removeComponentsSmallerThan(minPixels, gapPixels);
    const int reach = 1 + std::max(0, gapPixels);
    const std::size_t n = m_pixels.size();
    const std::unique_ptr<std::uint32_t[]> labels(new std::uint32_t[n]);
    const std::unique_ptr<std::uint32_t[]> sizes(new std::uint32_t[n]);
    std::vector<std::vector<std::uint32_t>> bandRoots(static_cast<std::size_t>(bands));
    const auto firstRow = [&](int band) { return int(std::int64_t(band) * m_height / bands); };
    core::parallelFor(
        std::size_t(bands),
        [&](std::size_t b) {
            const int from = firstRow(int(b));
            const std::size_t offset = std::size_t(from) * std::size_t(m_width);
            ComponentFinder finder(m_pixels.data() + offset, m_width, firstRow(int(b) + 1) - from,
                                   reach);
            finder.forEach([&](const std::vector<std::size_t>& group) {
                const auto root = std::uint32_t(offset + finder.originalIndex(group[0]));
                for (const std::size_t member : group)
                    labels[offset + finder.originalIndex(member)] = root;
                sizes[root] = std::uint32_t(group.size());
                bandRoots[b].push_back(root);
            });
        },
        workers);
    const kernels::LabelCompareAndSwap swap;
    for (int b = 1; b < bands; ++b)
        forEachOnPixel(m_pixels.data(), m_width, firstRow(b),
                       std::min(firstRow(b) + reach, firstRow(b + 1)),
                       [&](std::size_t, int x, int y) {
                           kernels::uniteWithEarlierNeighbours(
                               m_pixels.data(), labels.get(), m_width, m_height, reach, x, y, swap);
                       });
    for (const std::vector<std::uint32_t>& roots : bandRoots)
        for (const std::uint32_t root : roots)
            if (const std::uint32_t joined = kernels::strokeRoot(labels.get(), root);
                joined != root)
                sizes[joined] += sizes[root];
    std::atomic<std::size_t> removed{0};
    core::parallelFor(
        std::size_t(bands),
        [&](std::size_t b) {
            std::size_t cleared = 0;
            forEachOnPixel(m_pixels.data(), m_width, firstRow(int(b)), firstRow(int(b) + 1),
                           [&](std::size_t i, int, int) {
                               const std::uint32_t root =
                                   kernels::strokeRootReadOnly(labels.get(), std::uint32_t(i));
                               if (sizes[root] < std::uint32_t(minPixels)) {
                                   m_pixels[i] = 0;
                                   ++cleared;
                               }
                           });
            removed += cleared;
        },
        workers);
    return removed;
}

std::vector<std::size_t> PixelMask::componentSizes(int gapPixels) const {
    std::vector<std::size_t> sizes;
    if (m_pixels.empty())
        return sizes;
    ComponentFinder finder(m_pixels.data(), m_width, m_height, 1 + std::max(0, gapPixels));
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
