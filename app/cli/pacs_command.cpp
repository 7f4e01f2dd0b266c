// `linework-cli pacs echo|find|get|store NODE ...`: modules/pacs headless. NODE is a node of the
// node file (--nodes, default beside the study database) or AET@HOST:PORT.
#include "arguments.h"
#include "commands.h"
#include "lw/core/json_writer.h"
#include "lw/pacs/pacs_client.h"
#include "lw/pacs/retrieve.h"
#include "lw/pacs/store_scu.h"
#include "pacs_database.h"
#include "pacs_target.h"

#include <chrono>
#include <cstdio>
#include <ostream>

namespace lw::cli {

#ifndef LINEWORK_HAVE_STUDYDB
bool canRegisterInDatabase() {
    return false;
}
Registration registerInDatabase(const std::filesystem::path&, const std::string&) {
    throw core::Error("--database", "this linework-cli was built without the study database (it "
                                    "needs Qt 6: LINEWORK_GUI)");
}
#endif

namespace {

std::set<std::string> with(std::set<std::string> options) {
    options.insert(pacsTargetOptions().begin(), pacsTargetOptions().end());
    return options;
}

using Target = PacsTarget;

// The node named by the first positional.
Target target(const Arguments& arguments, std::size_t positionalsWanted) {
    if (arguments.positionals().size() < positionalsWanted)
        throw UsageError("pacs", "NODE is missing (a node's name or AET@HOST:PORT)");
    return resolvePacsTarget(arguments, arguments.positionals()[0]);
}

int runEcho(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {}, pacsTargetOptions());
    const Target to = target(arguments, 1);
    const pacs::EchoResult result = pacs::echo(to.node, to.options);
    if (!result.ok)
        throw pacs::PacsError(*result.failure,
                              to.node.calledAet + "@" + to.node.host + ":" +
                                  std::to_string(to.node.port),
                              result.message);
    out << "C-ECHO " << to.node.name << ": " << result.message << "\n";
    return 0;
}

void writeStudies(const std::vector<pacs::StudyRecord>& studies, bool json, std::ostream& out) {
    if (!json) {
        for (const pacs::StudyRecord& s : studies)
            out << s.studyDate << "  " << s.patientId << "  " << s.patientName << "  "
                << s.modalities << "  " << s.studyDescription << "  " << s.studyInstanceUid << "\n";
        out << studies.size() << " studies\n";
        return;
    }
    core::JsonWriter writer;
    writer.beginObject().key("studies").beginArray();
    for (const pacs::StudyRecord& s : studies)
        writer.beginObject()
            .field("studyInstanceUid", s.studyInstanceUid)
            .field("patientName", s.patientName)
            .field("patientId", s.patientId)
            .field("studyDate", s.studyDate)
            .field("studyDescription", s.studyDescription)
            .field("accessionNumber", s.accessionNumber)
            .field("modalities", s.modalities)
            .field("instances", s.numberOfInstances)
            .endObject();
    writer.endArray().endObject();
    out << writer.str() << "\n";
}

void writeSeries(const std::vector<pacs::SeriesRecord>& series, bool json, std::ostream& out) {
    if (!json) {
        for (const pacs::SeriesRecord& s : series)
            out << s.seriesNumber << "  " << s.modality << "  " << s.numberOfInstances << "  "
                << s.seriesDescription << "  " << s.seriesInstanceUid << "\n";
        out << series.size() << " series\n";
        return;
    }
    core::JsonWriter writer;
    writer.beginObject().key("series").beginArray();
    for (const pacs::SeriesRecord& s : series)
        writer.beginObject()
            .field("seriesInstanceUid", s.seriesInstanceUid)
            .field("modality", s.modality)
            .field("seriesNumber", s.seriesNumber)
            .field("seriesDescription", s.seriesDescription)
            .field("instances", s.numberOfInstances)
            .endObject();
    writer.endArray().endObject();
    out << writer.str() << "\n";
}

// Study level by patient, date range and modality; with --study UID the series of that study.
int runFind(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json"},
                              with({"patient", "patient-id", "study-date", "modality", "study"}));
    const Target to = target(arguments, 1);
    if (const std::optional<std::string> study = arguments.option("study")) {
        writeSeries(pacs::findSeries(to.node, *study, to.options), arguments.flag("json"), out);
        return 0;
    }
    pacs::StudyQuery query;
    query.patientName = arguments.option("patient", "");
    query.patientId = arguments.option("patient-id", "");
    query.modality = arguments.option("modality", "");
    if (const std::optional<std::string> dates = arguments.option("study-date"))
        std::tie(query.dateFrom, query.dateTo) =
            parseUsage([&] { return pacs::parseDateRange(*dates); });
    writeStudies(pacs::findStudies(to.node, query, to.options), arguments.flag("json"), out);
    return 0;
}

