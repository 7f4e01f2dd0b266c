#include "export_send.h"

#include "lw/pacs/pacs_error.h"
#include "lw/pacs/store_scu.h"

#include <chrono>
#include <cstdio>

namespace lw::cli {

int sendExports(const PacsTarget& target, const std::vector<std::filesystem::path>& files,
                std::ostream& out) {
    const std::string node = pacs::describeNode(target.node);
    std::vector<pacs::StoreOutcome> outcomes;
    const auto start = std::chrono::steady_clock::now();
    try {
        outcomes = pacs::storeFiles(target.node, files, target.options);
    } catch (const pacs::PacsError& error) {
        throw core::Error("--send " + node,
                          error.reason() + "; nothing was sent (the exported files are kept)");
    }
    std::size_t stored = 0;
    for (const pacs::StoreOutcome& outcome : outcomes) {
        stored += outcome.accepted ? 1 : 0;
        out << "sent " << outcome.file.string() << " to " << node << ": " << outcome.message
            << "\n";
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    char timing[48];
    std::snprintf(timing, sizeof timing, " in %.0f ms\n", ms);
    out << node << " stored " << stored << " of " << outcomes.size() << " files" << timing;
    if (stored == outcomes.size())
        return 0;
    std::fprintf(stderr, "linework-cli: --send %s: the PACS stored %zu of %zu files\n",
                 node.c_str(), stored, outcomes.size());
    return 1;
}

} // namespace lw::cli
