#pragma once

// The PACS node a command talks to and how to call it, from the command line: NODE is a node of
// the node file (--nodes FILE, default beside the study database) or AET@HOST:PORT; the calling
// AE title is the node file's workstation AE title unless --aet says; --timeout in seconds.
// Shared by `pacs ...` and `export --send NODE`.

#include "arguments.h"
#include "lw/pacs/pacs_client.h"
#include "lw/pacs/pacs_node.h"

#include <cstdint>
#include <set>
#include <string>

namespace lw::cli {

// The options resolvePacsTarget reads: nodes, aet, timeout.
const std::set<std::string>& pacsTargetOptions();

struct PacsTarget {
    pacs::PacsNode node;
    pacs::CallOptions options;
    std::uint16_t storagePort = 0; // the node file's, for C-MOVE
};

// Throws UsageError for an unknown node, a malformed AE title, a timeout outside 1..3600 s;
// core::Error naming the node file when it cannot be read.
PacsTarget resolvePacsTarget(const Arguments& arguments, const std::string& nodeText);

} // namespace lw::cli
