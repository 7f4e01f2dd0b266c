#pragma once

// What several sub-commands read from their arguments the same way: lists, sizes, views and the
// input volume. Arguments (arguments.h) splits the command line; these give the values meaning.

#include "arguments.h"
#include "lw/evaluation/view_sweep.h"
#include "lw/input/open_input.h"
#include "lw/volume/volume.h"

#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lw::cli {

// "a,b,c" -> {"a", "b", "c"}; empty parts are kept unless `keepEmpty` is false.
std::vector<std::string> splitList(const std::string& text, char separator = ',',
                                   bool keepEmpty = true);
// Numbers separated by `separator`; throws core::Error(subject, ...) naming a part that is not one.
// The median of `values` (the mean of the two middle ones for an even count; 0 for none): what
// the measuring commands report beside the worst view.
double medianOf(std::vector<double> values);

std::vector<double> parseNumbers(const std::string& text, char separator,
                                 const std::string& subject);

// parseDims and dimsText come from lw::input (the phantom specs parse the same way).
using input::dimsText;
using input::parseDims;
// parseDims for an option's value; throws core::Error("OPTION TEXT", ...) when it does not parse.
glm::ivec3 parseDimsOption(const std::string& option, const std::string& text, int minimum);

// "WxH" with whole numbers in [minimum, 16384]; throws core::Error("OPTION TEXT", ...) otherwise.
glm::ivec2 parseImageSize(const std::string& option, const std::string& text, int minimum);
// "--view AZ,EL" in degrees: {azimuth, elevation}; throws core::Error otherwise.
glm::dvec2 parseView(const std::string& text);

// The views a command measures at: `--view AZ,EL` one view (single), `--views sweep|N` the first
// N views of evaluation::viewSweep (faces, edges, corners, then seeded random ones; `sweep` =
// evaluation::kDefaultSweepViewCount), neither: the first `defaultCount`. Throws UsageError for
// both, a malformed value or |EL| > 90.
struct ViewChoice {
    std::vector<evaluation::View> views;
    bool single = false;
};
ViewChoice parseViewChoice(const Arguments& arguments, int defaultCount);

// `--max-volume-gib G`: the most one volume may take, in GiB (default: half the physical memory,
// core::ImportLimits); the refusals then say how to raise it. Throws UsageError for a value
// that is not a positive number.
inline constexpr const char* kMaxVolumeOption = "max-volume-gib";
core::ImportLimits importLimits(const Arguments& arguments);

// The INPUT of `render` (lw::input::openInput, shared with the GUI): phantom:N | phantom:NXxNYxNZ
// (optionally :ct or :sphere), a volume
// file (NRRD, NIfTI, PVM, raw), or, in a DICOM build, a DICOM folder / DICOMDIR / file, where
// `seriesUid` picks the series (default: the one with the most slices).
// `limits`: importLimits(arguments) of the command.
volume::Volume loadInput(const std::string& input, const std::optional<std::string>& seriesUid,
                         const core::ImportLimits& limits);
// The same with what the input says about itself (description, DICOM patient/study/series).
input::OpenedVolume openCliInput(const std::string& input,
                                 const std::optional<std::string>& seriesUid,
                                 const core::ImportLimits& limits);

} // namespace lw::cli
