#include "move.h"

#include <cstdio>
#include <dcmtk/dcmdata/dcuid.h>

namespace lw::pacs::detail {
namespace {

struct MoveState {
    InstanceTransfer& transfer;
    int timeoutSeconds;
    std::string problem; // a sub-association that broke
};

void dropSubAssociation(T_ASC_Association** sub, bool abort) {
    if (abort)
        ASC_abortAssociation(*sub);
    ASC_dropSCPAssociation(*sub);
    ASC_destroyAssociation(sub);
    *sub = nullptr;
}

// The PACS's association to the storage SCP: every storage SOP class, uncompressed preferred
// (what the PACS holds compressed it may send so too).
void acceptSubAssociation(T_ASC_Network* network, T_ASC_Association** sub) {
    if (ASC_receiveAssociation(network, sub, ASC_DEFAULTMAXPDU).bad()) {
        if (*sub)
            dropSubAssociation(sub, false);
        return;
    }
    const char* syntaxes[] = {
        UID_LittleEndianExplicitTransferSyntax, UID_LittleEndianImplicitTransferSyntax,
        UID_JPEGLSLosslessTransferSyntax,       UID_JPEGProcess14SV1TransferSyntax,
        UID_JPEG2000LosslessOnlyTransferSyntax, UID_RLELosslessTransferSyntax};
    const int count = int(sizeof syntaxes / sizeof *syntaxes);
    const char* verification[] = {UID_VerificationSOPClass};
    ASC_acceptContextsWithPreferredTransferSyntaxes((*sub)->params, verification, 1, syntaxes,
                                                    count);
    ASC_acceptContextsWithPreferredTransferSyntaxes((*sub)->params, dcmAllStorageSOPClassUIDs,
                                                    numberOfDcmAllStorageSOPClassUIDs, syntaxes,
                                                    count);
    disableNagle(*sub);
    if (ASC_acknowledgeAssociation(*sub).bad())
        dropSubAssociation(sub, false);
}

void serveSubAssociation(MoveState& state, T_ASC_Association** sub) {
    if (!ASC_dataWaiting(*sub, 0))
        return;
    T_DIMSE_Message message{};
    T_ASC_PresentationContextID context = 0;
    acknowledgeQuickly(*sub);
    OFCondition cond = DIMSE_receiveCommand(*sub, DIMSE_BLOCKING, 0, &context, &message, nullptr);
    if (cond.good() && message.CommandField == DIMSE_C_STORE_RQ)
        cond = state.transfer.receive(*sub, state.timeoutSeconds, context, message.msg.CStoreRQ);
    else if (cond.good() && message.CommandField == DIMSE_C_ECHO_RQ)
        cond = DIMSE_sendEchoResponse(*sub, context, &message.msg.CEchoRQ, STATUS_Success, nullptr);
    else if (cond.good())
        cond = DIMSE_BADCOMMANDTYPE;
    if (cond == DUL_PEERREQUESTEDRELEASE) {
        ASC_acknowledgeRelease(*sub);
        dropSubAssociation(sub, false);
    } else if (cond == DUL_PEERABORTEDASSOCIATION) {
        dropSubAssociation(sub, false);
    } else if (cond.bad()) {
        state.problem =
            std::string("the PACS's association to the storage SCP failed: ") + cond.text();
        dropSubAssociation(sub, true);
    }
}

void onSubOperation(void* data, T_ASC_Network* network, T_ASC_Association** sub) {
    if (*sub == nullptr)
        acceptSubAssociation(network, sub);
    else
        serveSubAssociation(*static_cast<MoveState*>(data), sub);
}

std::string moveFailure(const T_DIMSE_C_MoveRSP& response, const std::string& destination) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "%04X", unsigned(response.DimseStatus));
    if (response.DimseStatus == STATUS_MOVE_Failed_MoveDestinationUnknown)
        return "the PACS does not know the move destination \"" + destination +
               "\" (it must list this AE title with the workstation's host and storage port)";
    return "the PACS ended the C-MOVE with status " + std::string(hex) + " (" +
           std::to_string(response.NumberOfFailedSubOperations) +
           " failed: can it reach the workstation's storage port?)";
}

} // namespace

PresentationContext moveContext() {
    return {UID_MOVEStudyRootQueryRetrieveInformationModel, uncompressedTransferSyntaxes()};
}

void moveInstances(Association& association, InstanceTransfer& transfer, DcmDataset& keys,
                   const std::string& destinationAet) {
    const T_ASC_PresentationContextID context =
        association.contextFor(UID_MOVEStudyRootQueryRetrieveInformationModel);
    T_DIMSE_C_MoveRQ request{};
    request.MessageID = association.nextMessageId();
    OFStandard::strlcpy(request.AffectedSOPClassUID, UID_MOVEStudyRootQueryRetrieveInformationModel,
                        sizeof request.AffectedSOPClassUID);
    OFStandard::strlcpy(request.MoveDestination, destinationAet.c_str(),
                        sizeof request.MoveDestination);
    request.Priority = DIMSE_PRIORITY_MEDIUM;
    request.DataSetType = DIMSE_DATASET_PRESENT;
    T_ASC_Association* main = association.get();
    const DIC_US id = request.MessageID;
    transfer.setCancelRequest([main, context, id] { DIMSE_sendCancelRequest(main, context, id); });
    MoveState state{transfer, association.timeoutSeconds(), {}};
    T_DIMSE_C_MoveRSP response{};
    DcmDataset* statusDetail = nullptr;
    DcmDataset* responseIdentifiers = nullptr;
    const OFCondition cond =
        DIMSE_moveUser(main, context, &request, &keys, nullptr, nullptr, DIMSE_NONBLOCKING,
                       association.timeoutSeconds(), association.network(), onSubOperation, &state,
                       &response, &statusDetail, &responseIdentifiers);
    delete statusDetail;
    delete responseIdentifiers;
    if (cond.bad())
        association.fail("C-MOVE", cond);
    RetrieveResult& result = transfer.result();
    if (response.opts & O_MOVE_NUMBEROFFAILEDSUBOPERATIONS)
        result.failed += response.NumberOfFailedSubOperations;
    if (!state.problem.empty() && result.message.empty())
        result.message = state.problem;
    if (response.DimseStatus != STATUS_Success && response.DimseStatus != STATUS_MOVE_Cancel &&
        result.message.empty())
        result.message = moveFailure(response, destinationAet);
}

} // namespace lw::pacs::detail
