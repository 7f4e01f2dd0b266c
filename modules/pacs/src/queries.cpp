// C-ECHO and the C-FIND queries of the public API: one association each.
#include "query.h"

#include <cctype>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace lw::pacs {
namespace {

using detail::Association;

std::string text(DcmDataset& data, const DcmTagKey& tag) {
    OFString value;
    data.findAndGetOFStringArray(tag, value);
    return value.c_str();
}

int count(DcmDataset& data, const DcmTagKey& tag) {
    const std::string value = text(data, tag);
    if (value.empty())
        return -1;
    try {
        return std::stoi(value);
    } catch (const std::exception&) {
        return -1;
    }
}

std::vector<DcmDataset> query(const PacsNode& node, DcmDataset& keys, const CallOptions& options,
                              const core::CancelToken* cancel) {
    Association association(node, options, {detail::studyRootFindContext()});
    return detail::findOnAssociation(association, keys, cancel);
}

std::string dateKey(const std::string& from, const std::string& to) {
    if (from.empty() && to.empty())
        return {};
    if (from == to)
        return from;
    return from + "-" + to;
}

void checkDate(const std::string& date, const std::string& subject) {
    if (date.empty())
        return;
    if (date.size() != 8 ||
        !std::all_of(date.begin(), date.end(), [](unsigned char c) { return std::isdigit(c); }))
        throw core::Error(subject, "\"" + date + "\" is not a date YYYYMMDD");
}

} // namespace

const char* failureName(PacsFailure failure) {
    switch (failure) {
    case PacsFailure::ConnectionRefused:
        return "connection refused";
    case PacsFailure::TimedOut:
        return "timed out";
    case PacsFailure::CalledAeRejected:
        return "called AE title not recognised";
    case PacsFailure::CallingAeRejected:
        return "calling AE title not recognised";
    case PacsFailure::AssociationRejected:
        return "association rejected";
    case PacsFailure::Aborted:
        return "aborted";
    case PacsFailure::NotSupported:
        return "not supported";
    case PacsFailure::Refused:
        return "refused";
    case PacsFailure::DiskFull:
        return "disk full";
    case PacsFailure::Network:
        return "network error";
    }
    return "unknown";
}

EchoResult echo(const PacsNode& node, const CallOptions& options) {
    try {
        Association association(
            node, options, {{UID_VerificationSOPClass, detail::uncompressedTransferSyntaxes()}});
        DIC_US status = 0;
        DcmDataset* detail = nullptr;
        const OFCondition cond =
            DIMSE_echoUser(association.get(), association.nextMessageId(), DIMSE_NONBLOCKING,
                           association.timeoutSeconds(), &status, &detail);
        delete detail;
        if (cond.bad())
            association.fail("C-ECHO", cond);
        if (status != STATUS_Success)
            throw PacsError(PacsFailure::Refused, association.subject(),
                            "C-ECHO answered with a failure status");
        return {true, std::nullopt, "accepted"};
    } catch (const PacsError& error) {
        return {false, error.kind(), error.reason()};
    }
}

std::pair<std::string, std::string> parseDateRange(const std::string& range) {
    const std::size_t dash = range.find('-');
    const std::string from = dash == std::string::npos ? range : range.substr(0, dash);
    const std::string to = dash == std::string::npos ? range : range.substr(dash + 1);
    checkDate(from, range);
    checkDate(to, range);
    return {from, to};
}

std::vector<StudyRecord> findStudies(const PacsNode& node, const StudyQuery& studyQuery,
                                     const CallOptions& options, const core::CancelToken* cancel) {
    DcmDataset keys;
    keys.putAndInsertString(DCM_QueryRetrieveLevel, "STUDY");
    keys.putAndInsertString(DCM_StudyInstanceUID, "");
    keys.putAndInsertString(DCM_PatientName, studyQuery.patientName.c_str());
    keys.putAndInsertString(DCM_PatientID, studyQuery.patientId.c_str());
    keys.putAndInsertString(DCM_StudyDate, dateKey(studyQuery.dateFrom, studyQuery.dateTo).c_str());
    keys.putAndInsertString(DCM_ModalitiesInStudy, studyQuery.modality.c_str());
    keys.putAndInsertString(DCM_StudyDescription, "");
    keys.putAndInsertString(DCM_AccessionNumber, "");
    keys.putAndInsertString(DCM_NumberOfStudyRelatedInstances, "");
    std::vector<StudyRecord> studies;
    for (DcmDataset& found : query(node, keys, options, cancel))
        studies.push_back({text(found, DCM_StudyInstanceUID), text(found, DCM_PatientName),
                           text(found, DCM_PatientID), text(found, DCM_StudyDate),
                           text(found, DCM_StudyDescription), text(found, DCM_AccessionNumber),
                           text(found, DCM_ModalitiesInStudy),
                           count(found, DCM_NumberOfStudyRelatedInstances)});
    return studies;
}

std::vector<SeriesRecord> findSeries(const PacsNode& node, const std::string& studyUid,
                                     const CallOptions& options, const core::CancelToken* cancel) {
    DcmDataset keys;
    keys.putAndInsertString(DCM_QueryRetrieveLevel, "SERIES");
    keys.putAndInsertString(DCM_StudyInstanceUID, studyUid.c_str());
    keys.putAndInsertString(DCM_SeriesInstanceUID, "");
    keys.putAndInsertString(DCM_Modality, "");
    keys.putAndInsertString(DCM_SeriesNumber, "");
    keys.putAndInsertString(DCM_SeriesDescription, "");
    keys.putAndInsertString(DCM_NumberOfSeriesRelatedInstances, "");
    std::vector<SeriesRecord> series;
    for (DcmDataset& found : query(node, keys, options, cancel))
        series.push_back({text(found, DCM_SeriesInstanceUID), text(found, DCM_Modality),
                          text(found, DCM_SeriesNumber), text(found, DCM_SeriesDescription),
                          count(found, DCM_NumberOfSeriesRelatedInstances)});
    return series;
}

std::vector<InstanceRecord> findInstances(const PacsNode& node, const std::string& studyUid,
                                          const std::string& seriesUid, const CallOptions& options,
                                          const core::CancelToken* cancel) {
    DcmDataset keys = detail::instanceKeys(studyUid, seriesUid);
    std::vector<InstanceRecord> instances;
    for (DcmDataset& found : query(node, keys, options, cancel))
        instances.push_back(detail::instanceRecord(found));
    return instances;
}

} // namespace lw::pacs
