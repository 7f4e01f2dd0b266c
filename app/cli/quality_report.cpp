#include "quality_report.h"

#include "cli_inputs.h"
#include "lw/core/json_writer.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <ostream>

namespace lw::cli {
namespace {

using evaluation::View;

// One number of the report: its JSON key, its table column, which way is better and its goal.
struct Metric {
    const char* key;
    const char* column;
    bool higherIsBetter;
    std::optional<double> goal;
    std::function<std::optional<double>(const ViewQuality&)> value;
};

template <typename T, typename Field>
std::optional<double> fieldOf(const std::optional<T>& measure, Field field) {
    return measure ? std::optional<double>((*measure).*field) : std::nullopt;
}

const std::vector<Metric>& metrics() {
    using evaluation::FragmentShare;
    using evaluation::LineAgreement;
    using evaluation::OutlineCoverage;
    const auto coverage = [](int m) {
        return [m](const ViewQuality& q) {
            return fieldOf(q.coverage[m], &OutlineCoverage::coverage);
        };
    };
    const auto fragments = [](int m) {
        return [m](const ViewQuality& q) { return fieldOf(q.fragments[m], &FragmentShare::share); };
    };
    const auto agree = [](bool m1, double LineAgreement::*field) {
        return [m1, field](const ViewQuality& q) {
            return m1 ? fieldOf(q.agree13, field) : std::optional<double>(q.agree23.*field);
        };
    };
    static const std::vector<Metric> list = {
        {"outline_coverage_m3", "cov3", true, evaluation::kOutlineCoverageGoal, coverage(3)},
        {"outline_coverage_m2", "cov2", true, evaluation::kOutlineCoverageGoal, coverage(2)},
        {"outline_coverage_m1", "cov1", true, evaluation::kOutlineCoverageGoal, coverage(1)},
        {"fragment_share_m3", "frag3", false, evaluation::kFragmentShareGoal, fragments(3)},
        {"fragment_share_m2", "frag2", false, evaluation::kFragmentShareGoal, fragments(2)},
        {"fragment_share_m1", "frag1", false, evaluation::kFragmentShareGoal, fragments(1)},
        {"fragment_share_m3_unpruned", "frag3raw", false, std::nullopt,
         [](const ViewQuality& q) { return std::optional<double>(q.unprunedFragments3.share); }},
        {"agreement_1_in_3", "1in3", true, std::nullopt,
         agree(true, &LineAgreement::firstNearSecond)},
        {"agreement_3_in_1", "3in1", true, std::nullopt,
         agree(true, &LineAgreement::secondNearFirst)},
        {"agreement_13", "1~3", true, evaluation::kAgreementGoalMethods13,
         agree(true, &LineAgreement::minimum)},
        {"agreement_2_in_3", "2in3", true, std::nullopt,
         agree(false, &LineAgreement::firstNearSecond)},
        {"agreement_3_in_2", "3in2", true, std::nullopt,
         agree(false, &LineAgreement::secondNearFirst)},
        {"agreement_23", "2~3", true, evaluation::kAgreementGoalMethods23,
         agree(false, &LineAgreement::minimum)},
    };
    return list;
}

bool meets(const Metric& metric, double value) {
    return !metric.goal || (metric.higherIsBetter ? value >= *metric.goal : value <= *metric.goal);
}

// Worst (the first view in sweep order on a tie) and median over the views that have the value.
struct Spread {
    int views = 0;
    int met = 0;
    double worst = 0.0;
    double median = 0.0;
    View worstView;
};

std::optional<Spread> spreadOf(const Metric& metric, const std::vector<ViewQuality>& rows) {
    Spread spread;
    std::vector<double> values;
    for (const ViewQuality& row : rows) {
        const std::optional<double> value = metric.value(row);
        if (!value)
            continue;
        const bool worse = metric.higherIsBetter ? *value < spread.worst : *value > spread.worst;
        if (values.empty() || worse) {
            spread.worst = *value;
            spread.worstView = row.view;
        }
        spread.met += meets(metric, *value) ? 1 : 0;
        values.push_back(*value);
    }
    if (values.empty())
        return std::nullopt;
    spread.views = int(values.size());
    spread.median = medianOf(std::move(values));
    return spread;
}

std::string viewName(const View& view) {
    char text[48];
    std::snprintf(text, sizeof text, "(%g,%g)", view.azimuthDeg, view.elevationDeg);
    return text;
}

std::string number(std::optional<double> value) {
    char text[16];
    if (!value)
        return "   n/a";
    std::snprintf(text, sizeof text, "%6.4f", *value);
    return text;
}

void writeRow(const std::string& label, const std::string& outline,
              const std::vector<std::optional<double>>& values, std::ostream& out) {
    char head[64];
    std::snprintf(head, sizeof head, "%-15s %8s", label.c_str(), outline.c_str());
    out << head;
    for (const auto& value : values)
        out << ' ' << number(value);
    out << '\n';
}

} // namespace

ViewQuality measureLines(const View& view, const render::PixelMask& outline,
                         const render::PixelMask (&lines)[4], const render::PixelMask& speckled) {
    ViewQuality quality;
    quality.view = view;
    quality.outlinePixels = outline.count();
    for (int m = 1; m <= 3; ++m) {
        if (lines[m].width() == 0)
            continue;
        quality.coverage[m] = evaluation::outlineCoverage(outline, lines[m], 1);
        quality.fragments[m] = evaluation::fragmentShare(lines[m], evaluation::kFragmentPixels);
    }
    quality.unprunedFragments3 = evaluation::fragmentShare(speckled, evaluation::kFragmentPixels);
    if (lines[1].width() > 0)
        quality.agree13 = evaluation::lineAgreement(lines[1], lines[3], 1);
    quality.agree23 = evaluation::lineAgreement(lines[2], lines[3], 1);
    return quality;
}

void writeQualityTable(const QualityRun& run, const std::vector<ViewQuality>& rows,
                       std::ostream& out) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "line quality of %s (%s; %s): iso %g, %dx%d, %zu views, strokes under %d px "
                  "pruned, 1 px tolerance, method 2 tested %s\n",
                  run.input.c_str(), run.description.c_str(), run.sampling.c_str(), run.iso,
                  run.width, run.height, rows.size(), run.minStrokePixels,
                  run.method2AlongSegment ? "along each segment" : "at the segments' endpoints");
    out << line;
    out << "cov = outer outline of the shaded panel within 1 px of a line; frag = line pixels in "
           "groups under "
        << evaluation::kFragmentPixels
        << " px (frag3raw: method 3 before pruning); a~b = min of a in b and b in a\n";
    char head[64];
    std::snprintf(head, sizeof head, "%-15s %8s", "view (az,el)", "outline");
    out << head;
    for (const Metric& metric : metrics()) {
        std::snprintf(line, sizeof line, " %6s", metric.column);
        out << line;
    }
    out << '\n';
    for (const ViewQuality& row : rows) {
        std::vector<std::optional<double>> values;
        for (const Metric& metric : metrics())
            values.push_back(metric.value(row));
        writeRow(viewName(row.view), std::to_string(row.outlinePixels), values, out);
    }
    std::vector<std::optional<double>> worst, median;
    std::vector<std::string> goals;
    for (const Metric& metric : metrics()) {
        const std::optional<Spread> spread = spreadOf(metric, rows);
        worst.push_back(spread ? std::optional(spread->worst) : std::nullopt);
        median.push_back(spread ? std::optional(spread->median) : std::nullopt);
        if (spread && metric.goal) {
            std::snprintf(line, sizeof line, "%s %s %.2f at %d of %d views (worst %.4f at %s)",
                          metric.column, metric.higherIsBetter ? ">=" : "<=", *metric.goal,
                          spread->met, spread->views, spread->worst,
                          viewName(spread->worstView).c_str());
            goals.push_back(line);
        }
    }
    writeRow("worst", "", worst, out);
    writeRow("median", "", median, out);
    for (const std::string& goal : goals)
        out << "goal " << goal << '\n';
    for (const std::string& note : run.notes)
        out << "note: " << note << '\n';
}

