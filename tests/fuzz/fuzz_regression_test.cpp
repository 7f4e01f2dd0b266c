// Every input under tests/data/fuzz/<target>/ (fuzz findings and hand-made hostile files, their
// origin in tests/data/fuzz/README.md) replayed through the reader its folder names, in every
// build: a crash, a sanitizer finding (build/asan), an exception other than core::Error, an
// input slower than the fuzz runs' timeout, or one allocation larger than their malloc limit
// fails. This test, not the random fuzz runs, is what gates CI on every known hostile input.
#include "fuzz_inputs.h"
#include "test_support.h"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <vector>

namespace fs = std::filesystem;

namespace {

// What scripts/fuzz.sh gives libFuzzer: -timeout=10, and a malloc limit (its default: the RSS
// limit, 2560 MB; the replay's bound is lower, the readers run under a 256 MB import limit).
constexpr double kTimeoutSeconds = 10.0;
constexpr std::size_t kLargestAllocation = std::size_t(1) << 30;

fs::path regressionInputs() {
    return lw::test::sourceDir() / "tests/data/fuzz";
}

std::vector<std::uint8_t> bytesOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

#if defined(__SANITIZE_ADDRESS__)
// AddressSanitizer reports (and fails the test on) any single allocation over the bound; the
// environment's ASAN_OPTIONS are read after these defaults and keep theirs.
extern "C" const char* __asan_default_options() {
    return "max_allocation_size_mb=1024";
}
namespace {
void resetLargestAllocation() {}
std::size_t largestAllocation() {
    return 0;
}
} // namespace
#else
// Without a sanitizer a 4 GB allocation that is never touched costs nothing visible (the 4 GB
// DCMTK allocated for a 16 KB file went unnoticed here): this binary's malloc notes the largest
// request, every thread's, and hands it to glibc.
extern "C" void* __libc_malloc(std::size_t size);
namespace {
std::atomic<std::size_t> g_largestRequest{0};
void resetLargestAllocation() {
    g_largestRequest = 0;
}
std::size_t largestAllocation() {
    return g_largestRequest;
}
} // namespace
extern "C" void* malloc(std::size_t size) {
    std::size_t seen = g_largestRequest.load(std::memory_order_relaxed);
    while (size > seen && !g_largestRequest.compare_exchange_weak(seen, size))
        ;
    return __libc_malloc(size);
}
#endif

TEST(FuzzRegression, EveryInputIsReadWithoutACrash) {
    ASSERT_TRUE(fs::is_directory(regressionInputs())) << regressionInputs();
    const fs::path fileSet = lw::fuzz::fileSetRoot(lw::test::sharedDataDir().value_or(fs::path()));
    int replayed = 0;
    for (const auto& folder : fs::directory_iterator(regressionInputs())) {
        if (!folder.is_directory())
            continue;
        const std::string target = folder.path().filename().string();
        for (const auto& input : fs::directory_iterator(folder.path())) {
            SCOPED_TRACE(input.path().string());
            const auto bytes = bytesOf(input.path());
            resetLargestAllocation();
            const auto start = std::chrono::steady_clock::now();
            EXPECT_TRUE(lw::fuzz::runTarget(target, bytes, fileSet))
                << "tests/data/fuzz/" << target << " names no fuzz target";
            const std::chrono::duration<double> took = std::chrono::steady_clock::now() - start;
            EXPECT_LT(took.count(), kTimeoutSeconds);
            EXPECT_LE(largestAllocation(), kLargestAllocation);
            ++replayed;
        }
    }
    EXPECT_GT(replayed, 0);
}
