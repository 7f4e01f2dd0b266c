#pragma once

// What the `quality` command tests share: the bundled demo study and a number of the JSON.

#include "cli_runner.h"
#include "test_support.h"

#include <regex>
#include <string>

namespace lw::test {

inline std::string demo() {
    return quoted((sourceDir() / "resources/demo/ct_head_ge_tilt").string());
}

// The number after `"key":` in compact JSON (the first occurrence), or -1 for null or none.
inline double numberOf(const std::string& json, const std::string& key) {
    const std::regex pattern("\"" + key + "\":(-?[0-9.e+-]+)");
    std::smatch match;
    return std::regex_search(json, match, pattern) ? std::stod(match[1]) : -1.0;
}

} // namespace lw::test
