#include "cli_runner.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

namespace lw::test {

CliResult runProgram(const std::string& program, const std::string& arguments,
                     const std::string& environment) {
    CliResult result;
    // stderr goes to a temporary file, read after the program has ended.
    char errorFile[] = "/tmp/lw_cli_stderr_XXXXXX";
    const int descriptor = ::mkstemp(errorFile);
    if (descriptor < 0)
        return result;
    ::close(descriptor);
    const std::string command =
        environment + "\"" + program + "\" " + arguments + " 2>" + quoted(errorFile);
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) {
        std::remove(errorFile);
        return result;
    }
    char buffer[4096];
    std::size_t n = 0;
    while ((n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0)
        result.out.append(buffer, n);
    const int status = pclose(pipe);
    result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ostringstream err;
    err << std::ifstream(errorFile).rdbuf();
    result.err = err.str();
    std::remove(errorFile);
    return result;
}

std::string compact(const std::string& json) {
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

std::string quoted(const std::string& path) {
    return "'" + path + "'";
}

} // namespace lw::test
