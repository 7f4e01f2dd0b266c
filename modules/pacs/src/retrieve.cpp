// C-GET into the managed store, resumable: the instances are listed first (C-FIND, image
// level), those whose file exists are skipped, and each arriving instance is written to a
// temporary sibling and renamed, so a file in the store is always whole.
#include "lw/pacs/retrieve.h"

#include "lw/core/file_util.h"
#include "move.h"
#include "query.h"
#include "transfer.h"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <map>
#include <set>

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

// The temporaries a killed client left behind (whole files are never named ".part"); only old
// ones, as another retrieve of the same series may be writing its own right now.
void removeStaleTemporaries(const fs::path& folder) {
    std::error_code error;
    const auto staleBefore = fs::file_time_type::clock::now() - core::kStaleTemporaryAge;
    for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error))
        if (it->path().extension() == ".part" && it->last_write_time(error) < staleBefore)
            fs::remove(it->path(), error);
}

// One C-GET exchange: the request's keys, then C-STORE sub-operations on the same association
// until the final answer.
class GetSession {
public:
    GetSession(Association& association, detail::InstanceTransfer& transfer)
        : m_association(association), m_transfer(transfer) {}

    void run(DcmDataset& keys);

private:
    void send(DcmDataset& keys);
    void finish(const T_DIMSE_C_GetRSP& response);

    Association& m_association;
    detail::InstanceTransfer& m_transfer;
};

void GetSession::send(DcmDataset& keys) {
    const T_ASC_PresentationContextID context =
        m_association.contextFor(UID_GETStudyRootQueryRetrieveInformationModel);
    T_DIMSE_Message message{};
    message.CommandField = DIMSE_C_GET_RQ;
    T_DIMSE_C_GetRQ& get = message.msg.CGetRQ;
    get.MessageID = m_association.nextMessageId();
    OFStandard::strlcpy(get.AffectedSOPClassUID, UID_GETStudyRootQueryRetrieveInformationModel,
                        sizeof get.AffectedSOPClassUID);
    get.Priority = DIMSE_PRIORITY_MEDIUM;
    get.DataSetType = DIMSE_DATASET_PRESENT;
    const OFCondition cond = DIMSE_sendMessageUsingMemoryData(
        m_association.get(), context, &message, nullptr, &keys, nullptr, nullptr);
    if (cond.bad())
        m_association.fail("C-GET", cond);
    T_ASC_Association* association = m_association.get();
    const DIC_US id = get.MessageID;
    m_transfer.setCancelRequest(
        [association, context, id] { DIMSE_sendCancelRequest(association, context, id); });
}

void GetSession::finish(const T_DIMSE_C_GetRSP& response) {
    RetrieveResult& result = m_transfer.result();
    if (response.opts & O_GET_NUMBEROFFAILEDSUBOPERATIONS)
        result.failed += response.NumberOfFailedSubOperations;
    if (response.DimseStatus != STATUS_Success && response.DimseStatus != STATUS_GET_Cancel &&
        result.message.empty())
        result.message =
            "the PACS ended the C-GET with status " + std::to_string(response.DimseStatus);
}

void GetSession::run(DcmDataset& keys) {
    send(keys);
    for (;;) {
        T_DIMSE_Message message{};
        T_ASC_PresentationContextID context = 0;
        DcmDataset* statusDetail = nullptr;
        m_association.acknowledgeQuickly();
        OFCondition cond =
            DIMSE_receiveCommand(m_association.get(), DIMSE_NONBLOCKING,
                                 m_association.timeoutSeconds(), &context, &message, &statusDetail);
        delete statusDetail;
        if (cond.good() && message.CommandField == DIMSE_C_STORE_RQ)
            cond = m_transfer.receive(m_association.get(), m_association.timeoutSeconds(), context,
                                      message.msg.CStoreRQ);
        else if (cond.good() && message.CommandField != DIMSE_C_GET_RSP)
            cond = DIMSE_BADCOMMANDTYPE;
        if (cond.bad())
            m_association.fail("C-GET", cond);
        if (message.CommandField == DIMSE_C_GET_RSP &&
            message.msg.CGetRSP.DimseStatus != STATUS_Pending)
            return finish(message.msg.CGetRSP);
    }
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
    const std::uint64_t available = detail::availableBytes(request.store);
    if (available < needed)
        throw PacsError(PacsFailure::DiskFull, subject,
                        "not enough disk space in " + request.store.string() + ": " +
                            std::to_string(available >> 20) + " MiB free, " +
                            std::to_string(needed >> 20) + " MiB needed for " +
                            std::to_string(missing.size()) + " instances");
}

struct Wanted {
    const std::vector<InstanceRecord>& listed;
    const std::vector<InstanceRecord>& missing;
    const std::map<std::string, InstanceRecord>& byUid;
};

// One association for every request (a series each); a request that ends early (cancel, full
// disk, the PACS gone) ends the retrieve, whose message says why.
void transferMissing(const PacsNode& node, const RetrieveRequest& request,
                     const CallOptions& options, const Wanted& wanted,
                     const RetrieveCallback& onInstance, const core::CancelToken* cancel,
                     RetrieveResult& result) {
    const bool move = request.method == RetrieveMethod::Move;
    if (move && request.storagePort == 0)
        throw core::Error(detail::describe(node), "C-MOVE needs the workstation's storage port");
    Association association(node, options,
                            move ? std::vector<detail::PresentationContext>{detail::moveContext()}
                                 : getContexts(wanted.missing),
                            move ? request.storagePort : 0);
    try {
        for (DcmDataset& keys : getRequests(request.studyUid, wanted.listed, wanted.missing)) {
            OFString series;
            keys.findAndGetOFString(DCM_SeriesInstanceUID, series);
            removeStaleTemporaries(request.store / request.studyUid / series.c_str());
            detail::InstanceTransfer transfer(request, wanted.byUid, onInstance, cancel, result);
            if (move)
                detail::moveInstances(association, transfer, keys, options.callingAet);
            else
                GetSession(association, transfer).run(keys);
            if (!result.message.empty())
                break;
        }
    } catch (const PacsError& error) {
        if (result.message.empty())
            result.message = error.reason();
    }
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
        transferMissing(node, request, options, {listed, missing, wanted}, onInstance, cancel,
                        result);
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
