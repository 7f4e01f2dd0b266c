#include "lw/core/json_reader.h"

#include "lw/core/error.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <optional>

namespace lw::core {

const JsonValue* JsonValue::find(std::string_view key) const {
    if (!isObject())
        return nullptr;
    for (const auto& [name, value] : object())
        if (name == key)
            return &value;
    return nullptr;
}

const char* jsonTypeName(JsonValue::Type type) {
    static const char* const names[] = {"null", "boolean", "number", "string", "array", "object"};
    return names[int(type)];
}

namespace {

constexpr std::size_t kMaxDepth = 256;

using Sax = nlohmann::json_sax<nlohmann::json>;

// "syntax error while parsing object key - unexpected '}'; ..." out of nlohmann's
// "[json.exception.parse_error.101] parse error at line 1, column 9: syntax error ...": the
// place is said once, by us, with the path.
std::string reasonOf(const nlohmann::detail::exception& error) {
    std::string_view what = error.what();
    if (const auto close = what.find("] "); close != std::string_view::npos)
        what.remove_prefix(close + 2);
    if (what.starts_with("parse error"))
        if (const auto colon = what.find(": "); colon != std::string_view::npos)
            what.remove_prefix(colon + 2);
    return std::string(what);
}

// "line L, column C" of the byte nlohmann stopped at (`position`: bytes read, so 1-based).
std::string lineAndColumn(std::string_view text, std::size_t position) {
    const std::size_t at = std::min(position > 0 ? position - 1 : 0, text.size());
    const auto line = 1 + std::count(text.begin(), text.begin() + std::ptrdiff_t(at), '\n');
    const std::size_t newline = at > 0 ? text.rfind('\n', at - 1) : std::string_view::npos;
    const std::size_t lineStart = newline == std::string_view::npos ? 0 : newline + 1;
    return "line " + std::to_string(line) + ", column " + std::to_string(at - lineStart + 1);
}

// Builds JsonValues from nlohmann's parse events on an explicit stack (no recursion however
// deep the input), refuses nesting beyond kMaxDepth (JsonValue's destructor and the readers of
// a document do recurse) and knows the path to the innermost open value for messages.
class Builder final : public Sax {
public:
    JsonValue document;

    // Why parsing stopped: "line L, column C, in annotations[0]: reason".
    std::string failure(std::string_view text) const {
        const std::string place = m_position ? lineAndColumn(text, *m_position) : std::string();
        const std::string path = openPath();
        std::string where = place;
        if (!path.empty())
            where += (where.empty() ? "in " : ", in ") + path;
        return where.empty() ? m_reason : where + ": " + m_reason;
    }

    bool null() override { return add(JsonValue()); }
    bool boolean(bool flag) override { return add(JsonValue(flag)); }
    bool number_integer(number_integer_t n) override { return add(JsonValue(double(n))); }
    bool number_unsigned(number_unsigned_t n) override { return add(JsonValue(double(n))); }
    bool number_float(number_float_t n, const string_t&) override { return add(JsonValue(n)); }
    bool string(string_t& text) override { return add(JsonValue(std::move(text))); }
    bool binary(binary_t&) override { return false; } // JSON text has no binary values
    bool start_object(std::size_t) override { return open(true); }
    bool start_array(std::size_t) override { return open(false); }
    bool key(string_t& name) override {
        m_open.back().key = std::move(name);
        return true;
    }
    bool end_object() override { return close(); }
    bool end_array() override { return close(); }
    bool parse_error(std::size_t position, const std::string&,
                     const nlohmann::detail::exception& error) override {
        m_position = position;
        m_reason = reasonOf(error);
        return false;
    }

private:
    struct Open {
        bool isObject;
        std::string key; // an object's member being read
        JsonValue::Array items;
        JsonValue::Object members;
    };

    bool add(JsonValue value) {
        if (m_open.empty()) {
            document = std::move(value);
        } else if (Open& top = m_open.back(); top.isObject) {
            top.members.emplace_back(std::move(top.key), std::move(value));
            top.key.clear(); // no member pending until the next key
        } else {
            top.items.push_back(std::move(value));
        }
        return true;
    }

    bool open(bool isObject) {
        if (m_open.size() >= kMaxDepth) {
            m_reason = "nested deeper than " + std::to_string(kMaxDepth) + " levels";
            return false;
        }
        m_open.push_back({isObject, {}, {}, {}});
        return true;
    }

    bool close() {
        Open top = std::move(m_open.back());
        m_open.pop_back();
        return add(top.isObject ? JsonValue(std::move(top.members))
                                : JsonValue(std::move(top.items)));
    }

    // "annotations[2].points": where each open container sits in the one around it, and the
    // member of the innermost object whose value was being read.
    std::string openPath() const {
        if (m_open.size() > 16) // a path through hostile nesting would be longer than useful
            return {};
        std::string path;
        for (std::size_t i = 0; i < m_open.size(); ++i) {
            const bool innermost = i + 1 == m_open.size();
            if (m_open[i].isObject && !m_open[i].key.empty())
                path += (path.empty() ? "" : ".") + m_open[i].key;
            else if (!m_open[i].isObject && !innermost)
                path += "[" + std::to_string(m_open[i].items.size()) + "]";
        }
        return path;
    }

    std::vector<Open> m_open;
    std::optional<std::size_t> m_position;
    std::string m_reason;
};

} // namespace

JsonValue parseJson(std::string_view text, const std::string& subject) {
    Builder builder;
    // Strict RFC 8259: no comments, nothing after the document.
    if (!nlohmann::json::sax_parse(text.begin(), text.end(), &builder,
                                   nlohmann::json::input_format_t::json, /*strict=*/true,
                                   /*ignore_comments=*/false))
        throw Error(subject, builder.failure(text));
    return std::move(builder.document);
}

} // namespace lw::core
