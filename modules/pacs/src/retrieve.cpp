// C-GET into the managed store, resumable: the instances are listed first (C-FIND, image
// level), those whose file exists are skipped, and each arriving instance is written to a
// temporary sibling and renamed, so a file in the store is always whole.
#include "lw/pacs/retrieve.h"

#include "lw/core/file_util.h"
#include "query.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcostrmf.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <map>
#include <set>
#include <unistd.h>

namespace lw::pacs {
namespace {

namespace fs = std::filesystem;
using detail::Association;

// The ways a retrieved instance may be sent: as stored, or decoded by the PACS when it cannot
// send the stored syntax.
std::vector<std::string> storageTransferSyntaxes() {
    return {UID_LittleEndianExplicitTransferSyntax,
            UID_LittleEndianImplicitTransferSyntax,
            UID_JPEGLSLosslessTransferSyntax,
            UID_JPEGProcess14SV1TransferSyntax,
            UID_JPEG2000LosslessOnlyTransferSyntax,
            UID_RLELosslessTransferSyntax,
            UID_DeflatedExplicitVRLittleEndianTransferSyntax};
}

std::vector<detail::PresentationContext> getContexts(const std::vector<InstanceRecord>& instances) {
    std::vector<detail::PresentationContext> contexts{
        {UID_GETStudyRootQueryRetrieveInformationModel, detail::uncompressedTransferSyntaxes()}};
    std::set<std::string> classes;
    for (const InstanceRecord& instance : instances)
        if (!instance.sopClassUid.empty() && classes.insert(instance.sopClassUid).second)
            contexts.push_back({instance.sopClassUid, storageTransferSyntaxes(), ASC_SC_ROLE_SCP});
    if (contexts.size() > 127) // presentation context IDs are the odd numbers 1..255
        throw core::Error("C-GET",
                          std::to_string(classes.size()) +
                              " SOP classes in one request; at most 126 fit an association");
    return contexts;
}

std::uint64_t availableBytes(const fs::path& folder) {
    std::error_code error;
    const fs::space_info space = fs::space(folder, error);
    return error ? 0 : space.available;
}

// The temporaries a killed client left behind (whole files are never named ".part"); only old
// ones, as another retrieve of the same series may be writing its own right now.
void removeStaleTemporaries(const fs::path& folder) {
    std::error_code error;
    const auto staleBefore = fs::file_time_type::clock::now() - core::kStaleTemporaryAge;
    for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
        if (it->path().extension() == ".part" && it->last_write_time(error) < staleBefore)
            fs::remove(it->path(), error);
}

// One C-GET exchange: the request's keys, then C-STORE sub-operations until the final answer.
class GetSession {
public:
    GetSession(Association& association, const RetrieveRequest& request,
               const std::map<std::string, InstanceRecord>& wanted,
               const RetrieveCallback& onInstance, const core::CancelToken* cancel,
               RetrieveResult& result)
        : m_association(association), m_request(request), m_wanted(wanted),
          m_onInstance(onInstance), m_cancel(cancel), m_result(result) {}

    void run(DcmDataset& keys);

private:
    void send(DcmDataset& keys);
    void receiveInstance(T_ASC_PresentationContextID context, const T_DIMSE_C_StoreRQ& store);
    Uint16 writeInstance(T_ASC_PresentationContextID context, const T_DIMSE_C_StoreRQ& store,
                         const fs::path& target);
    void stop(std::string why);

