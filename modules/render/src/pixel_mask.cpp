#include "lw/render/pixel_mask.h"

#include "lw/core/error.h"
#include "lw/kernels/stroke_components.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <glm/vec2.hpp>
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

// Union-find over numbered items whose labels point to a number no larger than their own (the
// device's rules, lw/kernels/stroke_components.h), so a group's root is its smallest number.
// Run in sequence (one thread), a root stays a root until join() changes it: no
// compare-and-swap is needed.
class LowestRootUnion {
public:
    explicit LowestRootUnion(std::size_t items) : m_label(items) {
        for (std::uint32_t i = 0; i < m_label.size(); ++i)
            m_label[i] = i;
    }
    std::uint32_t root(std::uint32_t item) { return kernels::strokeRoot(m_label.data(), item); }
    // Joins the group whose root is `root` with the group of `other`; returns the joined root.
    std::uint32_t joinRoot(std::uint32_t root, std::uint32_t other) {
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
    void join(std::uint32_t a, std::uint32_t b) { joinRoot(root(a), b); }

private:
    std::vector<std::uint32_t> m_label;
};

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
// A group's root is the run of its first pixel in raster order. Each earlier row is walked with
// a cursor that only moves right. With visibility off a frame has some 10^5 line pixels in 10^6,
// pruned on every frame: runs are a third to a quarter of the pixels, and nothing the size of
// the image is allocated. With `trackPieces` the same walk also unites the 8-connected pieces
// (pieces()), which stroke pruning needs after it has bridged the gaps.
class StrokeGroups {
public:
    struct Run {
        std::uint32_t y, first, last; // line pixels (first..last, y)
        std::uint32_t length() const { return last - first + 1; }
    };

    StrokeGroups(const std::vector<std::uint8_t>& pixels, int width, int height, int reach,
                 bool trackPieces = false)
        : m_reach(std::uint32_t(reach)), m_rowBegin(std::size_t(height) + 1, 0) {
        for (int y = 0; y < height; ++y) {
            const std::uint8_t* row = pixels.data() + std::size_t(y) * std::size_t(width);
            forEachRunOfRow(row, width, [&](int first, int last) {
                m_runs.push_back({std::uint32_t(y), std::uint32_t(first), std::uint32_t(last)});
            });
            m_rowBegin[std::size_t(y) + 1] = std::uint32_t(m_runs.size());
        }
        m_groups = LowestRootUnion(m_runs.size());
        if (trackPieces)
            m_pieces = LowestRootUnion(m_runs.size());
        m_trackPieces = trackPieces;
        m_cursor.resize(std::size_t(reach));
        for (int y = 0; y < height; ++y)
            uniteRow(y);
    }

    const std::vector<Run>& runs() const { return m_runs; }
    std::uint32_t root(std::uint32_t run) { return m_groups.root(run); }
    LowestRootUnion& pieces() { return m_pieces; }

    // The pixels of each group, at its root run's number (0 elsewhere).
    std::vector<std::uint32_t> sizesAtRoots() {
        std::vector<std::uint32_t> sizes(m_runs.size(), 0);
        for (std::uint32_t i = 0; i < sizes.size(); ++i)
            sizes[root(i)] += m_runs[i].length();
        return sizes;
    }

