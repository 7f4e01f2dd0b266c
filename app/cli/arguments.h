#pragma once

#include "lw/core/error.h"

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lw::cli {

// A mistake in the command line itself: an unknown option, a missing or malformed value, the
// wrong number of arguments. main prints it with the command's usage and exits 2; an input that
// cannot be read stays a core::Error and exits 1.
class UsageError : public core::Error {
public:
    using core::Error::Error;
};

// Runs parse() and rethrows its core::Error as a UsageError: option values that the engine
// parses (method, back-end, chunks, voxel type, phantom kind) are command-line mistakes there.
template <typename Parse> auto parseUsage(Parse&& parse) -> decltype(parse()) {
    try {
        return parse();
    } catch (const UsageError&) {
        throw;
    } catch (const core::Error& error) {
        throw UsageError(error.subject(), error.reason());
    }
}

// Command-line arguments of one sub-command: positionals, `--name value` options and `--flag`s.
// Which names are flags (take no value) is declared up front, so `--json PATH` is not misread.
class Arguments {
public:
    // Throws UsageError for an option without a value or an unknown option.
    Arguments(const std::vector<std::string>& args, const std::set<std::string>& flags,
              const std::set<std::string>& options);

    const std::vector<std::string>& positionals() const { return m_positionals; }
    bool flag(const std::string& name) const { return m_flags.count(name) > 0; }
    std::optional<std::string> option(const std::string& name) const;
    std::string option(const std::string& name, const std::string& fallback) const;
    // Throws UsageError when the value is not a number.
    double number(const std::string& name, double fallback) const;

private:
    std::vector<std::string> m_positionals;
    std::set<std::string> m_flags;
    std::map<std::string, std::string> m_options;
};

} // namespace lw::cli
