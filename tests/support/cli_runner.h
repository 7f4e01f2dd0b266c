#pragma once

// Runs a program (linework-cli) as a user would and captures what it prints, for the CLI
// contract tests.

#include <string>

namespace lw::test {

struct CliResult {
    int exitCode = -1; // -1 when the program could not be run or did not exit normally
    std::string out;   // stdout
    std::string err;   // stderr
};

// Runs `"PROGRAM" ARGUMENTS` through the shell, `environment` (e.g. "LW_X=1 ") put in front.
CliResult runProgram(const std::string& program, const std::string& arguments,
                     const std::string& environment = {});

#ifdef LINEWORK_CLI_PATH
// linework-cli, whose path the test target defines as LINEWORK_CLI_PATH.
inline CliResult runCli(const std::string& arguments, const std::string& environment = {}) {
    return runProgram(LINEWORK_CLI_PATH, arguments, environment);
}
#endif

// JSON without whitespace, so tests can look for `"dims":[512,512,28]` whatever the indent.
std::string compact(const std::string& json);

// `path` in single quotes, for a shell command line.
std::string quoted(const std::string& path);

} // namespace lw::test