    // The run holding line pixel (x, y).
    std::uint32_t runAt(int x, int y) const {
        const auto begin = m_runs.begin() + m_rowBegin[std::size_t(y)];
        const auto end = m_runs.begin() + m_rowBegin[std::size_t(y) + 1];
        const auto after =
            std::upper_bound(begin, end, std::uint32_t(x),
                             [](std::uint32_t v, const Run& r) { return v < r.first; });
        return std::uint32_t(after - m_runs.begin()) - 1;
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
            std::uint32_t root = run, pieceRoot = run; // the run's roots so far
            for (int above = firstRow; above < y; ++above) {
                std::uint32_t& other = m_cursor[std::size_t(y - above - 1)];
                const std::uint32_t rowEnd = m_rowBegin[std::size_t(above) + 1];
                while (other < rowEnd && m_runs[other].last + m_reach < r.first)
                    ++other;
                for (std::uint32_t n = other; n < rowEnd && m_runs[n].first <= r.last + m_reach;
                     ++n) {
                    root = m_groups.joinRoot(root, n);
                    if (m_trackPieces && above == y - 1 && m_runs[n].first <= r.last + 1 &&
                        m_runs[n].last + 1 >= r.first)
                        pieceRoot = m_pieces.joinRoot(pieceRoot, n);
                }
            }
            // Runs of one row are never 8-connected (a gap parts them): groups only.
            for (std::uint32_t n = run; n > begin && m_runs[n - 1].last + m_reach >= r.first; --n)
                root = m_groups.joinRoot(root, n - 1);
        }
    }

    std::uint32_t m_reach;
    bool m_trackPieces = false;
    std::vector<Run> m_runs;               // raster order
    std::vector<std::uint32_t> m_rowBegin; // row y's runs are [m_rowBegin[y], m_rowBegin[y+1])
    LowestRootUnion m_groups{0};
    LowestRootUnion m_pieces{0};
    std::vector<std::uint32_t> m_cursor; // per earlier row: its first run that may still join
};

int reachOfGap(int gapPixels) {
    return 1 + std::max(0, gapPixels);
}

// A pixel to draw between two stroke ends (kernels::bridgesStrokeEnds) and the two line pixels
// of its ring, the ends it joins.
struct Bridge {
    glm::ivec2 at, endA, endB;
};

// Raster order (row, then column), the order the bridges are kept in.
bool rasterBefore(glm::ivec2 a, glm::ivec2 b) {
    return a.y < b.y || (a.y == b.y && a.x < b.x);
}

// The bridges beside the given stroke ends: a bridge lies beside a stroke end, so only the ends'
// neighbours are tried; all are found before any is drawn, as on the device. Sorted by pixel,
// each once.
std::vector<Bridge> bridgesBeside(const std::vector<std::uint8_t>& pixels, int width, int height,
                                  const std::vector<glm::ivec2>& ends) {
    std::vector<Bridge> bridges;
    for (const glm::ivec2 end : ends)
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const glm::ivec2 p = end + glm::ivec2(dx, dy);
                if (!kernels::bridgesStrokeEnds(pixels.data(), width, height, p.x, p.y))
                    continue;
                Bridge bridge{p, {}, {}};
                int found = 0;
                for (int ry = -1; ry <= 1; ++ry)
                    for (int rx = -1; rx <= 1; ++rx)
                        if ((rx || ry) &&
                            kernels::isLinePixel(pixels.data(), width, height, p.x + rx, p.y + ry))
                            (found++ == 0 ? bridge.endA : bridge.endB) = p + glm::ivec2(rx, ry);
                bridges.push_back(bridge);
            }
    std::sort(bridges.begin(), bridges.end(),
              [](const Bridge& a, const Bridge& b) { return rasterBefore(a.at, b.at); });
    bridges.erase(std::unique(bridges.begin(), bridges.end(),
                              [](const Bridge& a, const Bridge& b) { return a.at == b.at; }),
                  bridges.end());
    return bridges;
}

std::size_t clearRun(std::vector<std::uint8_t>& pixels, int width, const StrokeGroups::Run& run) {
    std::memset(pixels.data() + std::size_t(run.y) * std::size_t(width) + run.first, 0,
                run.length());
    return run.length();
}

// Clears the runs of the groups under `minPixels`; kept[i]: run i stays. Returns the pixels
// cleared.
std::size_t clearShortGroups(StrokeGroups& groups, int minPixels, std::vector<std::uint8_t>& pixels,
                             int width, std::vector<std::uint8_t>& kept) {
    const std::vector<std::uint32_t> sizes = groups.sizesAtRoots();
    kept.assign(groups.runs().size(), 1);
    std::size_t removed = 0;
    for (std::uint32_t i = 0; i < groups.runs().size(); ++i)
        if (sizes[groups.root(i)] < std::uint32_t(minPixels)) {
            removed += clearRun(pixels, width, groups.runs()[i]);
            kept[i] = 0;
        }
    return removed;
}