    Association& m_association;
    const RetrieveRequest& m_request;
    const std::map<std::string, InstanceRecord>& m_wanted;
    const RetrieveCallback& m_onInstance;
    const core::CancelToken* m_cancel;
    RetrieveResult& m_result;
    T_ASC_PresentationContextID m_getContext = 0;
    DIC_US m_messageId = 0;
    bool m_cancelSent = false;
};

void GetSession::send(DcmDataset& keys) {
    m_getContext = m_association.contextFor(UID_GETStudyRootQueryRetrieveInformationModel);
    T_DIMSE_Message message{};
    message.CommandField = DIMSE_C_GET_RQ;
    T_DIMSE_C_GetRQ& get = message.msg.CGetRQ;
    get.MessageID = m_messageId = m_association.nextMessageId();
    OFStandard::strlcpy(get.AffectedSOPClassUID, UID_GETStudyRootQueryRetrieveInformationModel,
                        sizeof get.AffectedSOPClassUID);
    get.Priority = DIMSE_PRIORITY_MEDIUM;
    get.DataSetType = DIMSE_DATASET_PRESENT;
    const OFCondition cond = DIMSE_sendMessageUsingMemoryData(
        m_association.get(), m_getContext, &message, nullptr, &keys, nullptr, nullptr);
    if (cond.bad())
        m_association.fail("C-GET", cond);
}

void GetSession::stop(std::string why) {
    if (m_result.message.empty())
        m_result.message = std::move(why);
    if (!m_cancelSent) {
        DIMSE_sendCancelRequest(m_association.get(), m_getContext, m_messageId);
        m_cancelSent = true;
    }
}

void GetSession::run(DcmDataset& keys) {
    send(keys);
    for (;;) {
        T_DIMSE_Message message{};
        T_ASC_PresentationContextID context = 0;
        DcmDataset* statusDetail = nullptr;
        m_association.acknowledgeQuickly();
        const OFCondition cond =
            DIMSE_receiveCommand(m_association.get(), DIMSE_NONBLOCKING,
                                 m_association.timeoutSeconds(), &context, &message, &statusDetail);
        delete statusDetail;
        if (cond.bad())
            m_association.fail("C-GET", cond);
        if (message.CommandField == DIMSE_C_STORE_RQ) {
            receiveInstance(context, message.msg.CStoreRQ);
            continue;
        }
        if (message.CommandField != DIMSE_C_GET_RSP)
            m_association.fail("C-GET", DIMSE_BADCOMMANDTYPE);
        const T_DIMSE_C_GetRSP& response = message.msg.CGetRSP;
        if (response.DimseStatus == STATUS_Pending)
            continue;
        if (response.opts & O_GET_NUMBEROFFAILEDSUBOPERATIONS)
            m_result.failed += response.NumberOfFailedSubOperations;
        if (response.DimseStatus != STATUS_Success && response.DimseStatus != STATUS_GET_Cancel &&
            m_result.message.empty())
            m_result.message =
                "the PACS ended the C-GET with status " + std::to_string(response.DimseStatus);
        return;
    }
}

void GetSession::receiveInstance(T_ASC_PresentationContextID context,
                                 const T_DIMSE_C_StoreRQ& store) {
    const std::string uid = store.AffectedSOPInstanceUID;
    const auto listed = m_wanted.find(uid);
    const InstanceRecord instance =
        listed != m_wanted.end() ? listed->second
                                 : InstanceRecord{uid, "unlisted", store.AffectedSOPClassUID};
    const fs::path target = instancePath(m_request.store, instance, m_request.studyUid);
    T_DIMSE_C_StoreRSP response{};
    response.MessageIDBeingRespondedTo = store.MessageID;
    response.DataSetType = DIMSE_DATASET_NULL;
    OFStandard::strlcpy(response.AffectedSOPClassUID, store.AffectedSOPClassUID,
                        sizeof response.AffectedSOPClassUID);
    OFStandard::strlcpy(response.AffectedSOPInstanceUID, store.AffectedSOPInstanceUID,
                        sizeof response.AffectedSOPInstanceUID);
    response.opts = O_STORE_AFFECTEDSOPCLASSUID | O_STORE_AFFECTEDSOPINSTANCEUID;
    response.DimseStatus = writeInstance(context, store, target);
    const OFCondition cond =
        DIMSE_sendStoreResponse(m_association.get(), context, &store, &response, nullptr);
    if (cond.bad())
        m_association.fail("C-STORE response", cond);
    if (response.DimseStatus == STATUS_Success) {
        ++m_result.transferred;
        if (m_onInstance)
            m_onInstance({m_result.transferred, m_wanted.size(), uid});
        if (availableBytes(target.parent_path()) < m_request.reserveBytes)
            stop("disk full: less than " + std::to_string(m_request.reserveBytes >> 20) +
                 " MiB left in " + m_request.store.string() + "; what arrived is kept");
    }
    if (m_cancel && m_cancel->isCancelled()) {
        m_result.cancelled = true;
        stop("cancelled; what arrived is kept");
    }
}

// Streams the data set into TARGET.<pid>.part without parsing it (bit-preserving), then renames.
// A file that cannot be written refuses the instance (out of resources) and stops the transfer;
// a broken connection throws (PacsError), caught by retrieve().
Uint16 GetSession::writeInstance(T_ASC_PresentationContextID context,
                                 const T_DIMSE_C_StoreRQ& store, const fs::path& target) {
    std::error_code error;
    fs::create_directories(target.parent_path(), error);
    const fs::path temporary = target.string() + "." + std::to_string(getpid()) + ".part";
    DcmOutputFileStream* stream = nullptr;
    if (error ||
        DIMSE_createFilestream(temporary.c_str(), &store, m_association.get(), context, 1, &stream)
            .bad()) {
        DIC_UL bytes = 0,
               pdvs = 0; // the data set still comes: read it to keep the exchange in step
        const OFCondition drained = DIMSE_ignoreDataSet(
            m_association.get(), DIMSE_NONBLOCKING, m_association.timeoutSeconds(), &bytes, &pdvs);
        if (drained.bad())
            m_association.fail("C-GET", drained);
        stop("cannot create " + temporary.string() + "; what arrived is kept");
        return STATUS_STORE_Refused_OutOfResources;
    }
    m_association.acknowledgeQuickly();
    const OFCondition cond = DIMSE_receiveDataSetInFile(m_association.get(), DIMSE_NONBLOCKING,
                                                        m_association.timeoutSeconds(), &context,
                                                        stream, nullptr, nullptr);
    const bool streamGood = stream->good();
    delete stream;
    if (!streamGood || cond.bad())
        fs::remove(temporary, error);
    if (!streamGood) {
        stop("cannot write " + target.string() + " (disk full?); what arrived is kept");
        if (cond.bad())
            m_association.fail("C-GET", cond);
        return STATUS_STORE_Refused_OutOfResources;
    }
    if (cond.bad())
        m_association.fail("C-GET", cond);
    fs::rename(temporary, target, error);
    if (!error)
        return STATUS_Success;
    fs::remove(temporary, error);
    stop("cannot rename into " + target.string() + "; what arrived is kept");
    return STATUS_STORE_Refused_OutOfResources;
}

// What to ask for, in C-GET requests of one series each at most: a series of which nothing is
// here whole, else its missing instances by UID (image level needs the series UID).
std::vector<DcmDataset> getRequests(const std::string& studyUid,
                                    const std::vector<InstanceRecord>& listed,
                                    const std::vector<InstanceRecord>& missing) {
    std::map<std::string, std::size_t> listedPerSeries;
    for (const InstanceRecord& instance : listed)
        ++listedPerSeries[instance.seriesInstanceUid];
    std::map<std::string, std::vector<std::string>> missingPerSeries;
    for (const InstanceRecord& instance : missing)
        missingPerSeries[instance.seriesInstanceUid].push_back(instance.sopInstanceUid);
    std::vector<DcmDataset> requests;
    for (const auto& [series, uids] : missingPerSeries) {
        DcmDataset& keys = requests.emplace_back();
        keys.putAndInsertString(DCM_StudyInstanceUID, studyUid.c_str());
        keys.putAndInsertString(DCM_SeriesInstanceUID, series.c_str());
        if (uids.size() == listedPerSeries[series]) {
            keys.putAndInsertString(DCM_QueryRetrieveLevel, "SERIES");
            continue;
        }
        std::string list;
        for (const std::string& uid : uids)
            list += (list.empty() ? "" : "\\") + uid;
        keys.putAndInsertString(DCM_QueryRetrieveLevel, "IMAGE");
        keys.putAndInsertString(DCM_SOPInstanceUID, list.c_str());
    }
    return requests;
}

void checkFreeSpace(const RetrieveRequest& request, const std::vector<InstanceRecord>& missing,
                    const std::string& subject) {
    // The size of what is missing is estimated from what is stored of the request, when
    // anything is; else from 512x512 16-bit slices, what a CT series mostly is.
    std::uint64_t stored = 0, count = 0;
    std::error_code error;
    const fs::path study = request.store / request.studyUid;
    for (fs::recursive_directory_iterator it(study, error), end; !error && it != end;
         it.increment(error))
        if (it->is_regular_file(error) && it->path().extension() == ".dcm")
            stored += it->file_size(error), ++count;
    const std::uint64_t perInstance = count ? stored / count : 512ull * 512 * 2 + 4096;
    const std::uint64_t needed = perInstance * missing.size() + request.reserveBytes;
    const std::uint64_t available = availableBytes(request.store);
    if (available < needed)
        throw PacsError(PacsFailure::DiskFull, subject,
                        "not enough disk space in " + request.store.string() + ": " +
                            std::to_string(available >> 20) + " MiB free, " +
                            std::to_string(needed >> 20) + " MiB needed for " +
                            std::to_string(missing.size()) + " instances");
}

} // namespace

fs::path instancePath(const fs::path& store, const InstanceRecord& instance,
                      const std::string& studyUid) {
    return store / studyUid / instance.seriesInstanceUid / (instance.sopInstanceUid + ".dcm");
}

RetrieveResult retrieve(const PacsNode& node, const RetrieveRequest& request,
                        const CallOptions& options, const RetrieveCallback& onInstance,
                        const core::CancelToken* cancel) {
    if (request.studyUid.empty())
        throw core::Error(detail::describe(node), "retrieve: no study UID");
    const std::vector<InstanceRecord> listed =
        findInstances(node, request.studyUid, request.seriesUid, options, cancel);
    RetrieveResult result;
    result.instances = listed.size();
    std::vector<InstanceRecord> missing;
    std::map<std::string, InstanceRecord> wanted;
    for (const InstanceRecord& instance : listed) {
        std::error_code error;
        if (fs::is_regular_file(instancePath(request.store, instance, request.studyUid), error))
            ++result.skipped;
        else
            missing.push_back(instance), wanted.emplace(instance.sopInstanceUid, instance);
    }
    if (!missing.empty()) {
        std::error_code error;
        fs::create_directories(request.store, error);
        if (error)
            throw core::Error(request.store.string(),
                              "cannot create the store: " + error.message());
        checkFreeSpace(request, missing, detail::describe(node));
        Association association(node, options, getContexts(missing));
        try {
            for (DcmDataset& keys : getRequests(request.studyUid, listed, missing)) {
                OFString series;
                keys.findAndGetOFString(DCM_SeriesInstanceUID, series);
                removeStaleTemporaries(request.store / request.studyUid / series.c_str());
                GetSession(association, request, wanted, onInstance, cancel, result).run(keys);
                if (!result.message.empty())
                    break;
            }
        } catch (const PacsError& error) {
            if (result.message.empty())
                result.message = error.reason();
        }
    }
    for (const InstanceRecord& instance : listed)
        if (std::error_code error;
            fs::is_regular_file(instancePath(request.store, instance, request.studyUid), error))
            result.files.push_back(instancePath(request.store, instance, request.studyUid));
    if (result.message.empty() && !result.complete())
        result.message =
            std::to_string(result.instances - result.files.size()) + " instances did not arrive";
    return result;
}

} // namespace lw::pacs
