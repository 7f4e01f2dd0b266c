#include "transfer.h"

#include "association.h"

#include <dcmtk/dcmdata/dcostrmf.h>
#include <unistd.h>

namespace lw::pacs::detail {
namespace {

namespace fs = std::filesystem;

bool sendResponse(T_ASC_Association* association, T_ASC_PresentationContextID context,
                  const T_DIMSE_C_StoreRQ& store, Uint16 status) {
    T_DIMSE_C_StoreRSP response{};
    response.MessageIDBeingRespondedTo = store.MessageID;
    response.DataSetType = DIMSE_DATASET_NULL;
    OFStandard::strlcpy(response.AffectedSOPClassUID, store.AffectedSOPClassUID,
                        sizeof response.AffectedSOPClassUID);
    OFStandard::strlcpy(response.AffectedSOPInstanceUID, store.AffectedSOPInstanceUID,
                        sizeof response.AffectedSOPInstanceUID);
    response.opts = O_STORE_AFFECTEDSOPCLASSUID | O_STORE_AFFECTEDSOPINSTANCEUID;
    response.DimseStatus = status;
    T_DIMSE_C_StoreRQ request = store;
    return DIMSE_sendStoreResponse(association, context, &request, &response, nullptr).good();
}

} // namespace

std::uint64_t availableBytes(const fs::path& folder) {
    std::error_code error;
    const fs::space_info space = fs::space(folder, error);
    return error ? 0 : space.available;
}

void InstanceTransfer::stop(std::string why) {
    if (m_result.message.empty())
        m_result.message = std::move(why);
    if (!m_cancelSent && m_sendCancel) {
        m_sendCancel();
        m_cancelSent = true;
    }
}

OFCondition InstanceTransfer::receive(T_ASC_Association* association, int timeoutSeconds,
                                      T_ASC_PresentationContextID context,
                                      const T_DIMSE_C_StoreRQ& store) {
    const std::string uid = store.AffectedSOPInstanceUID;
    const auto listed = m_wanted.find(uid);
    const InstanceRecord instance =
        listed != m_wanted.end() ? listed->second
                                 : InstanceRecord{uid, "unlisted", store.AffectedSOPClassUID};
    const fs::path target = instancePath(m_request.store, instance, m_request.studyUid);
    OFCondition network = EC_Normal;
    const Uint16 status = write(association, timeoutSeconds, context, store, target, network);
    if (network.bad())
        return network;
    if (!sendResponse(association, context, store, status))
        return DIMSE_SENDFAILED;
    if (status == STATUS_Success)
        arrived(uid, target);
    if (m_cancel && m_cancel->isCancelled()) {
        m_result.cancelled = true;
        stop("cancelled; what arrived is kept");
    }
    return EC_Normal;
}

void InstanceTransfer::arrived(const std::string& uid, const fs::path& target) {
    ++m_result.transferred;
    if (m_onInstance)
        m_onInstance({m_result.transferred, m_wanted.size(), uid});
    if (availableBytes(target.parent_path()) < m_request.reserveBytes)
        stop("disk full: less than " + std::to_string(m_request.reserveBytes >> 20) +
             " MiB left in " + m_request.store.string() + "; what arrived is kept");
}

// Streams the data set into TARGET.<pid>.part without parsing it (bit-preserving), then renames.
Uint16 InstanceTransfer::write(T_ASC_Association* association, int timeoutSeconds,
                               T_ASC_PresentationContextID context, const T_DIMSE_C_StoreRQ& store,
                               const fs::path& target, OFCondition& network) {
    std::error_code error;
    fs::create_directories(target.parent_path(), error);
    const fs::path temporary = target.string() + "." + std::to_string(getpid()) + ".part";
    DcmOutputFileStream* stream = nullptr;
    if (error ||
        DIMSE_createFilestream(temporary.c_str(), &store, association, context, 1, &stream).bad()) {
        DIC_UL bytes = 0,
               pdvs = 0; // the data set still comes: read it to keep the exchange in step
        network =
            DIMSE_ignoreDataSet(association, DIMSE_NONBLOCKING, timeoutSeconds, &bytes, &pdvs);
        stop("cannot create " + temporary.string() + "; what arrived is kept");
        return STATUS_STORE_Refused_OutOfResources;
    }
    acknowledgeQuickly(association);
    network = DIMSE_receiveDataSetInFile(association, DIMSE_NONBLOCKING, timeoutSeconds, &context,
                                         stream, nullptr, nullptr);
    const bool written = stream->good();
    delete stream;
    if (!written || network.bad())
        fs::remove(temporary, error);
    if (!written) { // the network may have failed too: the caller sees `network`
        stop("cannot write " + target.string() + " (disk full?); what arrived is kept");
        return STATUS_STORE_Refused_OutOfResources;
    }
    if (network.bad())
        return STATUS_STORE_Refused_OutOfResources;
    fs::rename(temporary, target, error);
    if (!error)
        return STATUS_Success;
    fs::remove(temporary, error);
    stop("cannot rename into " + target.string() + "; what arrived is kept");
    return STATUS_STORE_Refused_OutOfResources;
}

} // namespace lw::pacs::detail
