#include "cli_inputs.h"

#include "arguments.h"
#include "lw/core/error.h"
#include "lw/input/open_input.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <sstream>

namespace lw::cli {

double medianOf(std::vector<double> values) {
    if (values.empty())
        return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t half = values.size() / 2;
    return values.size() % 2 ? values[half] : 0.5 * (values[half - 1] + values[half]);
}

std::vector<std::string> splitList(const std::string& text, char separator, bool keepEmpty) {
    std::vector<std::string> parts;
    std::stringstream stream(text);
    std::string part;
    while (std::getline(stream, part, separator))
        if (keepEmpty || !part.empty())
            parts.push_back(part);
    return parts;
}

std::vector<double> parseNumbers(const std::string& text, char separator,
                                 const std::string& subject) {
    std::vector<double> values;
    for (const std::string& part : splitList(text, separator)) {
        double value = 0.0;
        const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), value);
        if (part.empty() || error != std::errc() || end != part.data() + part.size())
            throw UsageError(subject, "'" + part + "' is not a number");
        values.push_back(value);
    }
    return values;
}

glm::ivec3 parseDimsOption(const std::string& option, const std::string& text, int minimum) {
    const std::optional<glm::ivec3> dims = parseDims(text, minimum);
    if (!dims)
        throw UsageError(option + " " + text,
                         "expected N or NXxNYxNZ with integers >= " + std::to_string(minimum));
    return *dims;
}

glm::ivec2 parseImageSize(const std::string& option, const std::string& text, int minimum) {
    const std::string subject = option + " " + text;
    const std::vector<double> values = parseNumbers(text, 'x', subject);
    const auto valid = [minimum](double v) {
        return v >= minimum && v <= 16384 && v == double(int(v));
    };
    if (values.size() != 2 || !valid(values[0]) || !valid(values[1]))
        throw UsageError(subject, "expected WxH with whole numbers between " +
                                      std::to_string(minimum) + " and 16384");
    return {int(values[0]), int(values[1])};
}

glm::dvec2 parseView(const std::string& text) {
    const std::vector<double> values = parseNumbers(text, ',', "--view " + text);
    if (values.size() != 2)
        throw UsageError("--view " + text, "expected AZ,EL in degrees");
    return {values[0], values[1]};
}

ViewChoice parseViewChoice(const Arguments& arguments, int defaultCount) {
    const auto single = arguments.option("view");
    const auto sweep = arguments.option("views");
    if (single && sweep)
        throw UsageError("--view and --views", "give one view or a sweep, not both");
    ViewChoice choice;
    if (single) {
        const glm::dvec2 parsed = parseView(*single);
        if (std::abs(parsed.y) > 90.0)
            throw UsageError("--view " + *single, "expected AZ,EL in degrees with |EL| <= 90");
        choice.single = true;
        choice.views = {evaluation::View{parsed.x, parsed.y}};
        return choice;
    }
    int count = defaultCount;
    if (sweep) {
        count = evaluation::kDefaultSweepViewCount;
        const auto [end, error] =
            *sweep == "sweep"
                ? std::from_chars_result{sweep->data() + sweep->size(), std::errc()}
                : std::from_chars(sweep->data(), sweep->data() + sweep->size(), count);
        if (error != std::errc() || end != sweep->data() + sweep->size() || count < 1)
            throw UsageError("--views " + *sweep, "expected 'sweep' or a number of views >= 1");
    }
    choice.views = evaluation::viewSweep(count);
    return choice;
}

core::ImportLimits importLimits(const Arguments& arguments) {
    core::ImportLimits limits;
    limits.raiseHint = std::string("--") + kMaxVolumeOption + " raises it";
    const double gib = arguments.number(kMaxVolumeOption, 0.0);
    if (arguments.option(kMaxVolumeOption)) {
        // 2^24 GiB (16 PiB) bounds it well inside size_t.
        if (!(gib > 0.0 && gib <= double(1 << 24)))
            throw UsageError(std::string("--") + kMaxVolumeOption,
                             "expected a number of GiB above 0");
        limits.maxBytes = std::size_t(gib * double(std::size_t(1) << 30));
    }
    return limits;
}

input::OpenedVolume openCliInput(const std::string& input,
                                 const std::optional<std::string>& seriesUid,
                                 const core::ImportLimits& limits) {
    input::OpenOptions options;
    options.seriesUid = seriesUid;
    options.limits = limits;
    return input::openInput(input, options);
}

volume::Volume loadInput(const std::string& input, const std::optional<std::string>& seriesUid,
                         const core::ImportLimits& limits) {
    return openCliInput(input, seriesUid, limits).volume;
}

} // namespace lw::cli
