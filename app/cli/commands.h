#pragma once

#include <iosfwd>
#include <string>
#include <vector>

namespace lw::cli {

// Each sub-command takes its arguments (after the command name) and returns the exit code.
// Errors are thrown as core::Error and reported by main().
int runInfo(const std::vector<std::string>& args, std::ostream& out);
int runBenchImport(const std::vector<std::string>& args, std::ostream& out);
int runRender(const std::vector<std::string>& args, std::ostream& out);
int runPhantom(const std::vector<std::string>& args, std::ostream& out);
int runBenchMc(const std::vector<std::string>& args, std::ostream& out);
int runAccuracy(const std::vector<std::string>& args, std::ostream& out);
int runBench(const std::vector<std::string>& args, std::ostream& out);
int runQuality(const std::vector<std::string>& args, std::ostream& out);
// The thin INPUT's drawing against its thick version's (made by averaging, or read).
int runThickSlices(const std::vector<std::string>& args, std::ostream& out);
int runConvert(const std::vector<std::string>& args, std::ostream& out);
// In a build without modules/report (no Qt or no DCMTK) it says so and returns 1.
int runExport(const std::vector<std::string>& args, std::ostream& out);
// echo, find, get, store against a PACS; in a build without modules/pacs (no DCMTK) it says so.
int runPacs(const std::vector<std::string>& args, std::ostream& out);

} // namespace lw::cli
