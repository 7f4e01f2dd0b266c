#include "query.h"

#include <cstdio>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace lw::pacs::detail {
namespace {

struct FindState {
    Association* association;
    T_ASC_PresentationContextID context;
    const core::CancelToken* cancel;
    bool cancelSent = false;
    std::vector<DcmDataset> identifiers;
};

void onFindResponse(void* data, T_DIMSE_C_FindRQ* request, int /*count*/, T_DIMSE_C_FindRSP*,
                    DcmDataset* identifier) {
    auto* state = static_cast<FindState*>(data);
    if (identifier)
        state->identifiers.push_back(*identifier);
    if (!state->cancelSent && state->cancel && state->cancel->isCancelled()) {
        DIMSE_sendCancelRequest(state->association->get(), state->context, request->MessageID);
        state->cancelSent = true;
    }
}

std::string hexStatus(Uint16 status) {
    char text[8];
    std::snprintf(text, sizeof text, "%04X", unsigned(status));
    return text;
}

std::string tagText(DcmDataset& data, const DcmTagKey& tag) {
    OFString value;
    data.findAndGetOFStringArray(tag, value);
    return value.c_str();
}

} // namespace

PresentationContext studyRootFindContext() {
    return {UID_FINDStudyRootQueryRetrieveInformationModel, uncompressedTransferSyntaxes()};
}

std::vector<DcmDataset> findOnAssociation(Association& association, DcmDataset& keys,
                                          const core::CancelToken* cancel) {
    const std::string model = UID_FINDStudyRootQueryRetrieveInformationModel;
    FindState state{&association, association.contextFor(model), cancel};
    T_DIMSE_C_FindRQ request{};
    request.MessageID = association.nextMessageId();
    OFStandard::strlcpy(request.AffectedSOPClassUID, model.c_str(),
                        sizeof request.AffectedSOPClassUID);
    request.DataSetType = DIMSE_DATASET_PRESENT;
    request.Priority = DIMSE_PRIORITY_MEDIUM;
    T_DIMSE_C_FindRSP response{};
    DcmDataset* statusDetail = nullptr;
    int count = 0;
    const OFCondition cond = DIMSE_findUser(association.get(), state.context, &request, &keys,
                                            count, onFindResponse, &state, DIMSE_NONBLOCKING,
                                            association.timeoutSeconds(), &response, &statusDetail);
    delete statusDetail;
    if (cond.bad())
        association.fail("C-FIND", cond);
    if (state.cancelSent)
        throw core::Cancelled();
    if (response.DimseStatus != STATUS_Success)
        throw PacsError(PacsFailure::Refused, association.subject(),
                        "C-FIND refused with status " + hexStatus(response.DimseStatus));
    return std::move(state.identifiers);
}

DcmDataset instanceKeys(const std::string& studyUid, const std::string& seriesUid) {
    DcmDataset keys;
    keys.putAndInsertString(DCM_QueryRetrieveLevel, "IMAGE");
    keys.putAndInsertString(DCM_StudyInstanceUID, studyUid.c_str());
    keys.putAndInsertString(DCM_SeriesInstanceUID, seriesUid.c_str());
    keys.putAndInsertString(DCM_SOPInstanceUID, "");
    keys.putAndInsertString(DCM_SOPClassUID, "");
    return keys;
}

InstanceRecord instanceRecord(DcmDataset& identifier) {
    return {tagText(identifier, DCM_SOPInstanceUID), tagText(identifier, DCM_SeriesInstanceUID),
            tagText(identifier, DCM_SOPClassUID)};
}

} // namespace lw::pacs::detail
