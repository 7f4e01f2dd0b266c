#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lw::cli {

// Command-line arguments of one sub-command: positionals, `--name value` options and `--flag`s.
// Which names are flags (take no value) is declared up front, so `--json PATH` is not misread.
class Arguments {
public:
    // Throws core::Error for an option without a value or an unknown option.
    Arguments(const std::vector<std::string>& args, const std::set<std::string>& flags,
              const std::set<std::string>& options);

    const std::vector<std::string>& positionals() const { return m_positionals; }
    bool flag(const std::string& name) const { return m_flags.count(name) > 0; }
    std::optional<std::string> option(const std::string& name) const;
    std::string option(const std::string& name, const std::string& fallback) const;
    double number(const std::string& name, double fallback) const;

private:
    std::vector<std::string> m_positionals;
    std::set<std::string> m_flags;
    std::map<std::string, std::string> m_options;
};

} // namespace lw::cli
