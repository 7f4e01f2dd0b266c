// linework-cli: the headless face of the engine. Needs no display, Qt or (optionally) DCMTK.
#include "arguments.h"
#include "commands.h"
#include "lw/core/error.h"

#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

constexpr const char* kUsage = R"(usage: linework-cli COMMAND [ARGS]

commands:
  info PATH [--json]          describe a DICOM folder/DICOMDIR/file or a volume file
                              (raw: --raw WxHxD --type int16 [--big-endian] [--spacing X,Y,Z])
  bench-import PATH [--repeat N] [--json]
                              scan a DICOM input and load all its volumes N times (default 5);
                              prints the median time and slices/s
  phantom --size N|NXxNYxNZ [--kind ct|sphere] -o OUT.nrrd
                              the deterministic benchmark phantom (tools/phantom.py); prints
                              its checksums (sum, voxels above 300.5)
  bench-mc [--size N|NXxNYxNZ] [--kind ct|sphere] [--chunks off|auto|N] [--repeat R] [--iso HU]
                              marching cubes on the phantom: median ms, triangles
  accuracy [--methods 1,2,3] [--sizes 32,64,256] [--shapes sphere,...] [--view AZ,EL]
           [--backend cpu|cuda|auto] [--json]
                              the paper's Table 5 measured: recall/precision (1 px) of each
                              method (S and L) against analytic contours
  render INPUT [--series UID] --iso HU --method 1|2|3 [--chunks off|auto|N] [--mode a|b]
         [--visibility on|off] [--view AZ,EL] [--camera perspective|ortho] [--size WxH]
         [--panel iso|silhouette|both] [--backend cpu|cuda|auto] [--repeat N] [--threads N] -o OUT.png
                              one view as PNG (default 512x512, silhouette, method 3, view 0,0);
                              INPUT: volume file, DICOM folder/DICOMDIR or phantom:N[xNYxNZ][:sphere];
                              both = shaded iso-surface left, silhouette right (width 2W);
                              --repeat N: N more views 1 degree apart, prints their median ms
  bench [--sizes 32,256,512,512x512x1024] [--input FILE --iso HU] [--backend cpu|cuda|auto]
        [--methods mc,1,2,3] [--variants S,L] [--modes a,b] [--repeat N] [--image WxH]
        [--peak-memory-of METHOD,VARIANT] [--json]
                              the paper's Tables 1-4: median ms of marching cubes and of each
                              method x S/L x mode a/b x visibility on/off (default phantom
                              32,256, 1024x1024, 5 runs), stage times, peak memory (VmHWM)
  help                        this text

Exit codes: 0 success, 1 error (the message names the file and the reason), 2 usage error.
)";

// The lines of kUsage about `command`: its synopsis and description, up to the next command
// (a line indented by exactly two spaces starts a command).
std::string usageOf(const std::string& command) {
    std::istringstream lines(kUsage);
    std::string line, text;
    bool inside = false;
    while (std::getline(lines, line)) {
        if (line.size() > 2 && line.compare(0, 2, "  ") == 0 && line[2] != ' ')
            inside = line.compare(2, command.size() + 1, command + " ") == 0;
        else if (line.empty())
            inside = false;
        if (inside)
            text += line + "\n";
    }
    return text;
}

} // namespace

int main(int argc, char** argv) {
    std::vector<std::string> args(argv + 1, argv + argc);
    if (args.empty() || args[0] == "help" || args[0] == "--help" || args[0] == "-h") {
        std::fputs(kUsage, args.empty() ? stderr : stdout);
        return args.empty() ? 2 : 0;
    }
    using Command = std::function<int(const std::vector<std::string>&, std::ostream&)>;
    const std::map<std::string, Command> commands = {
        {"info", lw::cli::runInfo},
        {"bench-import", lw::cli::runBenchImport},
        {"render", lw::cli::runRender},
        {"phantom", lw::cli::runPhantom},
        {"bench-mc", lw::cli::runBenchMc},
        {"accuracy", lw::cli::runAccuracy},
        {"bench", lw::cli::runBench},
    };
    const auto command = commands.find(args[0]);
    if (command == commands.end()) {
        std::fprintf(stderr, "linework-cli: unknown command '%s'\n\n%s", args[0].c_str(), kUsage);
        return 2;
    }
    try {
        return command->second(std::vector<std::string>(args.begin() + 1, args.end()), std::cout);
    } catch (const lw::cli::UsageError& error) {
        std::fprintf(stderr,
                     "linework-cli: %s\n\nusage (linework-cli help lists every command):\n%s",
                     error.what(), usageOf(args[0]).c_str());
        return 2;
    } catch (const lw::core::Cancelled&) {
        std::fprintf(stderr, "linework-cli: cancelled\n");
        return 1;
    } catch (const lw::core::Error& error) {
        std::fprintf(stderr, "linework-cli: %s\n", error.what());
        return 1;
    } catch (const std::exception& error) {
        std::fprintf(stderr, "linework-cli: internal error: %s\n", error.what());
        return 1;
    }
}
