#include "cli_inputs.h"

#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/phantom.h"
#include "lw/volume/volume_reader.h"

#ifdef LINEWORK_HAVE_DICOM
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"
#endif

#include <charconv>
#include <sstream>

namespace lw::cli {
namespace {

constexpr core::LogCategory kLog("lw.cli");

// phantom:N, phantom:NXxNYxNZ, optionally followed by :ct or :sphere.
volume::Volume loadPhantom(const std::string& spec) {
    const std::string body = spec.substr(std::string("phantom:").size());
    const auto colon = body.find(':');
    const render::PhantomKind kind =
        render::parsePhantomKind(colon == std::string::npos ? "ct" : body.substr(colon + 1));
    const std::optional<glm::ivec3> dims = parseDims(body.substr(0, colon), 2, 4096);
    if (!dims)
        throw core::Error(
            spec,
            "expected phantom:N or phantom:NXxNYxNZ (2..4096) with an optional :ct or :sphere");
    return render::makePhantom(*dims, kind);
}

#ifdef LINEWORK_HAVE_DICOM
volume::Volume loadDicom(const std::string& path, const std::optional<std::string>& seriesUid) {
    const dicom::DicomIndex index = dicom::scanDicom(path);
    const dicom::SeriesInfo* chosen = nullptr;
    if (seriesUid) {
        chosen = index.findSeries(*seriesUid);
        if (!chosen)
            throw core::Error(path, "no series with UID " + *seriesUid);
    } else {
        // The series with the most slices: in a CT study that is the diagnostic volume, not a
        // scout or a dose report.
        for (const dicom::SeriesInfo* series : index.allSeries())
            if (!chosen || series->instances.size() > chosen->instances.size())
                chosen = series;
        if (!chosen)
            throw core::Error(path, "no DICOM series found");
    }
    const dicom::SeriesAssembly assembly = dicom::planVolumes(*chosen);
    const dicom::VolumePlan* plan = nullptr;
    for (const dicom::VolumePlan& candidate : assembly.volumes)
        if (!plan || candidate.slices.size() > plan->slices.size())
            plan = &candidate;
    if (!plan)
        throw core::Error(path, "series " + chosen->seriesInstanceUid +
                                    " holds no volume that can be assembled");
    if (plan->dims.z < 2)
        throw core::Error(path, "series " + chosen->seriesInstanceUid +
                                    " has a single slice; an iso-surface needs two");
    kLog.info("rendering series " + chosen->seriesInstanceUid + " (" +
              std::to_string(plan->slices.size()) + " slices)");
    return dicom::loadVolume(*chosen, *plan);
}
#endif

} // namespace

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
            throw core::Error(subject, "'" + part + "' is not a number");
        values.push_back(value);
    }
    return values;
}

std::optional<glm::ivec3> parseDims(std::string_view text, int minimum, int maximum) {
    std::vector<int> parts;
    const char* p = text.data();
    const char* end = text.data() + text.size();
    while (p < end) {
        int value = 0;
        const auto [next, error] = std::from_chars(p, end, value);
        if (error != std::errc() || value < minimum || value > maximum)
            break;
        parts.push_back(value);
        p = next;
        if (p < end && *p == 'x')
            ++p;
        else
            break;
    }
    if (p != end || (parts.size() != 1 && parts.size() != 3))
        return std::nullopt;
    return parts.size() == 1 ? glm::ivec3(parts[0]) : glm::ivec3(parts[0], parts[1], parts[2]);
}

glm::ivec3 parseDimsOption(const std::string& option, const std::string& text, int minimum) {
    const std::optional<glm::ivec3> dims = parseDims(text, minimum);
    if (!dims)
        throw core::Error(option + " " + text,
                          "expected N or NXxNYxNZ with integers >= " + std::to_string(minimum));
    return *dims;
}

std::string dimsText(glm::ivec3 d) {
    return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

glm::ivec2 parseImageSize(const std::string& option, const std::string& text, int minimum) {
    const std::string subject = option + " " + text;
    const std::vector<double> values = parseNumbers(text, 'x', subject);
    const auto valid = [minimum](double v) {
        return v >= minimum && v <= 16384 && v == double(int(v));
    };
    if (values.size() != 2 || !valid(values[0]) || !valid(values[1]))
        throw core::Error(subject, "expected WxH with whole numbers between " +
                                       std::to_string(minimum) + " and 16384");
    return {int(values[0]), int(values[1])};
}

glm::dvec2 parseView(const std::string& text) {
    const std::vector<double> values = parseNumbers(text, ',', "--view " + text);
    if (values.size() != 2)
        throw core::Error("--view " + text, "expected AZ,EL in degrees");
    return {values[0], values[1]};
}

volume::Volume loadInput(const std::string& input, const std::optional<std::string>& seriesUid) {
    if (input.rfind("phantom:", 0) == 0)
        return loadPhantom(input);
#ifdef LINEWORK_HAVE_DICOM
    if (dicom::looksLikeDicomInput(input) ||
        volume::detectVolumeFormat(input) == volume::VolumeFormat::Unknown)
        return loadDicom(input, seriesUid);
#else
    if (seriesUid)
        throw core::Error("--series", "this build reads no DICOM (LINEWORK_DICOM off)");
#endif
    return volume::readVolumeFile(input);
}

} // namespace lw::cli
