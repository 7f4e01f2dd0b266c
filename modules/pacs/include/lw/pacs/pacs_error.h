#pragma once

#include "lw/core/error.h"

#include <string>

namespace lw::pacs {

// Why talking to a PACS failed, in the categories a user acts on differently.
enum class PacsFailure {
    ConnectionRefused,   // nothing listens at host:port (the PACS is down, or a wrong port)
    TimedOut,            // no answer in time (a firewall dropping packets, a hung PACS)
    CalledAeRejected,    // the PACS does not answer to this called AE title
    CallingAeRejected,   // the PACS does not know the workstation's AE title
    AssociationRejected, // rejected for another reason (given in the message)
    Aborted,             // the PACS aborted the association (Orthanc does so for an unknown AE)
    NotSupported,        // the PACS accepted none of the proposed presentation contexts
    Refused,             // a DIMSE request answered with a failure status
    DiskFull,            // the store ran out of space; what arrived is kept
    Network,             // any other network failure
};

// "connection refused", "timed out", ...: for messages and the CLI's JSON.
const char* failureName(PacsFailure failure);

// A core::Error whose subject names the node (AET@HOST:PORT) and whose reason says what
// happened in words; kind() lets callers decide (retry, fix the settings, free space).
class PacsError : public core::Error {
public:
    PacsError(PacsFailure kind, std::string subject, std::string reason)
        : core::Error(std::move(subject), std::move(reason)), m_kind(kind) {}
    PacsFailure kind() const noexcept { return m_kind; }

private:
    PacsFailure m_kind;
};

} // namespace lw::pacs
