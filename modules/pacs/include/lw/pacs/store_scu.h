#pragma once

#include "lw/pacs/pacs_client.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace lw::pacs {

// What the PACS answered for one file sent by C-STORE.
struct StoreOutcome {
    std::filesystem::path file;
    std::string sopInstanceUid;
    bool accepted = false;    // status Success or Warning
    std::uint16_t status = 0; // the C-STORE-RSP status (0x0000 success, 0xB0xx warning, ...)
    std::string message;      // "stored", "warning: ...", "refused: ..."
};

// Sends each file in one association (a presentation context per SOP class, in the file's own
// transfer syntax). Throws PacsError when no association is made, core::Error naming the file
// when one cannot be read; a file the PACS refuses is reported in its outcome, the others go on.
std::vector<StoreOutcome> storeFiles(const PacsNode& node,
                                     const std::vector<std::filesystem::path>& files,
                                     const CallOptions& options);

} // namespace lw::pacs
