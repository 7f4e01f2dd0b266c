#include "pacs_target.h"

namespace lw::cli {

const std::set<std::string>& pacsTargetOptions() {
    static const std::set<std::string> options = {"nodes", "aet", "timeout"};
    return options;
}

PacsTarget resolvePacsTarget(const Arguments& arguments, const std::string& nodeText) {
    const pacs::PacsNodeFile file = pacs::readNodeFileOrDefaults(
        arguments.option("nodes", pacs::defaultNodeFilePath().string()));
    PacsTarget result{parseUsage([&] { return pacs::resolveNode(file, nodeText); }),
                      {},
                      file.workstation.storagePort};
    result.options.callingAet = arguments.option("aet", file.workstation.aet);
    parseUsage([&] {
        pacs::validateAeTitle(result.options.callingAet, "--aet");
        return 0;
    });
    const double timeout = arguments.number("timeout", 10);
    if (timeout < 1 || timeout > 3600)
        throw UsageError("--timeout", "seconds between 1 and 3600");
    result.options.timeout = std::chrono::seconds(int(timeout));
    return result;
}

} // namespace lw::cli
