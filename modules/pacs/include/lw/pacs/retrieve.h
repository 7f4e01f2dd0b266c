#pragma once

#include "lw/core/progress.h"
#include "lw/pacs/pacs_client.h"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace lw::pacs {

// Where retrieved instances live: STORE/<StudyInstanceUID>/<SeriesInstanceUID>/<SOP UID>.dcm.
// A file is there only when it arrived whole (written to a temporary, then renamed), so "the
// file exists" is "the instance arrived", and a retrieve after a cancel or a killed client asks
// only for the others.
std::filesystem::path instancePath(const std::filesystem::path& store,
                                   const InstanceRecord& instance, const std::string& studyUid);

struct RetrieveRequest {
    std::string studyUid;
    std::string seriesUid; // empty: the whole study
    std::filesystem::path store;
    // Refuse to start unless this much stays free after the estimated size of what is missing.
    std::uint64_t reserveBytes = 256ull << 20;
    RetrieveMethod method = RetrieveMethod::Get;
    std::uint16_t storagePort =
        0; // C-MOVE: where the storage SCP listens (node file's storagePort)
};

struct RetrieveProgress {
    std::size_t done = 0; // instances of this retrieve that arrived so far
    std::size_t toTransfer = 0;
    std::string sopInstanceUid; // the one that just arrived
};

struct RetrieveResult {
    std::size_t instances = 0;                // what the PACS holds for the request
    std::size_t transferred = 0;              // arrived in this retrieve
    std::size_t skipped = 0;                  // already in the store
    std::size_t failed = 0;                   // the PACS reported as failed, or not sent
    std::vector<std::filesystem::path> files; // every instance of the request now in the store
    std::string message;                      // empty when all arrived; otherwise what went wrong
    bool cancelled = false;
    bool complete() const { return transferred + skipped == instances; }
};

using RetrieveCallback = std::function<void(const RetrieveProgress&)>;

// C-GET (or C-MOVE) of the missing instances of a study or series into `request.store`. Asks the
// PACS which instances there are (C-FIND, image level) first and skips those already stored. Throws
// PacsError when nothing can start (refused, timed out, not enough disk space); a transfer that
// stops halfway (cancel, a full disk, the PACS gone) returns what arrived with `message` saying
// why, and keeps every whole file.
RetrieveResult retrieve(const PacsNode& node, const RetrieveRequest& request,
                        const CallOptions& options, const RetrieveCallback& onInstance = {},
                        const core::CancelToken* cancel = nullptr);

} // namespace lw::pacs
