#include "arguments.h"

#include <cstdlib>

namespace lw::cli {

Arguments::Arguments(const std::vector<std::string>& args, const std::set<std::string>& flags,
                     const std::set<std::string>& options) {
    for (std::size_t i = 0; i < args.size(); ++i) {
        const std::string& arg = args[i];
        if (arg.size() > 2 && arg.rfind("--", 0) == 0) {
            std::string name = arg.substr(2);
            std::optional<std::string> inlineValue;
            if (const auto eq = name.find('='); eq != std::string::npos) {
                inlineValue = name.substr(eq + 1);
                name = name.substr(0, eq);
            }
            if (flags.count(name)) {
                m_flags.insert(name);
            } else if (options.count(name)) {
                if (inlineValue) {
                    m_options[name] = *inlineValue;
                } else {
                    if (i + 1 >= args.size())
                        throw UsageError("--" + name, "needs a value");
                    m_options[name] = args[++i];
                }
            } else {
                throw UsageError(arg, "unknown option");
            }
        } else if (arg == "-o") {
            if (i + 1 >= args.size())
                throw UsageError("-o", "needs an output path");
            m_options["output"] = args[++i];
        } else {
            m_positionals.push_back(arg);
        }
    }
}

std::optional<std::string> Arguments::option(const std::string& name) const {
    if (auto it = m_options.find(name); it != m_options.end())
        return it->second;
    return std::nullopt;
}

std::string Arguments::option(const std::string& name, const std::string& fallback) const {
    return option(name).value_or(fallback);
}

double Arguments::number(const std::string& name, double fallback) const {
    const auto text = option(name);
    if (!text)
        return fallback;
    char* end = nullptr;
    const double value = std::strtod(text->c_str(), &end);
    if (end == text->c_str() || *end != '\0')
        throw UsageError("--" + name, "expected a number, got '" + *text + "'");
    return value;
}

} // namespace lw::cli
