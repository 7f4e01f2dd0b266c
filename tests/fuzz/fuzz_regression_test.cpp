// Every input under tests/data/fuzz/<target>/ (fuzz findings and hand-made hostile files, their
// origin in tests/data/fuzz/README.md) replayed through the reader its folder names, in every
// build: a crash, a sanitizer finding (build/asan) or an exception other than core::Error fails.
#include "fuzz_inputs.h"
#include "test_support.h"

#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <vector>

namespace fs = std::filesystem;

namespace {

fs::path regressionInputs() {
    return lw::test::sourceDir() / "tests/data/fuzz";
}

std::vector<std::uint8_t> bytesOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

} // namespace

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
            EXPECT_TRUE(lw::fuzz::runTarget(target, bytes, fileSet))
                << "tests/data/fuzz/" << target << " names no fuzz target";
            ++replayed;
        }
    }
    EXPECT_GT(replayed, 0);
}