void writeQualityJson(const QualityRun& run, const std::vector<ViewQuality>& rows,
                      std::ostream& out) {
    core::JsonWriter writer;
    writer.beginObject();
    writer.field("input", run.input).field("description", run.description).field("iso", run.iso);
    writer.field("sampling", run.sampling);
    writer.field("width", run.width).field("height", run.height);
    writer.field("min_stroke_px", run.minStrokePixels).field("tolerance_px", 1);
    writer.field("method2_test", run.method2AlongSegment ? "along" : "endpoints");
    writer.field("fragment_px", evaluation::kFragmentPixels);
    writer.key("notes").beginArray();
    for (const auto& note : run.notes)
        writer.value(note);
    writer.endArray();
    const auto writeView = [&](const View& view) {
        writer.beginArray().value(view.azimuthDeg).value(view.elevationDeg).endArray();
    };
    writer.key("rows").beginArray();
    for (const ViewQuality& row : rows) {
        writer.beginObject();
        writer.key("view");
        writeView(row.view);
        writer.field("outline_pixels", row.outlinePixels);
        for (int m = 1; m <= 3; ++m) {
            const std::string key = "line_pixels_m" + std::to_string(m);
            if (row.fragments[m])
                writer.field(key, row.fragments[m]->linePixels);
            else
                writer.key(key).null();
        }
        for (const Metric& metric : metrics()) {
            const std::optional<double> value = metric.value(row);
            if (value)
                writer.field(metric.key, *value);
            else
                writer.key(metric.key).null();
        }
        writer.endObject();
    }
    writer.endArray();
    writer.key("summary").beginArray();
    for (const Metric& metric : metrics()) {
        const std::optional<Spread> spread = spreadOf(metric, rows);
        if (!spread)
            continue;
        writer.beginObject().field("metric", metric.key).field("views", spread->views);
        writer.field("worst", spread->worst);
        writer.key("worst_view");
        writeView(spread->worstView);
        writer.field("median", spread->median);
        if (metric.goal)
            writer.field("goal", *metric.goal).field("views_meeting_goal", spread->met);
        writer.endObject();
    }
    writer.endArray();
    writer.endObject();
    out << writer.str() << "\n";
}

} // namespace lw::cli
