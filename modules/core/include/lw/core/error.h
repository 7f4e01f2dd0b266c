#pragma once

#include <stdexcept>
#include <string>

namespace lw::core {

// Every failure the engine reports names what it was working on (a file, a series, a setting)
// and why it failed. The app and CLI catch Error at their boundary and show both parts.
class Error : public std::runtime_error {
public:
    Error(std::string subject, std::string reason);

    const std::string& subject() const noexcept { return m_subject; }
    const std::string& reason() const noexcept { return m_reason; }

private:
    std::string m_subject;
    std::string m_reason;
};

// Thrown when the user (or a newer request) cancelled long work; not an error to report.
class Cancelled : public std::runtime_error {
public:
    Cancelled() : std::runtime_error("cancelled") {}
};

} // namespace lw::core
