#pragma once

// The image-space search both ground truths share (true_contour.cpp, suggestive_reference.cpp):
// every pair of 4-neighbouring pixels is examined, rows in parallel, and may mark one pixel.

#include "lw/core/parallel.h"
#include "lw/render/pixel_mask.h"

#include <utility>
#include <vector>

namespace lw::evaluation::detail {

// examine(x, y, bx, by, marks) for each pixel (x, y) and its neighbour (bx, by) to the right and
// below; the pixels it appends to `marks` are marked. Marks are collected per row and merged
// afterwards (a pair may mark a pixel of the next row).
template <typename Examine>
render::PixelMask markNeighbourPairs(int width, int height, Examine&& examine) {
    std::vector<std::vector<std::pair<int, int>>> marks(static_cast<std::size_t>(height));
    core::parallelFor(std::size_t(height), [&](std::size_t row) {
        const int y = int(row);
        for (int x = 0; x < width; ++x)
            for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{0, 1}}) {
                const int bx = x + dx, by = y + dy;
                if (bx >= width || by >= height)
                    continue;
                examine(x, y, bx, by, marks[row]);
            }
    });
    render::PixelMask mask(width, height);
    for (const auto& rowMarks : marks)
        for (const auto& [x, y] : rowMarks)
            mask.set(x, y);
    return mask;
}

} // namespace lw::evaluation::detail
