#pragma once

#include "lw/core/progress.h"
#include "lw/pacs/pacs_error.h"
#include "lw/pacs/pacs_node.h"

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace lw::pacs {

// Who calls and how long to wait: for the TCP connect, the association and each DIMSE message.
struct CallOptions {
    std::string callingAet = "LINEWORK";
    std::chrono::seconds timeout{10};
};

// C-ECHO's outcome in words, for a "Test" button and `pacs echo`.
struct EchoResult {
    bool ok = false;
    std::optional<PacsFailure> failure; // empty when ok
    std::string message;                // "accepted", "connection refused: ...", ...
};
EchoResult echo(const PacsNode& node, const CallOptions& options);

// C-FIND, Study Root. Empty fields match everything; names and IDs accept DICOM wildcards (* ?).
struct StudyQuery {
    std::string patientName; // "DOE^J*"
    std::string patientId;
    std::string dateFrom; // YYYYMMDD, either or both may be empty
    std::string dateTo;
    std::string modality; // "CT": ModalitiesInStudy
};

struct StudyRecord {
    std::string studyInstanceUid;
    std::string patientName;
    std::string patientId;
    std::string studyDate;
    std::string studyDescription;
    std::string accessionNumber;
    std::string modalities;     // "CT\\SR"
    int numberOfInstances = -1; // -1: the PACS did not say
};

struct SeriesRecord {
    std::string seriesInstanceUid;
    std::string modality;
    std::string seriesNumber;
    std::string seriesDescription;
    int numberOfInstances = -1;
};

struct InstanceRecord {
    std::string sopInstanceUid;
    std::string seriesInstanceUid;
    std::string sopClassUid;
};

// Each throws PacsError (the node, what failed) and core::Cancelled when `cancel` is set: the
// token is checked between responses, and a set token sends C-CANCEL and ends the query.
std::vector<StudyRecord> findStudies(const PacsNode& node, const StudyQuery& query,
                                     const CallOptions& options,
                                     const core::CancelToken* cancel = nullptr);
std::vector<SeriesRecord> findSeries(const PacsNode& node, const std::string& studyUid,
                                     const CallOptions& options,
                                     const core::CancelToken* cancel = nullptr);
// The instances of a study, or of one of its series when `seriesUid` is not empty.
std::vector<InstanceRecord> findInstances(const PacsNode& node, const std::string& studyUid,
                                          const std::string& seriesUid, const CallOptions& options,
                                          const core::CancelToken* cancel = nullptr);

// The DICOM date range "FROM-TO" (either side may be empty) as two YYYYMMDD dates; throws
// core::Error naming `text` when a side is not 8 digits.
std::pair<std::string, std::string> parseDateRange(const std::string& text);

} // namespace lw::pacs
