#pragma once

// What `quality` measured at each view, and its report: the table (per view, worst, median,
// goals) and the JSON rows. The measures themselves are lw::evaluation's (line_quality.h).

#include "lw/evaluation/line_quality.h"
#include "lw/evaluation/view_sweep.h"
#include "lw/render/pixel_mask.h"

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace lw::cli {

struct ViewQuality {
    evaluation::View view;
    std::size_t outlinePixels = 0;
    // Index = method (1, 2, 3); empty where the method was not drawn (method 1 without GL).
    std::optional<evaluation::OutlineCoverage> coverage[4];
    std::optional<evaluation::FragmentShare> fragments[4];
    evaluation::FragmentShare unprunedFragments3; // method 3 before stroke pruning
    std::optional<evaluation::LineAgreement> agree13;
    evaluation::LineAgreement agree23; // method 2 with its along-segment test
};

// The measures of one view. `lines[m]` is method m's drawing (width 0: not drawn); `speckled`
// is method 3's before stroke pruning.
ViewQuality measureLines(const evaluation::View& view, const render::PixelMask& outline,
                         const render::PixelMask (&lines)[4], const render::PixelMask& speckled);

// What the report says about the run besides the rows.
struct QualityRun {
    std::string input;
    std::string description;
    std::string sampling; // samplingDescription (panel_rendering.h): the grid drawn
    double iso = 0.0;
    int minStrokePixels = 0;
    bool method2AlongSegment = true; // method 2's test: along each segment, else its endpoints
    int width = 0;
    int height = 0;
    std::vector<std::string> notes;
};

void writeQualityTable(const QualityRun& run, const std::vector<ViewQuality>& rows,
                       std::ostream& out);
void writeQualityJson(const QualityRun& run, const std::vector<ViewQuality>& rows,
                      std::ostream& out);

} // namespace lw::cli
