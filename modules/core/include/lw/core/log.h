#pragma once

#include <functional>
#include <sstream>
#include <string>
#include <string_view>

namespace lw::core {

enum class LogLevel { Debug, Info, Warning, Error };

std::string_view logLevelName(LogLevel level);

// A named logging category per module ("lw.dicom", "lw.render", ...). Messages go to the
// process's log sink: stderr by default; the GUI and the tests install their own (tests
// fail on error-level messages). The sink is process-wide on purpose, like Qt's message
// handler: it is set once at start-up by main() or a test fixture, never from library code.
class LogCategory {
public:
    constexpr explicit LogCategory(std::string_view name) : m_name(name) {}
    std::string_view name() const { return m_name; }

    void debug(const std::string& message) const { write(LogLevel::Debug, message); }
    void info(const std::string& message) const { write(LogLevel::Info, message); }
    void warning(const std::string& message) const { write(LogLevel::Warning, message); }
    void error(const std::string& message) const { write(LogLevel::Error, message); }
    void write(LogLevel level, const std::string& message) const;

private:
    std::string_view m_name;
};

using LogSink = std::function<void(LogLevel, std::string_view category, const std::string&)>;

// Installs a sink and returns the previous one (so a scope can restore it).
LogSink setLogSink(LogSink sink);
// Messages below this level are dropped before reaching the sink (default: Info).
void setLogThreshold(LogLevel level);

} // namespace lw::core
