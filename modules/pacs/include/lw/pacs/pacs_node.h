#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lw::pacs {

// C-GET: the instances come back on the retrieve's own association. C-MOVE: the PACS opens
// associations to the workstation's storage SCP (its AE title is the move destination, so the
// PACS must list that AE title with this host and `storagePort`); for PACS without C-GET.
enum class RetrieveMethod { Get, Move };

// A PACS the workstation talks to: its AE title (the "called" AE title), where it listens, and
// how it is asked for images.
struct PacsNode {
    std::string name;      // what the user calls it ("Radiology PACS"); unique in the file
    std::string calledAet; // 1..16 characters, no backslash
    std::string host;
    std::uint16_t port = 104;
    RetrieveMethod retrieve = RetrieveMethod::Get;
};

// The workstation's own identity: the AE title it calls with, and the port its storage SCP
// (C-MOVE destination) listens on. The PACS must list this AE title to answer C-MOVE.
struct WorkstationIdentity {
    std::string aet = "LINEWORK";
    std::uint16_t storagePort = 11112;
};

// The node file, shared by the GUI (Settings edits it) and the CLI. Format (JSON):
//   { "workstation": {"aet": "LINEWORK", "storagePort": 11112},
//     "nodes": [ {"name": "pacs", "calledAet": "ORTHANC", "host": "10.0.0.5", "port": 4242,
//                 "retrieve": "get"} ] }
// "retrieve" is "get" (C-GET, the default when it is missing) or "move" (C-MOVE).
struct PacsNodeFile {
    WorkstationIdentity workstation;
    std::vector<PacsNode> nodes;

    const PacsNode* find(const std::string& name) const;
};

// Beside the workstation's study database: $XDG_DATA_HOME (else ~/.local/share)
// /Linework/linework/pacs-nodes.json, the folder Qt's AppDataLocation gives the GUI.
std::filesystem::path defaultNodeFilePath();
// The managed store of retrieved files, beside the database: .../Linework/linework/pacs-store.
std::filesystem::path defaultStoreFolder();

// Throws core::Error naming the file and the reason (unreadable, not JSON, a node without a
// name, a duplicate name, an AE title over 16 characters, a port outside 1..65535).
PacsNodeFile readNodeFile(const std::filesystem::path& path);
// A missing file reads as the defaults (no nodes); any other failure throws as readNodeFile.
PacsNodeFile readNodeFileOrDefaults(const std::filesystem::path& path);
// Written atomically (a temporary sibling renamed over the file): a reader never sees half a
// file. Validates first, as readNodeFile does; creates the folder.
void writeNodeFile(const std::filesystem::path& path, const PacsNodeFile& file);

// "AET@HOST:PORT" as a node (named after the text), or nullopt when `text` is not of that form.
std::optional<PacsNode> parseNodeAddress(const std::string& text);
// A node's name in `file`, or AET@HOST:PORT; throws core::Error naming `text` otherwise.
PacsNode resolveNode(const PacsNodeFile& file, const std::string& text);

// For messages: "name (AET@HOST:PORT)", or the address alone for a node named after it
// (parseNodeAddress's); an IPv6 host in brackets.
std::string describeNode(const PacsNode& node);

// Throws core::Error(subject, reason) when the AE title is empty, longer than 16 characters,
// or holds a backslash or a control character.
void validateAeTitle(const std::string& aet, const std::string& subject);

} // namespace lw::pacs
