#pragma once

// One DICOM association with a PACS, over DCMTK's ASC/DIMSE layer (private to lw_pacs). Opening
// it maps every way it can fail to a PacsError in words; the destructor releases it (or aborts
// it when releasing fails), so no path leaves a socket or DCMTK's network behind.
#include "lw/pacs/pacs_client.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmnet/assoc.h>
#include <dcmtk/dcmnet/dimse.h>
#include <string>
#include <vector>

namespace lw::pacs::detail {

struct PresentationContext {
    std::string abstractSyntax;
    std::vector<std::string> transferSyntaxes;
    T_ASC_SC_ROLE role = ASC_SC_ROLE_DEFAULT; // ASC_SC_ROLE_SCP to receive C-GET's C-STOREs
};

// The transfer syntaxes proposed for queries and the storage of retrieved instances.
std::vector<std::string> uncompressedTransferSyntaxes();

// "ORTHANC@127.0.0.1:4242": the subject of every message about the node.
std::string describe(const PacsNode& node);

// Nagle's algorithm off on the association's socket: each C-STORE-RSP goes out at once.
void disableNagle(T_ASC_Association* association);
// ACK what arrived at once: a PACS with Nagle's algorithm on (Orthanc by default) holds its
// next small segment until our ACK, which Linux delays by up to 40 ms otherwise.
void acknowledgeQuickly(T_ASC_Association* association);

class Association {
public:
    // With `acceptorPort`, the network also listens there (the workstation's storage SCP, for
    // the PACS's associations of a C-MOVE); PacsError when the port cannot be bound.
    Association(const PacsNode& node, const CallOptions& options,
                const std::vector<PresentationContext>& contexts, std::uint16_t acceptorPort = 0);
    ~Association();
    Association(const Association&) = delete;
    Association& operator=(const Association&) = delete;

    T_ASC_Association* get() const { return m_association; }
    T_ASC_Network* network() const { return m_network; }
    // The accepted context for `abstractSyntax`; throws PacsError NotSupported when none is.
    T_ASC_PresentationContextID contextFor(const std::string& abstractSyntax) const;
    // Seconds each DIMSE message may take (the call's timeout).
    int timeoutSeconds() const { return m_timeoutSeconds; }
    DIC_US nextMessageId() { return m_association->nextMsgID++; }
    const std::string& subject() const { return m_subject; }
    // A PacsError for a failed DIMSE exchange, mapped from DCMTK's condition.
    [[noreturn]] void fail(const std::string& what, const OFCondition& condition);
    // Ends the association abruptly (after a failure the PACS may still be sending).
    void abort();

    void acknowledgeQuickly() { detail::acknowledgeQuickly(m_association); }

private:
    T_ASC_Network* m_network = nullptr;
    T_ASC_Association* m_association = nullptr;
    std::string m_subject;
    int m_timeoutSeconds;
};

} // namespace lw::pacs::detail
