#include "test_support.h"

#include "lw/core/log.h"

#include <cstdio>
#include <cstdlib>
#include <gtest/gtest.h>
#include <random>
#include <sstream>
#include <string>
#include <unistd.h>

namespace lw::test {

std::string firstMissingProgram(const std::string& names) {
    const char* path = std::getenv("PATH");
    std::istringstream programs(names);
    std::string program;
    while (programs >> program) {
        bool found = false;
        std::istringstream folders(path ? path : "");
        std::string folder;
        while (!found && std::getline(folders, folder, ':'))
            found = !folder.empty() && ::access((folder + "/" + program).c_str(), X_OK) == 0;
        if (!found)
            return program;
    }
    return {};
}

void installFailingLogSink() {
    lw::core::setLogSink([](lw::core::LogLevel level, std::string_view category,
                            const std::string& message) {
        std::fprintf(stderr, "[%.*s] %s\n", int(category.size()), category.data(), message.c_str());
        if (level == lw::core::LogLevel::Error)
            ADD_FAILURE() << "error logged in " << category << ": " << message;
    });
}

std::optional<std::filesystem::path> sharedDataDir() {
    std::filesystem::path dir = LINEWORK_DEFAULT_SHARED_DATA;
    if (const char* env = std::getenv("LINEWORK_SHARED_DATA"); env && *env)
        dir = env;
    std::error_code ec;
    if (std::filesystem::is_directory(dir, ec) && std::filesystem::exists(dir / "SOURCES.md", ec))
        return std::filesystem::canonical(dir, ec);
    return std::nullopt;
}

std::filesystem::path sourceDir() {
    if (const char* env = std::getenv("LINEWORK_SOURCE_DIR"); env && *env)
        return env;
    return LINEWORK_DEFAULT_SOURCE_DIR;
}

TempDir::TempDir() {
    std::random_device random;
    m_path = std::filesystem::temp_directory_path() /
             ("linework-test-" + std::to_string(random()) + std::to_string(random()));
    std::filesystem::create_directories(m_path);
}

TempDir::~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(m_path, ignored);
}

} // namespace lw::test
