#include "lw/volume/slice_contour.h"

#include "lw/core/parallel.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace lw::volume {
namespace {

// One cell of marching squares, its corners and edges numbered clockwise on the image
// (x right, y down), so edge e joins corner e and corner e + 1 and corner c lies between edges
// c - 1 and c:
//
//      corner 0 ── edge 0 ── corner 1
//         │                     │
//      edge 3                 edge 1
//         │                     │
//      corner 3 ── edge 2 ── corner 2
//
struct Cell {
    std::array<double, 4> value;
    std::array<glm::dvec2, 4> corner;
};

constexpr std::array<glm::ivec2, 4> kCornerOffset = {glm::ivec2{0, 0}, glm::ivec2{1, 0},
                                                     glm::ivec2{1, 1}, glm::ivec2{0, 1}};

// Where the iso-value crosses edge e, by linear interpolation between its corners.
glm::dvec2 crossing(const Cell& cell, int e, double iso) {
    const int a = e, b = (e + 1) % 4;
    const double t = (iso - cell.value[std::size_t(a)]) /
                     (cell.value[std::size_t(b)] - cell.value[std::size_t(a)]);
    return cell.corner[std::size_t(a)] +
           t * (cell.corner[std::size_t(b)] - cell.corner[std::size_t(a)]);
}

// The cell's segments: two crossed edges are joined; four (a saddle) are paired so that each
// segment cuts off a corner on the other side from the cell's centre, the mean of its corners.
void contourCell(const Cell& cell, double iso, std::vector<ContourSegment>& out) {
    std::array<bool, 4> inside{};
    for (std::size_t c = 0; c < 4; ++c)
        inside[c] = cell.value[c] >= iso;
    std::array<int, 4> crossed{};
    int count = 0;
    for (int e = 0; e < 4; ++e)
        if (inside[std::size_t(e)] != inside[std::size_t((e + 1) % 4)])
            crossed[std::size_t(count++)] = e;
    if (count == 2) {
        out.push_back({crossing(cell, crossed[0], iso), crossing(cell, crossed[1], iso)});
        return;
    }
    if (count != 4)
        return;
    const double mean = 0.25 * (cell.value[0] + cell.value[1] + cell.value[2] + cell.value[3]);
    const bool centreInside = mean >= iso;
    for (int c = 0; c < 4; ++c)
        if (inside[std::size_t(c)] != centreInside)
            out.push_back({crossing(cell, (c + 3) % 4, iso), crossing(cell, c, iso)});
}

void contourRow(const SliceImage& image, int y, double iso, std::vector<ContourSegment>& out) {
    const int width = image.geometry.size.x;
    for (int x = 0; x + 1 < width; ++x) {
        Cell cell;
        bool defined = true;
        for (std::size_t c = 0; c < 4; ++c) {
            const glm::ivec2 at = glm::ivec2(x, y) + kCornerOffset[c];
            cell.value[c] = image.at(at.x, at.y);
            cell.corner[c] = glm::dvec2(at);
            defined = defined && !std::isnan(cell.value[c]);
        }
        if (defined)
            contourCell(cell, iso, out);
    }
}

} // namespace

std::vector<ContourSegment> isoContour(const SliceImage& image, double iso) {
    const int height = image.geometry.size.y;
    if (height < 2 || image.geometry.size.x < 2 ||
        image.values.size() != std::size_t(image.geometry.size.x) * std::size_t(height))
        return {};
    // Bands of rows on the pool, joined in order: the result does not depend on the threads.
    constexpr std::size_t kRowsPerBand = 32;
    const std::size_t cellRows = std::size_t(height - 1);
    std::vector<std::vector<ContourSegment>> bands((cellRows + kRowsPerBand - 1) / kRowsPerBand);
    core::parallelFor(bands.size(), [&](std::size_t band) {
        const std::size_t end = std::min(cellRows, (band + 1) * kRowsPerBand);
        for (std::size_t y = band * kRowsPerBand; y < end; ++y)
            contourRow(image, int(y), iso, bands[band]);
    });
    std::vector<ContourSegment> segments;
    for (const auto& band : bands)
        segments.insert(segments.end(), band.begin(), band.end());
    return segments;
}

} // namespace lw::volume
