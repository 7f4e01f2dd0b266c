// The PACS node file: read strictly (every error names the file and the value), written
// atomically. Shared by the GUI's settings and the CLI, so it is plain JSON, no Qt.
#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "lw/core/json_reader.h"
#include "lw/core/json_writer.h"
#include "lw/pacs/pacs_node.h"

#include <cstdlib>
#include <regex>
#include <set>

namespace lw::pacs {
namespace {

constexpr std::size_t kMaxNodeFileBytes = 1 << 20; // a hand-edited list of nodes

std::filesystem::path appDataFolder() {
    // Qt's AppDataLocation on Linux for organisation "Linework", application "linework".
    std::filesystem::path base;
    if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg)
        base = xdg;
    else if (const char* home = std::getenv("HOME"); home && *home)
        base = std::filesystem::path(home) / ".local" / "share";
    else
        base = std::filesystem::temp_directory_path();
    return base / "Linework" / "linework";
}

const core::JsonValue& member(const core::JsonValue& object, std::string_view key,
                              core::JsonValue::Type type, const std::string& where,
                              const std::string& file) {
    const core::JsonValue* value = object.find(key);
    if (!value)
        throw core::Error(file, where + ": \"" + std::string(key) + "\" is missing");
    if (value->type() != type)
        throw core::Error(file, where + "." + std::string(key) + " is a " +
                                    core::jsonTypeName(value->type()) + ", expected a " +
                                    core::jsonTypeName(type));
    return *value;
}

std::uint16_t portValue(const core::JsonValue& object, std::string_view key,
                        const std::string& where, const std::string& file) {
    const double port = member(object, key, core::JsonValue::Type::Number, where, file).number();
    if (port < 1 || port > 65535 || port != double(int(port)))
        throw core::Error(file, where + "." + std::string(key) + " is " + std::to_string(port) +
                                    ", not a port (1..65535)");
    return std::uint16_t(port);
}

PacsNode readNode(const core::JsonValue& value, const std::string& where, const std::string& file) {
    if (!value.isObject())
        throw core::Error(file, where + " is not an object");
    using T = core::JsonValue::Type;
    PacsNode node;
    node.name = member(value, "name", T::String, where, file).string();
    node.calledAet = member(value, "calledAet", T::String, where, file).string();
    node.host = member(value, "host", T::String, where, file).string();
    node.port = portValue(value, "port", where, file);
    if (const core::JsonValue* retrieve = value.find("retrieve")) {
        const std::string method = retrieve->isString() ? retrieve->string() : std::string();
        if (method != "get" && method != "move")
            throw core::Error(file, where + ".retrieve is not \"get\" or \"move\"");
        node.retrieve = method == "move" ? RetrieveMethod::Move : RetrieveMethod::Get;
    }
    return node;
}

void validate(const PacsNodeFile& content, const std::string& file) {
    validateAeTitle(content.workstation.aet, file + ": workstation.aet");
    std::set<std::string> names;
    for (const PacsNode& node : content.nodes) {
        if (node.name.empty())
            throw core::Error(file, "a node has an empty name");
        if (!names.insert(node.name).second)
            throw core::Error(file, "two nodes are named \"" + node.name + "\"");
        if (node.host.empty())
            throw core::Error(file, "node \"" + node.name + "\" has an empty host");
        if (node.port == 0)
            throw core::Error(file, "node \"" + node.name + "\" has port 0");
        validateAeTitle(node.calledAet, file + ": node \"" + node.name + "\"");
    }
}

} // namespace

const PacsNode* PacsNodeFile::find(const std::string& name) const {
    for (const PacsNode& node : nodes)
        if (node.name == name)
            return &node;
    return nullptr;
}

std::filesystem::path defaultNodeFilePath() {
    return appDataFolder() / "pacs-nodes.json";
}
std::filesystem::path defaultStoreFolder() {
    return appDataFolder() / "pacs-store";
}

