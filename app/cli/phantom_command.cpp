// `phantom` writes the benchmark phantom; `bench-mc` times marching cubes on it.
#include "arguments.h"
#include "cli_inputs.h"
#include "commands.h"
#include "lw/core/error.h"
#include "lw/render/iso_surface.h"
#include "lw/volume/phantom.h"
#include "lw/volume/volume_reader.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <ostream>
#include <vector>

namespace lw::cli {
namespace {

// CPU time of the whole process: on a shared, loaded machine it says what the work cost
// even when the wall clock does not.
double processCpuSeconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace

int runPhantom(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {}, {"size", "kind", "threads", kMaxVolumeOption});
    const auto size = arguments.option("size");
    const auto output = arguments.option("output");
    if (!size || !output || !arguments.positionals().empty())
        throw UsageError("phantom", "needs --size and -o OUT.nrrd, and no other arguments");
    const glm::ivec3 dims = parseDimsOption("--size", *size, 1);
    const volume::PhantomKind kind =
        parseUsage([&] { return volume::parsePhantomKind(arguments.option("kind", "ct")); });
    const auto start = std::chrono::steady_clock::now();
    const volume::Volume phantom = volume::makePhantom(
        dims, kind, unsigned(arguments.number("threads", 0)), importLimits(arguments));
    const double seconds = secondsSince(start);
    const volume::PhantomChecksum checksum = volume::phantomChecksum(phantom);
    volume::writeNrrd(*output, phantom);
    char line[256];
    std::snprintf(line, sizeof line, "gen %s %s via linework: %.2fs sum=%lld above_iso=%lld\n",
                  std::string(volume::phantomKindName(kind)).c_str(), dimsText(dims).c_str(),
                  seconds, static_cast<long long>(checksum.sum),
                  static_cast<long long>(checksum.above));
    out << line;
    return 0;
}

int runBenchMc(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(
        args, {}, {"size", "kind", "chunks", "repeat", "iso", "threads", kMaxVolumeOption});
    const glm::ivec3 dims = parseDimsOption("--size", arguments.option("size", "256"), 1);
    const volume::PhantomKind kind =
        parseUsage([&] { return volume::parsePhantomKind(arguments.option("kind", "ct")); });
    const int repeat = std::max(1, int(arguments.number("repeat", 10)));
    const double iso = arguments.number("iso", volume::kPhantomBoneIso);
    const std::string chunks = arguments.option("chunks", "off");

    auto start = std::chrono::steady_clock::now();
    const volume::Volume phantom = volume::makePhantom(dims, kind, 0, importLimits(arguments));
    const double generateSeconds = secondsSince(start);

    render::IsoSurfaceOptions options;
    options.brickCells = parseUsage([&] { return render::parseChunks(chunks, dims); });
    options.threads = unsigned(arguments.number("threads", 0));
    start = std::chrono::steady_clock::now();
    const render::IsoSurfaceExtractor extractor(phantom, options);
    const double brickSeconds = secondsSince(start);
    render::Mesh mesh;
    render::IsoSurfaceStats stats;
    // Warm-up: first-touch page faults of the output buffers are not the algorithm's cost in
    // mode b, where the buffers are reused frame after frame.
    extractor.extract(iso, mesh, &stats);
    std::vector<double> times;
    const double cpuStart = processCpuSeconds();
    for (int i = 0; i < repeat; ++i) {
        start = std::chrono::steady_clock::now();
        extractor.extract(iso, mesh, &stats);
        times.push_back(secondsSince(start) * 1000.0);
    }
    const double cpuMs = (processCpuSeconds() - cpuStart) * 1000.0 / repeat;
    std::sort(times.begin(), times.end());
    const double median = times.size() % 2
                              ? times[times.size() / 2]
                              : 0.5 * (times[times.size() / 2 - 1] + times[times.size() / 2]);
    char line[512];
    std::snprintf(
        line, sizeof line,
        "mc %s %s iso=%g chunks=%s (brick %d) bricks=%zu/%zu: median %.1f ms, min %.1f ms over %d "
        "runs (CPU %.1f ms per run, all threads); triangles=%zu vertices=%zu; brick min/max %.1f "
        "ms; "
        "phantom generated in %.2f s\n",
        std::string(volume::phantomKindName(kind)).c_str(), dimsText(dims).c_str(), iso,
        chunks.c_str(), options.brickCells, stats.activeBricks, stats.totalBricks, median,
        times.front(), repeat, cpuMs, mesh.triangleCount(), mesh.vertexCount(),
        brickSeconds * 1000.0, generateSeconds);
    out << line;
    return 0;
}

} // namespace lw::cli