// The stroke ends among the kept runs: a run's inner pixels have two line neighbours, so only
// its first and last pixels can be one. Counted on the pruned mask (a removed pixel's neighbours
// were in its group and went with it, so a kept pixel's count is the same).
std::vector<glm::ivec2> keptStrokeEnds(const std::vector<std::uint8_t>& pixels, int width,
                                       int height, const std::vector<StrokeGroups::Run>& runs,
                                       const std::vector<std::uint8_t>& kept) {
    std::vector<glm::ivec2> ends;
    for (std::size_t i = 0; i < runs.size(); ++i) {
        if (!kept[i])
            continue;
        for (const std::uint32_t x : {runs[i].first, runs[i].last}) {
            if (kernels::lineNeighbourCount(pixels.data(), width, height, int(x), int(runs[i].y)) <=
                1)
                ends.push_back({int(x), int(runs[i].y)});
            if (runs[i].first == runs[i].last)
                break;
        }
    }
    return ends;
}

// The sizes of the kept runs' 8-connected pieces once the bridges are drawn, at the pieces' root
// runs; pieceOf[b]: a run of bridge b's piece. A bridge joins the pieces of its two ends, and
// bridges side by side join theirs (the later four of the eight around a bridge; the bridges
// are sorted by pixel).
std::vector<std::uint32_t> piecesWithBridges(StrokeGroups& groups,
                                             const std::vector<std::uint8_t>& kept,
                                             const std::vector<Bridge>& bridges,
                                             std::vector<std::uint32_t>& pieceOf) {
    LowestRootUnion& pieces = groups.pieces();
    pieceOf.resize(bridges.size());
    for (std::size_t b = 0; b < bridges.size(); ++b) {
        pieceOf[b] = groups.runAt(bridges[b].endA.x, bridges[b].endA.y);
        pieces.join(pieceOf[b], groups.runAt(bridges[b].endB.x, bridges[b].endB.y));
    }
    for (std::size_t b = 0; b < bridges.size(); ++b)
        for (const glm::ivec2 step :
             {glm::ivec2(1, 0), glm::ivec2(-1, 1), glm::ivec2(0, 1), glm::ivec2(1, 1)}) {
            const glm::ivec2 n = bridges[b].at + step;
            const auto other = std::lower_bound(
                bridges.begin() + std::ptrdiff_t(b), bridges.end(), n,
                [](const Bridge& bridge, glm::ivec2 p) { return rasterBefore(bridge.at, p); });
            if (other != bridges.end() && other->at == n)
                pieces.join(pieceOf[b], pieceOf[std::size_t(other - bridges.begin())]);
        }
    std::vector<std::uint32_t> sizes(groups.runs().size(), 0);
    for (std::uint32_t i = 0; i < groups.runs().size(); ++i)
        if (kept[i])
            sizes[pieces.root(i)] += groups.runs()[i].length();
    for (std::size_t b = 0; b < bridges.size(); ++b)
        ++sizes[pieces.root(pieceOf[b])];
    return sizes;
}

} // namespace

