#include "lw/input/open_input.h"

#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/volume/phantom.h"
#include "lw/volume/volume_reader.h"

#ifdef LINEWORK_HAVE_DICOM
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"
#endif

#include <charconv>
#include <cstdio>
#include <string_view>

namespace lw::input {
namespace {

constexpr core::LogCategory kLog("lw.input");

OpenedVolume openPhantom(const std::string& spec, const core::ImportLimits& limits,
                         core::Progress* progress) {
    const std::string body = spec.substr(std::string("phantom:").size());
    const auto colon = body.find(':');
    const volume::PhantomKind kind =
        volume::parsePhantomKind(colon == std::string::npos ? "ct" : body.substr(colon + 1));
    const std::optional<glm::ivec3> dims = parseDims(body.substr(0, colon), 2, 4096);
    if (!dims)
        throw core::Error(
            spec,
            "expected phantom:N or phantom:NXxNYxNZ (2..4096) with an optional :ct or :sphere");
    OpenedVolume opened;
    opened.volume = volume::makePhantom(*dims, kind, 0, limits, progress);
    opened.source = spec;
    opened.description =
        "phantom " + std::string(volume::phantomKindName(kind)) + " " + dimsText(*dims);
    if (progress)
        progress->report(1.0, "Phantom ready");
    return opened;
}

#ifdef LINEWORK_HAVE_DICOM
// Scanning is the first fifth of the work, decoding the rest.
core::Progress subProgress(core::Progress* parent, double from, double to) {
    if (!parent)
        return {};
    return core::Progress(
        [parent, from, to](double fraction, const std::string& message) {
            parent->report(from + (to - from) * fraction, message);
        },
        parent->cancelToken());
}

// The plan already words tilt, uneven gaps and missing slices; add the series' own warnings and
// the files that could not be used.
std::vector<std::string> planWarnings(const dicom::VolumePlan& plan,
                                      const dicom::SeriesAssembly& assembly) {
    std::vector<std::string> warnings;
    warnings.insert(warnings.end(), plan.warnings.begin(), plan.warnings.end());
    warnings.insert(warnings.end(), assembly.warnings.begin(), assembly.warnings.end());
    for (const dicom::FileError& error : assembly.errors)
        warnings.push_back(error.file + ": " + error.reason);
    return warnings;
}

const dicom::SeriesInfo& chooseSeries(const dicom::DicomIndex& index, const std::string& path,
                                      const OpenOptions& options) {
    if (options.seriesUid) {
        const dicom::SeriesInfo* series = index.findSeries(*options.seriesUid);
        if (!series)
            throw core::Error(path, "no series with UID " + *options.seriesUid);
        return *series;
    }
    const dicom::SeriesInfo* chosen = nullptr;
    for (const dicom::SeriesInfo* series : index.allSeries())
        if (!chosen || series->instances.size() > chosen->instances.size())
            chosen = series;
    if (!chosen || chosen->instances.empty()) {
        std::string reason = "no DICOM image series found";
        if (!index.errors.empty())
            reason += " (" + std::to_string(index.errors.size()) +
                      " files failed, first: " + index.errors.front().file + ": " +
                      index.errors.front().reason + ")";
        throw core::Error(path, reason);
    }
    return *chosen;
}

DicomIdentity identityOf(const dicom::InstanceInfo& first) {
    DicomIdentity identity;
    identity.patientName = first.patientName;
    identity.patientId = first.patientId;
    identity.patientBirthDate = first.patientBirthDate;
    identity.patientSex = first.patientSex;
    identity.studyInstanceUid = first.studyInstanceUid;
    identity.studyId = first.studyId;
    identity.studyDate = first.studyDate;
    identity.studyTime = first.studyTime;
    identity.studyDescription = first.studyDescription;
    identity.accessionNumber = first.accessionNumber;
    identity.seriesInstanceUid = first.seriesInstanceUid;
    identity.seriesDescription = first.seriesDescription;
    identity.modality = first.modality;
    identity.seriesNumber = first.seriesNumber;
    return identity;
}

OpenedVolume assemble(const dicom::DicomIndex& index, const std::string& path,
                      const OpenOptions& options, core::Progress* progress) {
    const dicom::SeriesInfo& series = chooseSeries(index, path, options);
    const dicom::SeriesAssembly assembly = dicom::planVolumes(series);
    const dicom::VolumePlan* plan = nullptr;
    for (const dicom::VolumePlan& candidate : assembly.volumes)
        if (!plan || candidate.slices.size() > plan->slices.size())
            plan = &candidate;
    if (!plan)
        throw core::Error(path, "series " + series.seriesInstanceUid +
                                    " holds no volume that can be assembled");
    if (plan->dims.z < 2)
        throw core::Error(path, "series " + series.seriesInstanceUid +
                                    " has a single slice; an iso-surface needs two");
    kLog.info("opening series " + series.seriesInstanceUid + " (" +
              std::to_string(plan->slices.size()) + " slices)");
    core::Progress decoding = subProgress(progress, 0.2, 1.0);
    OpenedVolume opened;
    opened.volume =
        dicom::loadVolume(series, *plan, progress ? &decoding : nullptr, options.limits);
    opened.source = path;
    opened.seriesUid = series.seriesInstanceUid;
    const dicom::InstanceInfo& first = series.instances.front();
    opened.description = first.patientName.empty() ? first.patientId : first.patientName;
    if (!series.description.empty())
        opened.description += (opened.description.empty() ? "" : " — ") + series.description;
    opened.description +=
        (opened.description.empty() ? "" : " — ") + series.modality + " " + dimsText(plan->dims);
    opened.dicom = identityOf(first);
    opened.warnings = planWarnings(*plan, assembly);
    for (const dicom::FileError& error : index.errors)
        opened.warnings.push_back(error.file + ": " + error.reason);
    return opened;
}

OpenedVolume openDicom(const std::string& path, const OpenOptions& options,
                       core::Progress* progress) {
    core::Progress scanning = subProgress(progress, 0.0, 0.2);
    const dicom::DicomIndex index = dicom::scanDicom(path, progress ? &scanning : nullptr);
    if (progress)
        progress->throwIfCancelled();
    return assemble(index, path, options, progress);
}
#endif

} // namespace

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

std::string dimsText(glm::ivec3 d) {
    return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

bool isDicomBuild() {
#ifdef LINEWORK_HAVE_DICOM
    return true;
#else
    return false;
#endif
}

OpenedVolume openInput(const std::string& path, const OpenOptions& options,
                       core::Progress* progress) {
    // A request already cancelled (a newer one took its place) reads nothing.
    if (progress)
        progress->throwIfCancelled();
    if (path.rfind("phantom:", 0) == 0)
        return openPhantom(path, options.limits, progress);
#ifdef LINEWORK_HAVE_DICOM
    if (dicom::looksLikeDicomInput(path) ||
        volume::detectVolumeFormat(path) == volume::VolumeFormat::Unknown)
        return openDicom(path, options, progress);
#else
    if (options.seriesUid)
        throw core::Error(path, "a series UID was given, but this build reads no DICOM "
                                "(LINEWORK_DICOM off)");
#endif
    if (progress)
        progress->report(0.0, "Reading " + path);
    OpenedVolume opened;
    opened.volume = volume::readVolumeFile(path, progress, options.limits);
    if (progress)
        progress->throwIfCancelled();
    opened.source = path;
    opened.description =
        std::filesystem::path(path).filename().string() + " " + dimsText(opened.volume.dims());
    return opened;
}

OpenedVolume openDicomFiles(const std::vector<std::filesystem::path>& files,
                            const OpenOptions& options, core::Progress* progress) {
#ifdef LINEWORK_HAVE_DICOM
    const std::string subject =
        options.seriesUid ? "series " + *options.seriesUid : std::string("the series' files");
    if (files.empty())
        throw core::Error(subject, "has no files");
    std::vector<std::string> missing;
    for (const std::filesystem::path& file : files) {
        std::error_code ec;
        if (!std::filesystem::exists(file, ec))
            missing.push_back(file.string());
    }
    if (!missing.empty()) {
        std::string reason = std::to_string(missing.size()) + " of " +
                             std::to_string(files.size()) +
                             " files are missing (moved or "
                             "deleted since the import?), e.g. ";
        for (std::size_t i = 0; i < std::min<std::size_t>(3, missing.size()); ++i)
            reason += (i ? ", " : "") + missing[i];
        throw core::Error(subject, reason);
    }
    core::Progress scanning = subProgress(progress, 0.0, 0.2);
    const dicom::DicomIndex index = dicom::scanDicomFiles(files, progress ? &scanning : nullptr);
    if (progress)
        progress->throwIfCancelled();
    return assemble(index, subject, options, progress);
#else
    (void)files;
    (void)options;
    (void)progress;
    throw core::Error("DICOM", "this build reads no DICOM (LINEWORK_DICOM off)");
#endif
}

} // namespace lw::input