void validateAeTitle(const std::string& aet, const std::string& subject) {
    if (aet.empty() || aet.size() > 16)
        throw core::Error(subject, "the AE title \"" + aet + "\" must have 1 to 16 characters");
    for (const char c : aet)
        if (c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
            throw core::Error(subject, "the AE title \"" + aet +
                                           "\" holds a backslash or a control character");
}

PacsNodeFile readNodeFile(const std::filesystem::path& path) {
    const std::string file = path.string();
    const core::JsonValue root = core::parseJson(core::readFileText(path, kMaxNodeFileBytes), file);
    if (!root.isObject())
        throw core::Error(file, "the node file is not a JSON object");
    using T = core::JsonValue::Type;
    PacsNodeFile content;
    if (const core::JsonValue* station = root.find("workstation")) {
        if (!station->isObject())
            throw core::Error(file, "workstation is not an object");
        content.workstation.aet = member(*station, "aet", T::String, "workstation", file).string();
        content.workstation.storagePort = portValue(*station, "storagePort", "workstation", file);
    }
    if (const core::JsonValue* nodes = root.find("nodes")) {
        if (!nodes->isArray())
            throw core::Error(file, "nodes is not an array");
        for (std::size_t i = 0; i < nodes->array().size(); ++i)
            content.nodes.push_back(
                readNode(nodes->array()[i], "nodes[" + std::to_string(i) + "]", file));
    }
    validate(content, file);
    return content;
}

PacsNodeFile readNodeFileOrDefaults(const std::filesystem::path& path) {
    std::error_code error;
    if (!std::filesystem::exists(path, error) && !error)
        return {};
    return readNodeFile(path);
}

void writeNodeFile(const std::filesystem::path& path, const PacsNodeFile& content) {
    validate(content, path.string());
    core::JsonWriter json;
    json.beginObject().key("workstation").beginObject();
    json.field("aet", content.workstation.aet)
        .field("storagePort", int(content.workstation.storagePort));
    json.endObject().key("nodes").beginArray();
    for (const PacsNode& node : content.nodes) {
        json.beginObject().field("name", node.name).field("calledAet", node.calledAet);
        json.field("host", node.host).field("port", int(node.port));
        json.field("retrieve", node.retrieve == RetrieveMethod::Move ? "move" : "get").endObject();
    }
    json.endArray().endObject();
    const std::string text = json.str() + "\n";
    std::error_code error;
    if (path.has_parent_path())
        std::filesystem::create_directories(path.parent_path(), error);
    if (error)
        throw core::Error(path.string(), "cannot create its folder: " + error.message());
    core::writeFileAtomically(path, text.data(), text.size());
}

std::optional<PacsNode> parseNodeAddress(const std::string& text) {
    static const std::regex kAddress(R"(^([^@]{1,16})@(\[[^\]]+\]|[^:@]+):([0-9]{1,5})$)");
    std::smatch match;
    if (!std::regex_match(text, match, kAddress))
        return std::nullopt;
    const int port = std::stoi(match[3].str());
    if (port < 1 || port > 65535)
        return std::nullopt;
    std::string host = match[2].str();
    if (host.front() == '[')
        host = host.substr(1, host.size() - 2);
    return PacsNode{text, match[1].str(), host, std::uint16_t(port)};
}

std::string describeNode(const PacsNode& node) {
    const bool ipv6 = node.host.find(':') != std::string::npos;
    const std::string address = node.calledAet + "@" + (ipv6 ? "[" + node.host + "]" : node.host) +
                                ":" + std::to_string(node.port);
    return node.name == address ? address : node.name + " (" + address + ")";
}

PacsNode resolveNode(const PacsNodeFile& file, const std::string& text) {
    if (const PacsNode* node = file.find(text))
        return *node;
    if (std::optional<PacsNode> node = parseNodeAddress(text)) {
        validateAeTitle(node->calledAet, text);
        return *node;
    }
    throw core::Error(text, "not a node of the node file, nor AET@HOST:PORT");
}

} // namespace lw::pacs
