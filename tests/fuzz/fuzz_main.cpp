// A libFuzzer target: one of the readers of fuzz_inputs.h, chosen at build time
// (LINEWORK_FUZZ_TARGET). Built only with clang and LINEWORK_FUZZ=ON (tests/fuzz/CMakeLists.txt);
// scripts/linework.sh test runs each for a bounded time on the seed corpora of scripts/fuzz.sh.
#include "fuzz_inputs.h"
#include "lw/core/log.h"

#include <cstdlib>

namespace {

std::filesystem::path sharedData() {
    const char* fromEnvironment = std::getenv("LINEWORK_SHARED_DATA");
    return fromEnvironment ? fromEnvironment : LINEWORK_DEFAULT_SHARED_DATA;
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    // Warnings about damaged files are the point of fuzzing, not news: keep the output to
    // libFuzzer's own lines.
    lw::core::setLogSink([](lw::core::LogLevel, std::string_view, const std::string&) {});
    (void)lw::fuzz::fileSetRoot(sharedData());
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    lw::fuzz::runTarget(LINEWORK_FUZZ_TARGET, {data, size}, lw::fuzz::fileSetRoot(sharedData()));
    return 0;
}