void writeRetrieve(const pacs::RetrieveResult& result, const std::string& store, double seconds,
                   const std::optional<Registration>& registration, bool json, std::ostream& out) {
    const double rate = seconds > 0 ? double(result.transferred) / seconds : 0;
    if (!json) {
        out << result.instances << " instances: " << result.transferred << " transferred, "
            << result.skipped << " already in the store, in " << seconds << " s (" << rate
            << " instances/s), into " << store << "\n";
        if (registration)
            out << "registered in " << registration->database << ": " << registration->seriesAdded
                << " series added, " << registration->seriesUpdated << " updated\n";
        return;
    }
    core::JsonWriter writer;
    writer.beginObject()
        .field("instances", result.instances)
        .field("transferred", result.transferred)
        .field("skipped", result.skipped)
        .field("failed", result.failed)
        .field("complete", result.complete())
        .field("cancelled", result.cancelled)
        .field("seconds", seconds)
        .field("instancesPerSecond", rate)
        .field("store", store)
        .field("message", result.message);
    writer.key("database");
    if (registration)
        writer.beginObject()
            .field("path", registration->database)
            .field("seriesAdded", registration->seriesAdded)
            .field("seriesUpdated", registration->seriesUpdated)
            .endObject();
    else
        writer.null();
    writer.endObject();
    out << writer.str() << "\n";
}

int runGet(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json", "move", "no-database"},
                              with({"study", "series", "store", "storage-port", "database"}));
    const Target to = target(arguments, 1);
    pacs::RetrieveRequest request;
    request.studyUid = arguments.option("study", "");
    if (request.studyUid.empty())
        throw UsageError("pacs get", "--study UID is required");
    request.seriesUid = arguments.option("series", "");
    request.store = arguments.option("store", pacs::defaultStoreFolder().string());
    // --move, or a node set up for C-MOVE in the node file ("retrieve": "move").
    if (arguments.flag("move") || to.node.retrieve == pacs::RetrieveMethod::Move) {
        request.method = pacs::RetrieveMethod::Move;
        const double port = arguments.number("storage-port", to.storagePort);
        if (port < 1 || port > 65535 || port != double(int(port)))
            throw UsageError("--storage-port", "a port 1..65535");
        request.storagePort = std::uint16_t(port);
    }
    const auto start = std::chrono::steady_clock::now();
    const pacs::RetrieveResult result = pacs::retrieve(to.node, request, to.options);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    // What arrived is registered even when the retrieve stopped early: the database then lists
    // exactly the files that are there.
    std::optional<Registration> registration;
    const bool wanted =
        !arguments.flag("no-database") && (arguments.option("database") || canRegisterInDatabase());
    if (wanted && !result.files.empty()) {
        // Absolute: the database keeps the paths it is given; the GUI opens them from anywhere.
        const std::filesystem::path study =
            std::filesystem::absolute(request.store) / request.studyUid;
        registration =
            registerInDatabase(request.seriesUid.empty() ? study : study / request.seriesUid,
                               arguments.option("database", ""));
    }
    writeRetrieve(result, request.store.string(), seconds, registration, arguments.flag("json"),
                  out);
    if (!result.complete() || !result.message.empty()) {
        std::fprintf(stderr, "linework-cli: partial retrieve: %s\n", result.message.c_str());
        return 1;
    }
    return 0;
}

int runStore(const std::vector<std::string>& args, std::ostream& out) {
    const Arguments arguments(args, {"json"}, pacsTargetOptions());
    const Target to = target(arguments, 1);
    if (arguments.positionals().size() < 2)
        throw UsageError("pacs store", "no FILE to send");
    const std::vector<std::filesystem::path> files(arguments.positionals().begin() + 1,
                                                   arguments.positionals().end());
    const std::vector<pacs::StoreOutcome> outcomes = pacs::storeFiles(to.node, files, to.options);
    bool all = true;
    core::JsonWriter writer;
    writer.beginObject().key("files").beginArray();
    for (const pacs::StoreOutcome& outcome : outcomes) {
        all = all && outcome.accepted;
        writer.beginObject()
            .field("file", outcome.file.string())
            .field("sopInstanceUid", outcome.sopInstanceUid)
            .field("accepted", outcome.accepted)
            .field("status", int(outcome.status))
            .field("message", outcome.message)
            .endObject();
        if (!arguments.flag("json"))
            out << outcome.file.string() << ": " << outcome.message << "\n";
    }
    writer.endArray().endObject();
    if (arguments.flag("json"))
        out << writer.str() << "\n";
    return all ? 0 : 1;
}

} // namespace

int runPacs(const std::vector<std::string>& args, std::ostream& out) {
    if (args.empty())
        throw UsageError("pacs", "echo, find, get or store is missing");
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (args[0] == "echo")
        return runEcho(rest, out);
    if (args[0] == "find")
        return runFind(rest, out);
    if (args[0] == "get")
        return runGet(rest, out);
    if (args[0] == "store")
        return runStore(rest, out);
    throw UsageError("pacs " + args[0], "unknown; echo, find, get or store");
}

} // namespace lw::cli
