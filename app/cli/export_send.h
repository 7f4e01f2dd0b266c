#pragma once

// `linework-cli export ... --send NODE`: the export's DICOM files (the Secondary Capture and the
// Encapsulated PDF report, both in the source's study) sent to the PACS by C-STORE.

#include "pacs_target.h"

#include <filesystem>
#include <ostream>
#include <vector>

namespace lw::cli {

// Sends `files` in one association and prints what the PACS answered per file. Returns 0 when
// it stored every file, 1 when it refused any (the message on stderr names the node and the
// count). Throws core::Error naming the node when no association was made (the PACS is down,
// refused the AE titles, timed out); the written files are kept either way.
int sendExports(const PacsTarget& target, const std::vector<std::filesystem::path>& files,
                std::ostream& out);

} // namespace lw::cli
