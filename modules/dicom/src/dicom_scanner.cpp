#include "lw/dicom/dicom_scanner.h"

#include "dicom_file.h"
#include "dicomdir_reader.h"
#include "folder_walk.h"
#include "instance_grouping.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/core/module_boundary.h"
#include "scan_paths.h"

#include <algorithm>
#include <string_view>

// The scan entries: what the input is (a folder, a DICOMDIR, one file, a list of files) and
// which of folder_walk, dicomdir_reader and instance_grouping it goes through.

namespace fs = std::filesystem;

namespace lw::dicom {

using namespace detail;

namespace {

const core::LogCategory kLog("lw.dicom");

DicomIndex scanDicomdir(const fs::path& dicomdir, core::Progress* progress,
                        const core::ImportLimits& limits) {
    DicomIndex index;
    index.fromDicomdir = true;
    DicomdirState state;
    state.root = dicomdir.parent_path().empty() ? fs::path(".") : dicomdir.parent_path();
    state.canonicalRoot = canonicalOrAbsolute(state.root);
    state.progress = progress;
    index.root = state.root;
    walkDicomdir(dicomdir, state, 0, true);

    index.errors = std::move(state.errors);
    index.warnings = std::move(state.warnings);
    std::sort(state.files.begin(), state.files.end());
    finishIndex(index, state.files, progress, limits);

    std::size_t seriesWithoutFiles = 0;
    for (const auto& uid : state.listedSeries) {
        const SeriesInfo* series = index.findSeries(uid);
        if (series == nullptr || series->instances.empty())
            ++seriesWithoutFiles;
    }
    addListedSeries(index, state);
    if (seriesWithoutFiles > 0)
        index.warnings.push_back("DICOMDIR lists " + std::to_string(state.listedSeries.size()) +
                                 " series; " + std::to_string(seriesWithoutFiles) +
                                 " of them have no readable file");
    kLog.info("DICOMDIR " + dicomdir.string() + ": " + std::to_string(index.instanceCount()) +
              " instances in " + std::to_string(index.seriesCount()) + " series, " +
              std::to_string(index.errors.size()) + " file errors");
    return index;
}

} // namespace

std::size_t DicomIndex::seriesCount() const {
    std::size_t count = 0;
    for (const auto& patient : patients)
        for (const auto& study : patient.studies)
            count += study.series.size();
    return count;
}

std::size_t DicomIndex::instanceCount() const {
    std::size_t count = 0;
    for (const auto* series : allSeries())
        count += series->instances.size();
    return count;
}

const SeriesInfo* DicomIndex::findSeries(std::string_view seriesInstanceUid) const {
    for (const auto* series : allSeries())
        if (series->seriesInstanceUid == seriesInstanceUid)
            return series;
    return nullptr;
}

std::vector<const SeriesInfo*> DicomIndex::allSeries() const {
    std::vector<const SeriesInfo*> result;
    for (const auto& patient : patients)
        for (const auto& study : patient.studies)
            for (const auto& series : study.series)
                result.push_back(&series);
    return result;
}

static DicomIndex scanDicomUnguarded(const fs::path& path, core::Progress* progress,
                                     const core::ImportLimits& limits) {
    std::error_code ec;
    const auto status = fs::status(path, ec);
    if (ec || !fs::exists(status))
        throw core::Error(path.string(), "does not exist");

    if (fs::is_directory(status)) {
        WalkState walk;
        walk.progress = progress;
        walkFolder(path, walk);
        std::sort(walk.files.begin(), walk.files.end());
        DicomIndex index;
        index.root = path;
        index.errors = std::move(walk.errors);
        finishIndex(index, walk.files, progress, limits);
        kLog.info("scanned " + path.string() + ": " + std::to_string(index.filesExamined) +
                  " files, " + std::to_string(index.instanceCount()) + " instances in " +
                  std::to_string(index.seriesCount()) + " series, " +
                  std::to_string(index.errors.size()) + " file errors");
        return index;
    }
    if (!fs::is_regular_file(status))
        throw core::Error(path.string(), "is neither a folder nor a regular file");

    // A file named DICOMDIR is parsed as one even without a meta header saying so.
    if (isNamedDicomdir(path) || safeIsDicomdir(path))
        return scanDicomdir(path, progress, limits);

    // A single file: it is the whole input, so failing to read it fails the scan.
    DicomIndex index;
    index.root = path.parent_path();
    index.filesExamined = 1;
    if (progress)
        progress->setTotal(1, "Reading DICOM header");
    InstanceInfo instance = readInstanceHeader(path, limits);
    if (instance.path.empty())
        instance.path = path.string();
    if (progress)
        progress->step();
    std::vector<InstanceInfo> one;
    one.push_back(std::move(instance));
    index.patients = groupInstances(std::move(one), index.warnings);
    return index;
}

static DicomIndex scanDicomFilesUnguarded(const std::vector<fs::path>& files,
                                          core::Progress* progress,
                                          const core::ImportLimits& limits) {
    DicomIndex index;
    if (!files.empty())
        index.root = files.front().parent_path();
    std::vector<fs::path> present;
    present.reserve(files.size());
    for (const fs::path& file : files) {
        std::error_code ec;
        const fs::file_status status = fs::status(file, ec);
        if (fs::is_regular_file(status))
            present.push_back(file);
        else if (!fs::exists(status))
            index.errors.push_back({file.string(), "file is missing"});
        else
            index.errors.push_back({file.string(), ec ? ec.message() : "not a regular file"});
    }
    // Sorted like a folder scan, so the grouping does not depend on the caller's order.
    std::sort(present.begin(), present.end());
    finishIndex(index, present, progress,
                limits); // adds the read errors and sorts all errors by file
    index.filesExamined = files.size();
    return index;
}

static bool looksLikeDicomInputUnguarded(const fs::path& path) {
    std::error_code ec;
    if (fs::is_directory(path, ec))
        return true;
    if (!fs::is_regular_file(path, ec))
        return false;
    if (isNamedDicomdir(path) || hasDicmMagic(path))
        return true;
    // Files without preamble (ACR-NEMA, stripped meta) or gzip-wrapped ones are recognised by
    // their usual suffixes; volume formats have their own suffixes, so these never clash.
    const std::string name = lower(path.filename().string());
    for (const char* suffix : {".dcm", ".dcm.gz", ".dicom", ".ima"})
        if (name.size() > std::string_view(suffix).size() && name.ends_with(suffix))
            return true;
    return false;
}

// The public entries: nothing but core::Error (naming the input) and core::Cancelled leaves them.
DicomIndex scanDicom(const fs::path& path, core::Progress* progress,
                     const core::ImportLimits& limits) {
    return core::atModuleBoundary(path.string(),
                                  [&] { return scanDicomUnguarded(path, progress, limits); });
}

DicomIndex scanDicomFiles(const std::vector<fs::path>& files, core::Progress* progress,
                          const core::ImportLimits& limits) {
    const std::string subject =
        files.empty() ? std::string("DICOM file list") : files.front().parent_path().string();
    return core::atModuleBoundary(subject,
                                  [&] { return scanDicomFilesUnguarded(files, progress, limits); });
}

bool looksLikeDicomInput(const fs::path& path) {
    return core::atModuleBoundary(path.string(),
                                  [&] { return looksLikeDicomInputUnguarded(path); });
}

} // namespace lw::dicom
