// C-STORE of files the workstation made (a Secondary Capture, an Encapsulated PDF) to a PACS.
#include "lw/pacs/store_scu.h"

#include "association.h"

#include <cstdio>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <memory>
#include <set>

namespace lw::pacs {
namespace {

struct LoadedFile {
    std::filesystem::path path;
    std::unique_ptr<DcmFileFormat> content;
    std::string sopClass, sopInstance, transferSyntax;
};

LoadedFile load(const std::filesystem::path& path) {
    LoadedFile file{path, std::make_unique<DcmFileFormat>(), {}, {}, {}};
    const OFCondition cond = file.content->loadFile(path.c_str());
    if (cond.bad())
        throw core::Error(path.string(), std::string("cannot read it as DICOM: ") + cond.text());
    OFString sopClass, sopInstance;
    file.content->getDataset()->findAndGetOFString(DCM_SOPClassUID, sopClass);
    file.content->getDataset()->findAndGetOFString(DCM_SOPInstanceUID, sopInstance);
    if (sopClass.empty() || sopInstance.empty())
        throw core::Error(path.string(),
                          "no SOP Class or SOP Instance UID: not a DICOM object to send");
    file.sopClass = sopClass.c_str();
    file.sopInstance = sopInstance.c_str();
    file.transferSyntax = DcmXfer(file.content->getDataset()->getOriginalXfer()).getXferID();
    return file;
}

// A context per SOP class and transfer syntax as stored: the files are sent as they are.
std::vector<detail::PresentationContext> storeContexts(const std::vector<LoadedFile>& files) {
    std::vector<detail::PresentationContext> contexts;
    std::set<std::pair<std::string, std::string>> seen;
    for (const LoadedFile& file : files)
        if (seen.insert({file.sopClass, file.transferSyntax}).second)
            contexts.push_back({file.sopClass, {file.transferSyntax}});
    return contexts;
}

std::string statusWords(Uint16 status) {
    char hex[8];
    std::snprintf(hex, sizeof hex, "%04X", unsigned(status));
    if (status == STATUS_Success)
        return "stored";
    if ((status & 0xF000) == 0xB000)
        return std::string("stored with warning ") + hex;
    if ((status & 0xFF00) == 0xA700)
        return std::string("refused: out of resources (") + hex + ")";
    if ((status & 0xFF00) == 0xA900)
        return std::string("refused: data set does not match SOP class (") + hex + ")";
    if ((status & 0xF000) == 0xC000)
        return std::string("refused: cannot understand (") + hex + ")";
    return std::string("refused with status ") + hex;
}

StoreOutcome sendOne(detail::Association& association, LoadedFile& file) {
    StoreOutcome outcome{file.path, file.sopInstance};
    const T_ASC_PresentationContextID context = ASC_findAcceptedPresentationContextID(
        association.get(), file.sopClass.c_str(), file.transferSyntax.c_str());
    if (context == 0) {
        outcome.message = "refused: the PACS accepted no presentation context for its SOP class " +
                          file.sopClass + " in transfer syntax " + file.transferSyntax;
        return outcome;
    }
    T_DIMSE_C_StoreRQ request{};
    request.MessageID = association.nextMessageId();
    OFStandard::strlcpy(request.AffectedSOPClassUID, file.sopClass.c_str(),
                        sizeof request.AffectedSOPClassUID);
    OFStandard::strlcpy(request.AffectedSOPInstanceUID, file.sopInstance.c_str(),
                        sizeof request.AffectedSOPInstanceUID);
    request.DataSetType = DIMSE_DATASET_PRESENT;
    request.Priority = DIMSE_PRIORITY_MEDIUM;
    T_DIMSE_C_StoreRSP response{};
    DcmDataset* detail = nullptr;
    const OFCondition cond = DIMSE_storeUser(
        association.get(), context, &request, nullptr, file.content->getDataset(), nullptr, nullptr,
        DIMSE_NONBLOCKING, association.timeoutSeconds(), &response, &detail);
    delete detail;
    if (cond.bad())
        association.fail("C-STORE of " + file.path.string(), cond);
    outcome.status = response.DimseStatus;
    outcome.accepted =
        response.DimseStatus == STATUS_Success || (response.DimseStatus & 0xF000) == 0xB000;
    outcome.message = statusWords(response.DimseStatus);
    return outcome;
}

} // namespace

std::vector<StoreOutcome> storeFiles(const PacsNode& node,
                                     const std::vector<std::filesystem::path>& paths,
                                     const CallOptions& options) {
    std::vector<LoadedFile> files;
    for (const std::filesystem::path& path : paths)
        files.push_back(load(path));
    if (files.empty())
        return {};
    detail::Association association(node, options, storeContexts(files));
    std::vector<StoreOutcome> outcomes;
    for (LoadedFile& file : files)
        outcomes.push_back(sendOne(association, file));
    return outcomes;
}

} // namespace lw::pacs
