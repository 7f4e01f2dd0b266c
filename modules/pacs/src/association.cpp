#include "association.h"

#include <dcmtk/dcmnet/dcmtrans.h>
#include <dcmtk/dcmnet/dul.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>
#include <unistd.h>

namespace lw::pacs::detail {
namespace {

constexpr long kMaxPdu = 65536; // larger PDUs move big slices in fewer pieces

bool contains(const std::string& text, const char* part) {
    return text.find(part) != std::string::npos;
}

PacsError rejection(T_ASC_Parameters* params, const std::string& subject) {
    T_ASC_RejectParameters reject{};
    ASC_getRejectParameters(params, &reject);
    switch (reject.reason) {
    case ASC_REASON_SU_CALLEDAETITLENOTRECOGNIZED:
        return {PacsFailure::CalledAeRejected, subject,
                "association rejected: the PACS does not answer to the called AE title \"" +
                    std::string(params->DULparams.calledAPTitle) + "\""};
    case ASC_REASON_SU_CALLINGAETITLENOTRECOGNIZED:
        return {PacsFailure::CallingAeRejected, subject,
                "association rejected: the PACS does not know the workstation's AE title \"" +
                    std::string(params->DULparams.callingAPTitle) + "\""};
    default:
        break;
    }
    OFString text;
    ASC_printRejectParameters(text, &reject);
    return {PacsFailure::AssociationRejected, subject,
            "association rejected: " + std::string(text.c_str())};
}

// Connecting fails in DUL with the socket's reason in the text; a timeout on the A-ASSOCIATE
// answer is DUL_READTIMEOUT or an ARTIM expiry.
PacsError connectionFailure(const OFCondition& condition, const std::string& subject) {
    const std::string text = condition.text();
    if (contains(text, "Connection refused"))
        return {
            PacsFailure::ConnectionRefused, subject,
            "connection refused: nothing listens there (is the PACS running, is the port right?)"};
    if (condition == DUL_READTIMEOUT || contains(text, "imed out") || contains(text, "imeout"))
        return {PacsFailure::TimedOut, subject,
                "timed out: no answer from the PACS (" + text + ")"};
    if (condition == DUL_PEERABORTEDASSOCIATION)
        return {PacsFailure::Aborted, subject, "the PACS aborted the association"};
    return {PacsFailure::Network, subject, "cannot connect: " + text};
}

} // namespace

std::vector<std::string> uncompressedTransferSyntaxes() {
    return {UID_LittleEndianExplicitTransferSyntax, UID_LittleEndianImplicitTransferSyntax};
}

std::string describe(const PacsNode& node) {
    return node.calledAet + "@" + node.host + ":" + std::to_string(node.port);
}

Association::Association(const PacsNode& node, const CallOptions& options,
                         const std::vector<PresentationContext>& contexts,
                         std::uint16_t acceptorPort)
    : m_subject(describe(node)), m_timeoutSeconds(int(options.timeout.count())) {
    validateAeTitle(options.callingAet, m_subject + " (calling AE title)");
    validateAeTitle(node.calledAet, m_subject);
    OFCondition cond = ASC_initializeNetwork(acceptorPort ? NET_ACCEPTORREQUESTOR : NET_REQUESTOR,
                                             acceptorPort, m_timeoutSeconds, &m_network);
    if (cond.bad())
        throw PacsError(PacsFailure::Network, m_subject,
                        acceptorPort ? "cannot listen on port " + std::to_string(acceptorPort) +
                                           " for the PACS's C-MOVE: " + cond.text()
                                     : std::string("network: ") + cond.text());
    // DCMTK keeps the TCP connect timeout process-wide (an OFGlobal, set under its own lock):
    // each association sets its own before connecting; without it connect() blocks for minutes.
    dcmConnectionTimeout.set(Sint32(m_timeoutSeconds));
    T_ASC_Parameters* params = nullptr;
    ASC_createAssociationParameters(&params, kMaxPdu);
    ASC_setAPTitles(params, options.callingAet.c_str(), node.calledAet.c_str(), nullptr);
    char localHost[128] = "localhost";
    gethostname(localHost, sizeof localHost - 1);
    const std::string peer = node.host + ":" + std::to_string(node.port);
    ASC_setPresentationAddresses(params, localHost, peer.c_str());
    T_ASC_PresentationContextID id = 1;
    for (const PresentationContext& context : contexts) {
        std::vector<const char*> syntaxes;
        for (const std::string& syntax : context.transferSyntaxes)
            syntaxes.push_back(syntax.c_str());
        ASC_addPresentationContext(params, id, context.abstractSyntax.c_str(), syntaxes.data(),
                                   int(syntaxes.size()), context.role);
        id = T_ASC_PresentationContextID(id + 2);
    }
    cond = ASC_requestAssociation(m_network, params, &m_association);
    if (cond.bad()) {
        const PacsError error = cond == DUL_ASSOCIATIONREJECTED
                                    ? rejection(params, m_subject)
                                    : connectionFailure(cond, m_subject);
        if (m_association)
            ASC_destroyAssociation(&m_association);
        else
            ASC_destroyAssociationParameters(&params);
        ASC_dropNetwork(&m_network);
        throw error;
    }
    disableNagle(m_association);
    if (ASC_countAcceptedPresentationContexts(params) == 0) {
        abort();
        ASC_dropNetwork(&m_network);
        throw PacsError(PacsFailure::NotSupported, m_subject,
                        "the PACS accepted none of the proposed services");
    }
}

namespace {

// DCMTK has no public accessor for the socket (getSocket() is protected); a member pointer
// named through a derived class reaches it without a cast or copying DCMTK's layout.
struct SocketOf : DcmTransportConnection {
    static DcmNativeSocketType of(DcmTransportConnection& connection) {
        constexpr auto getter = &SocketOf::getSocket;
        return (connection.*getter)();
    }
};

void setSocketOption(T_ASC_Association* association, int option) {
    DcmTransportConnection* connection = DUL_getTransportConnection(association->DULassociation);
    if (!connection)
        return;
    const int on = 1;
    setsockopt(SocketOf::of(*connection), IPPROTO_TCP, option, &on, sizeof on);
}

} // namespace

// A C-GET answers each instance with a small C-STORE-RSP. With Nagle's algorithm on (Debian's
// DCMTK leaves it on unless $TCP_NODELAY says otherwise) that response waits for the PACS's
// delayed ACK, about 40 ms: 20 instances/s instead of hundreds (measured on loopback).
void disableNagle(T_ASC_Association* association) {
    setSocketOption(association, TCP_NODELAY);
}

// Linux leaves quick-ACK mode by itself after a while, so this is asked again per message.
void acknowledgeQuickly(T_ASC_Association* association) {
#ifdef TCP_QUICKACK
    setSocketOption(association, TCP_QUICKACK);
#else
    (void)association;
#endif
}

Association::~Association() {
    if (m_association) {
        if (ASC_releaseAssociation(m_association).bad())
            ASC_abortAssociation(m_association);
        ASC_destroyAssociation(&m_association);
    }
    if (m_network)
        ASC_dropNetwork(&m_network);
}

void Association::abort() {
    if (!m_association)
        return;
    ASC_abortAssociation(m_association);
    ASC_destroyAssociation(&m_association);
}

T_ASC_PresentationContextID Association::contextFor(const std::string& abstractSyntax) const {
    const T_ASC_PresentationContextID id =
        ASC_findAcceptedPresentationContextID(m_association, abstractSyntax.c_str());
    if (id == 0)
        throw PacsError(
            PacsFailure::NotSupported, m_subject,
            "the PACS does not offer " +
                std::string(dcmFindNameOfUID(abstractSyntax.c_str(), abstractSyntax.c_str())));
    return id;
}

void Association::fail(const std::string& what, const OFCondition& condition) {
    PacsError error = connectionFailure(condition, m_subject);
    abort();
    throw PacsError(error.kind(), m_subject, what + ": " + error.reason());
}

} // namespace lw::pacs::detail