std::vector<std::uint8_t> PixelMask::strokeCoverage(double lineWidth) const {
    const double reach = strokeReach(lineWidth);
    const int radius = strokeRadius(lineWidth);
    std::vector<std::uint8_t> out(m_pixels.size(), 0);
    if (radius == 0) { // one pixel wide (or less): the mask itself
        std::transform(m_pixels.begin(), m_pixels.end(), out.begin(),
                       [](std::uint8_t on) { return std::uint8_t(on ? 255 : 0); });
        return out;
    }
    // The coverage an on pixel gives each offset within the radius, as a byte.
    const int side = 2 * radius + 1;
    std::vector<std::uint8_t> stamp(std::size_t(side) * std::size_t(side));
    for (int dy = -radius; dy <= radius; ++dy)
        for (int dx = -radius; dx <= radius; ++dx) {
            const double coverage =
                std::clamp(reach - std::hypot(double(dx), double(dy)), 0.0, 1.0);
            stamp[std::size_t(dy + radius) * std::size_t(side) + std::size_t(dx + radius)] =
                std::uint8_t(std::lround(coverage * 255.0));
        }
    forEachLinePixel(m_pixels, m_width, m_height, [&](int x, int y) {
        for (int dy = std::max(-radius, -y); dy <= std::min(radius, m_height - 1 - y); ++dy) {
            const std::uint8_t* stampRow =
                stamp.data() + std::size_t(dy + radius) * std::size_t(side);
            std::uint8_t* row = out.data() + index(0, y + dy);
            for (int dx = std::max(-radius, -x); dx <= std::min(radius, m_width - 1 - x); ++dx)
                row[x + dx] = std::max(row[x + dx], stampRow[dx + radius]);
        }
    });
    return out;
}

std::size_t PixelMask::removeComponentsSmallerThan(int minPixels, int gapPixels) {
    if (minPixels <= 1 || m_pixels.empty())
        return 0;
    StrokeGroups groups(m_pixels, m_width, m_height, reachOfGap(gapPixels));
    std::vector<std::uint8_t> kept;
    return clearShortGroups(groups, minPixels, m_pixels, m_width, kept);
}

std::size_t PixelMask::bridgeStrokeEnds() {
    std::vector<glm::ivec2> ends;
    forEachLinePixel(m_pixels, m_width, m_height, [&](int x, int y) {
        if (kernels::lineNeighbourCount(m_pixels.data(), m_width, m_height, x, y) <= 1)
            ends.push_back({x, y});
    });
    const std::vector<Bridge> bridges = bridgesBeside(m_pixels, m_width, m_height, ends);
    for (const Bridge& bridge : bridges)
        set(bridge.at.x, bridge.at.y);
    return bridges.size();
}

std::size_t PixelMask::pruneStrokes(int minPixels, int gapPixels) {
    if (minPixels <= 1 || m_pixels.empty())
        return 0;
    if (gapPixels < 1) // strokes are the 8-connected groups
        return removeComponentsSmallerThan(minPixels, 0);
    // The three steps in one walk over the runs (groups and pieces together), each as its own
    // pass over the mask would do it: the groups within the gap go when short; the bridges are
    // found on what stays; the 8-connected pieces, joined by the bridges, go when under half
    // the length (kernels::minPiecePixels).
    StrokeGroups groups(m_pixels, m_width, m_height, reachOfGap(gapPixels), true);
    const std::vector<StrokeGroups::Run>& runs = groups.runs();
    std::vector<std::uint8_t> kept;
    std::size_t removed = clearShortGroups(groups, minPixels, m_pixels, m_width, kept);
    const std::vector<Bridge> bridges = bridgesBeside(
        m_pixels, m_width, m_height, keptStrokeEnds(m_pixels, m_width, m_height, runs, kept));
    std::vector<std::uint32_t> pieceOf;
    const std::vector<std::uint32_t> pieceSizes = piecesWithBridges(groups, kept, bridges, pieceOf);
    LowestRootUnion& pieces = groups.pieces();
    const int pieceMin = kernels::minPiecePixels(minPixels);
    for (std::uint32_t i = 0; i < runs.size(); ++i)
        if (kept[i] && pieceSizes[pieces.root(i)] < std::uint32_t(pieceMin))
            removed += clearRun(m_pixels, m_width, runs[i]);
    for (std::size_t b = 0; b < bridges.size(); ++b)
        if (pieceSizes[pieces.root(pieceOf[b])] >= std::uint32_t(pieceMin))
            set(bridges[b].at.x, bridges[b].at.y);
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
