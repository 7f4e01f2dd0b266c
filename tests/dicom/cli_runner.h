#pragma once

// Runs linework-cli as a user would and captures what it prints, for the CLI contract tests.

#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace lw::test {

struct CliResult {
    int exitCode = -1;
    std::string out;
};

inline CliResult runCli(const std::string& arguments) {
    CliResult result;
    const std::string command =
        std::string("\"") + LINEWORK_CLI_PATH + "\" " + arguments + " 2>/dev/null";
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe)
        return result;
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
        result.out.append(buffer, n);
    const int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
}

// JSON without whitespace, so tests can look for `"dims":[512,512,28]` whatever the indent.
inline std::string compact(const std::string& json) {
    std::string out;
    bool inString = false;
    for (std::size_t i = 0; i < json.size(); ++i) {
        const char c = json[i];
        if (c == '"' && (i == 0 || json[i - 1] != '\\'))
            inString = !inString;
        if (!inString && (c == ' ' || c == '\n' || c == '\t' || c == '\r'))
            continue;
        out += c;
    }
    return out;
}

inline std::string quoted(const std::string& path) {
    return "'" + path + "'";
}

} // namespace lw::test
