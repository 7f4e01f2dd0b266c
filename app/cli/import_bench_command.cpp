// `linework-cli bench-import PATH [--repeat N] [--max-volume-gib G] [--json]`: how fast a DICOM
// input is scanned and every volume in it decoded, for docs/BENCHMARKS.md. Each run starts from
// scratch (scan, plan, load) so the number covers what an import in the app costs; the median
// of N runs is reported because the first run also pays for a cold file cache. The process's
// peak resident memory (getrusage) is reported beside the largest volume.
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/core/error.h"
#include "lw/core/json_writer.h"
#include "lw/core/parallel.h"

#ifdef LINEWORK_HAVE_DICOM
#include "lw/dicom/dicom_scanner.h"
#include "lw/dicom/volume_assembler.h"
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>
#include <sys/resource.h>

namespace lw::cli {

#ifdef LINEWORK_HAVE_DICOM
namespace {

struct ImportRun {
    double scanSeconds = 0.0;
    double totalSeconds = 0.0;
    std::size_t files = 0;
    std::size_t volumes = 0;
    std::size_t slices = 0;
    std::size_t bytes = 0;
    std::size_t largestVolumeBytes = 0;
    std::size_t failedVolumes = 0;
};

// The process's peak resident set so far (ru_maxrss is in KiB on Linux).
std::size_t peakResidentBytes() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return std::size_t(usage.ru_maxrss) * 1024;
}

ImportRun importOnce(const std::string& path, const core::ImportLimits& limits) {
    using Clock = std::chrono::steady_clock;
    ImportRun run;
    const auto start = Clock::now();
    const dicom::DicomIndex index = dicom::scanDicom(path);
    run.scanSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    run.files = index.filesExamined;
    for (const auto* series : index.allSeries()) {
        const dicom::SeriesAssembly assembly = dicom::planVolumes(*series);
        for (const auto& plan : assembly.volumes) {
            try {
                const volume::Volume v = dicom::loadVolume(*series, plan, nullptr, limits);
                ++run.volumes;
                run.slices += std::size_t(v.dims().z);
                run.bytes += v.byteSize();
                run.largestVolumeBytes = std::max(run.largestVolumeBytes, v.byteSize());
            } catch (const core::Error&) {
                // Undecodable volumes are counted, not timed as slices: info reports why.
                ++run.failedVolumes;
            }
        }
    }
    run.totalSeconds = std::chrono::duration<double>(Clock::now() - start).count();
    return run;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

} // namespace
#endif

int runBenchImport(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json"}, {"repeat", kMaxVolumeOption});
    if (arguments.positionals().size() != 1)
        throw UsageError("bench-import", "expects exactly one PATH");
    const double repeatValue = arguments.number("repeat", 5);
    if (repeatValue < 1 || repeatValue > 1000 || repeatValue != std::floor(repeatValue))
        throw UsageError("--repeat", "expected a whole number from 1 to 1000");
#ifdef LINEWORK_HAVE_DICOM
    const std::string path = arguments.positionals()[0];
    const int repeat = int(repeatValue);
    const core::ImportLimits limits = importLimits(arguments);
    std::vector<ImportRun> runs;
    std::vector<double> totals, scans;
    for (int i = 0; i < repeat; ++i) {
        runs.push_back(importOnce(path, limits));
        totals.push_back(runs.back().totalSeconds);
        scans.push_back(runs.back().scanSeconds);
    }
    const ImportRun& first = runs.front();
    if (first.slices == 0)
        throw core::Error(
            path, "no volume could be loaded: nothing to measure (see `linework-cli info`)");
    const double medianTotal = median(totals);
    const double medianScan = median(scans);
    const double slicesPerSecond = double(first.slices) / medianTotal;
    const double peakMiB = double(peakResidentBytes()) / (1024.0 * 1024.0);
    const double largestMiB = double(first.largestVolumeBytes) / (1024.0 * 1024.0);
    if (arguments.flag("json")) {
        core::JsonWriter w;
        w.beginObject();
        w.field("path", path).field("repeat", repeat).field("threads", int(core::workerCount()));
        w.field("files", first.files).field("volumes", first.volumes).field("slices", first.slices);
        w.field("failed_volumes", first.failedVolumes).field("bytes", first.bytes);
        w.key("runs_s").beginArray();
        for (double t : totals)
            w.value(t);
        w.endArray();
        w.field("median_s", medianTotal).field("median_scan_s", medianScan);
        w.field("slices_per_s", slicesPerSecond);
        w.field("mib_per_s", double(first.bytes) / (1024.0 * 1024.0) / medianTotal);
        w.field("peak_rss_mib", peakMiB).field("largest_volume_mib", largestMiB);
        w.endObject();
        out << w.str() << "\n";
    } else {
        out << path << ": " << first.files << " files, " << first.volumes << " volumes, "
            << first.slices << " slices";
        if (first.failedVolumes)
            out << " (" << first.failedVolumes << " volumes failed to load)";
        out << "\n  median of " << repeat << " runs: " << medianTotal * 1000.0 << " ms (scan "
            << medianScan * 1000.0 << " ms) on " << core::workerCount() << " threads\n"
            << "  " << slicesPerSecond << " slices/s, "
            << double(first.bytes) / (1024.0 * 1024.0) / medianTotal << " MiB/s decoded\n"
            << "  peak resident memory " << peakMiB << " MiB (largest volume " << largestMiB
            << " MiB)\n";
    }
    return 0;
#else
    (void)out;
    throw core::Error("bench-import",
                      "this linework-cli was built without DICOM support (LINEWORK_DICOM=OFF)");
#endif
}

} // namespace lw::cli
