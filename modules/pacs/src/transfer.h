#pragma once

// The receiving side of a retrieve, shared by C-GET (sub-operations on the retrieve's own
// association) and C-MOVE (on the PACS's associations to the workstation's storage SCP): where an
// instance goes, writing it whole or not at all, counting, progress, and stopping (a cancel, a
// full disk) through the caller's C-CANCEL.
#include "lw/pacs/retrieve.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmnet/assoc.h>
#include <dcmtk/dcmnet/dimse.h>
#include <functional>
#include <map>

namespace lw::pacs::detail {

class InstanceTransfer {
public:
    InstanceTransfer(const RetrieveRequest& request,
                     const std::map<std::string, InstanceRecord>& wanted,
                     const RetrieveCallback& onInstance, const core::CancelToken* cancel,
                     RetrieveResult& result)
        : m_request(request), m_wanted(wanted), m_onInstance(onInstance), m_cancel(cancel),
          m_result(result) {}

    // Sends C-CANCEL for the retrieve; set once the retrieve request has gone out.
    void setCancelRequest(std::function<void()> sendCancel) {
        m_sendCancel = std::move(sendCancel);
    }

    // One C-STORE sub-operation whose command arrived on `association`: its data set into the
    // store (TARGET.<pid>.part, renamed when whole), the response sent. A file that cannot be
    // written is refused (out of resources) and stops the retrieve. Returns DCMTK's condition
    // when the network failed (the exchange cannot go on), else EC_Normal.
    OFCondition receive(T_ASC_Association* association, int timeoutSeconds,
                        T_ASC_PresentationContextID context, const T_DIMSE_C_StoreRQ& store);

    // Ends the retrieve early, keeping what arrived: records why (the first reason wins) and
    // sends C-CANCEL once.
    void stop(std::string why);
    RetrieveResult& result() { return m_result; }

private:
    Uint16 write(T_ASC_Association* association, int timeoutSeconds,
                 T_ASC_PresentationContextID context, const T_DIMSE_C_StoreRQ& store,
                 const std::filesystem::path& target, OFCondition& network);
    void arrived(const std::string& uid, const std::filesystem::path& target);

    const RetrieveRequest& m_request;
    const std::map<std::string, InstanceRecord>& m_wanted;
    const RetrieveCallback& m_onInstance;
    const core::CancelToken* m_cancel;
    RetrieveResult& m_result;
    std::function<void()> m_sendCancel;
    bool m_cancelSent = false;
};

std::uint64_t availableBytes(const std::filesystem::path& folder);

} // namespace lw::pacs::detail
