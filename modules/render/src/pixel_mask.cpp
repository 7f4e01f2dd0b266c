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

// fn(first, last) for each run of consecutive line pixels of a row, skipping eight off pixels
// at a time: a line drawing is mostly empty, and strokes are pruned on every frame.
template <typename Fn> void forEachRunOfRow(const std::uint8_t* row, int width, Fn&& fn) {
    int x = 0;
    while (x < width) {
        if (x + 8 <= width) {
            std::uint64_t word;
            std::memcpy(&word, row + x, sizeof word);
            if (word == 0) {
                x += 8;
                continue;
            }
        }
        if (!row[x]) {
            ++x;
            continue;
        }
        int last = x;
        while (last + 1 < width && row[last + 1])
            ++last;
        fn(x, last);
        x = last + 2; // the pixel after a run is off
    }
}

// visit(x, y) for each line pixel of a mask, row by row.
template <typename Visit>
void forEachLinePixel(const std::vector<std::uint8_t>& pixels, int width, int height,
                      Visit&& visit) {
    for (int y = 0; y < height; ++y)
        forEachRunOfRow(pixels.data() + std::size_t(y) * std::size_t(width), width,
                        [&](int first, int last) {
                            for (int x = first; x <= last; ++x)
                                visit(x, y);
                        });
}

// The groups of line pixels whose members lie within Chebyshev distance `reach` of each other
// (1: 8-connected), as a union-find over the mask's runs (a row's consecutive line pixels),
// numbered in raster order:
//
//     row y-2:  . a a a . . . . b b       run r = [first, last] of row y unites with the runs
//     row y-1:  . . . . . . . . . .       of the `reach` rows above that overlap
//     row y  :  c . r r r . . . . .       [first - reach, last + reach], and with the runs to
//                                         its left in its own row ending at first - reach or
//     reach 2: r joins a and c, not b     later: every pair of neighbours is united once, by
//                                         the later of the two.
//
// The labels follow the device's rules (lw/kernels/stroke_components.h), with run numbers for
// labels: a label points to a number no larger than its own, so a group's root is the run of
// its first pixel in raster order. Each earlier row is walked with a cursor that only moves
// right. With visibility off a frame has some 10^5 line pixels in 10^6, pruned on every frame:
// runs are a third to a quarter of the pixels, and nothing the size of the image is allocated.
class StrokeGroups {
public:
    struct Run {
        std::uint32_t y, first, last; // line pixels (first..last, y)
        std::uint32_t length() const { return last - first + 1; }
    };

    StrokeGroups(const std::vector<std::uint8_t>& pixels, int width, int height, int reach)
        : m_reach(std::uint32_t(reach)), m_rowBegin(std::size_t(height) + 1, 0) {
        for (int y = 0; y < height; ++y) {
            const std::uint8_t* row = pixels.data() + std::size_t(y) * std::size_t(width);
            forEachRunOfRow(row, width, [&](int first, int last) {
                m_runs.push_back({std::uint32_t(y), std::uint32_t(first), std::uint32_t(last)});
            });
            m_rowBegin[std::size_t(y) + 1] = std::uint32_t(m_runs.size());
        }
        m_label.resize(m_runs.size());
        for (std::uint32_t i = 0; i < m_label.size(); ++i)
            m_label[i] = i;
        m_cursor.resize(std::size_t(reach));
        for (int y = 0; y < height; ++y)
            uniteRow(y);
    }

    const std::vector<Run>& runs() const { return m_runs; }
    std::uint32_t root(std::uint32_t run) { return kernels::strokeRoot(m_label.data(), run); }

    // The pixels of each group, at its root run's number (0 elsewhere).
    std::vector<std::uint32_t> sizesAtRoots() {
        std::vector<std::uint32_t> sizes(m_runs.size(), 0);
        for (std::uint32_t i = 0; i < sizes.size(); ++i)
            sizes[root(i)] += m_runs[i].length();
        return sizes;
    }

private:
    void uniteRow(int y) {
        const std::uint32_t begin = m_rowBegin[std::size_t(y)];
        const std::uint32_t end = m_rowBegin[std::size_t(y) + 1];
        const int firstRow = std::max(0, y - int(m_reach));
        for (int above = firstRow; above < y; ++above)
            m_cursor[std::size_t(y - above - 1)] = m_rowBegin[std::size_t(above)];
        for (std::uint32_t run = begin; run < end; ++run) {
            const Run& r = m_runs[run];
            std::uint32_t root = run; // the run's root so far: joins hook onto it
            for (int above = firstRow; above < y; ++above) {
                std::uint32_t& other = m_cursor[std::size_t(y - above - 1)];
                const std::uint32_t rowEnd = m_rowBegin[std::size_t(above) + 1];
                while (other < rowEnd && m_runs[other].last + m_reach < r.first)
                    ++other;
                for (std::uint32_t n = other; n < rowEnd && m_runs[n].first <= r.last + m_reach;
                     ++n)
                    root = join(root, n);
            }
            for (std::uint32_t n = run; n > begin && m_runs[n - 1].last + m_reach >= r.first; --n)
                root = join(root, n - 1);
        }
    }

