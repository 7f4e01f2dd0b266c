#include "lw/core/log.h"

#include <cstdio>
#include <mutex>

namespace lw::core {
namespace {

struct LogState {
    std::mutex mutex;
    LogSink sink;
    LogLevel threshold = LogLevel::Info;
};

LogState& state() {
    static LogState instance;
    return instance;
}

void writeToStderr(LogLevel level, std::string_view category, const std::string& message) {
    std::fprintf(stderr, "%.*s %.*s: %s\n", int(logLevelName(level).size()),
                 logLevelName(level).data(), int(category.size()), category.data(),
                 message.c_str());
}

} // namespace

std::string_view logLevelName(LogLevel level) {
    switch (level) {
    case LogLevel::Debug: return "debug";
    case LogLevel::Info: return "info";
    case LogLevel::Warning: return "warning";
    case LogLevel::Error: return "error";
    }
    return "?";
}

void LogCategory::write(LogLevel level, const std::string& message) const {
    LogSink sink;
    {
        std::lock_guard lock(state().mutex);
        if (level < state().threshold)
            return;
        sink = state().sink;
    }
    if (sink)
        sink(level, m_name, message);
    else
        writeToStderr(level, m_name, message);
}

LogSink setLogSink(LogSink sink) {
    std::lock_guard lock(state().mutex);
    std::swap(state().sink, sink);
    return sink;
}

void setLogThreshold(LogLevel level) {
    std::lock_guard lock(state().mutex);
    state().threshold = level;
}

} // namespace lw::core