    // Joins root `root` with the group of run `other`; returns the joined group's root. The
    // larger root is hooked onto the smaller, so labels keep pointing down. In sequence (one
    // thread) a root stays a root until this changes it, so no compare-and-swap is needed.
    std::uint32_t join(std::uint32_t root, std::uint32_t other) {
        const std::uint32_t otherRoot = this->root(other);
        if (otherRoot == root)
            return root;
        if (otherRoot < root) {
            m_label[root] = otherRoot;
            return otherRoot;
        }
        m_label[otherRoot] = root;
        return root;
    }

    std::uint32_t m_reach;
    std::vector<Run> m_runs;               // raster order
    std::vector<std::uint32_t> m_rowBegin; // row y's runs are [m_rowBegin[y], m_rowBegin[y+1])
    std::vector<std::uint32_t> m_label;
    std::vector<std::uint32_t> m_cursor; // per earlier row: its first run that may still join
};

int reachOfGap(int gapPixels) {
    return 1 + std::max(0, gapPixels);
}

// Draws the bridges (kernels::bridgesStrokeEnds) beside the given stroke ends: a bridge lies
// beside a stroke end, so only the ends' neighbours are tried; all are found before any is
// drawn, as on the device.
std::size_t drawBridgesBeside(std::vector<std::uint8_t>& pixels, int width, int height,
                              const std::vector<std::size_t>& ends) {
    std::vector<std::size_t> bridges;
    for (const std::size_t end : ends) {
        const int x = int(end % std::size_t(width)), y = int(end / std::size_t(width));
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx)
                if (kernels::bridgesStrokeEnds(pixels.data(), width, height, x + dx, y + dy))
                    bridges.push_back(std::size_t(y + dy) * std::size_t(width) +
                                      std::size_t(x + dx));
    }
    std::size_t drawn = 0;
    for (const std::size_t i : bridges)
        if (!pixels[i]) {
            pixels[i] = 1;
            ++drawn;
        }
    return drawn;
}

} // namespace

std::size_t PixelMask::removeComponentsSmallerThan(int minPixels, int gapPixels) {
    return removeStrokesSmallerThan(minPixels, gapPixels, nullptr);
}

std::size_t PixelMask::removeStrokesSmallerThan(int minPixels, int gapPixels,
                                                std::vector<std::size_t>* strokeEnds) {
    if (minPixels <= 1 || m_pixels.empty())
        return 0;
    StrokeGroups groups(m_pixels, m_width, m_height, reachOfGap(gapPixels));
    const std::vector<std::uint32_t> sizes = groups.sizesAtRoots();
    std::size_t removed = 0;
    for (std::uint32_t i = 0; i < groups.runs().size(); ++i) {
        const StrokeGroups::Run run = groups.runs()[i];
        if (sizes[groups.root(i)] >= std::uint32_t(minPixels))
            continue;
        std::memset(m_pixels.data() + index(int(run.first), int(run.y)), 0, run.length());
        removed += run.length();
    }
    if (strokeEnds) {
        // A run's inner pixels have two line neighbours: only its first and last pixels can
        // be stroke ends. Counted on the pruned mask (a removed pixel's neighbours were in its
        // group and went with it, so a kept pixel's count is the same).
        for (const StrokeGroups::Run run : groups.runs())
            for (const std::uint32_t x : {run.first, run.last}) {
                if (m_pixels[index(int(x), int(run.y))] &&
                    kernels::lineNeighbourCount(m_pixels.data(), m_width, m_height, int(x),
                                                int(run.y)) <= 1)
                    strokeEnds->push_back(index(int(x), int(run.y)));
                if (run.first == run.last)
                    break;
            }
    }
    return removed;
}

std::size_t PixelMask::bridgeStrokeEnds() {
    std::vector<std::size_t> ends;
    forEachLinePixel(m_pixels, m_width, m_height, [&](int x, int y) {
        if (kernels::lineNeighbourCount(m_pixels.data(), m_width, m_height, x, y) <= 1)
            ends.push_back(index(x, y));
    });
    return drawBridgesBeside(m_pixels, m_width, m_height, ends);
}

std::size_t PixelMask::pruneStrokes(int minPixels, int gapPixels) {
    if (minPixels <= 1)
        return 0;
    std::vector<std::size_t> ends;
    const std::size_t removed =
        removeStrokesSmallerThan(minPixels, gapPixels, gapPixels >= 1 ? &ends : nullptr);
    if (gapPixels >= 1)
        drawBridgesBeside(m_pixels, m_width, m_height, ends);
    return removed;
}

std::vector<std::size_t> PixelMask::componentSizes(int gapPixels) const {
    std::vector<std::size_t> sizes;
    if (m_pixels.empty())
        return sizes;
    StrokeGroups groups(m_pixels, m_width, m_height, reachOfGap(gapPixels));
    const std::vector<std::uint32_t> atRoots = groups.sizesAtRoots();
    for (const std::uint32_t size : atRoots)
        if (size > 0)
            sizes.push_back(size);
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
