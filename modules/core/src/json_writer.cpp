#include "lw/core/json_writer.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

namespace lw::core {

std::string JsonWriter::escape(std::string_view text) {
    // nlohmann's serializer: the escapes JSON requires, and bytes that are not UTF-8 (a Latin-1
    // DICOM name, an odd file name) replaced by U+FFFD, so the output stays valid JSON.
    return nlohmann::json(std::string(text))
        .dump(-1, ' ', /*ensure_ascii=*/false, nlohmann::json::error_handler_t::replace);
}

void JsonWriter::newline() {
    if (m_indent <= 0)
        return;
    m_out += '\n';
    m_out.append(m_stack.size() * std::size_t(m_indent), ' ');
}

void JsonWriter::beforeValue() {
    if (m_afterKey) {
        m_afterKey = false;
        return;
    }
    if (!m_stack.empty()) {
        if (!m_stack.back().empty)
            m_out += ',';
        m_stack.back().empty = false;
        newline();
    }
}

JsonWriter& JsonWriter::beginObject() {
    beforeValue();
    m_out += '{';
    m_stack.push_back({true});
    return *this;
}

void JsonWriter::closeLevel(char bracket) {
    const bool wasEmpty = m_stack.back().empty;
    m_stack.pop_back();
    if (!wasEmpty)
        newline();
    m_out += bracket;
}

JsonWriter& JsonWriter::endObject() {
    closeLevel('}');
    return *this;
}

JsonWriter& JsonWriter::beginArray() {
    beforeValue();
    m_out += '[';
    m_stack.push_back({false});
    return *this;
}

JsonWriter& JsonWriter::endArray() {
    closeLevel(']');
    return *this;
}

JsonWriter& JsonWriter::key(std::string_view name) {
    beforeValue();
    m_out += escape(name);
    m_out += m_indent > 0 ? ": " : ":";
    m_afterKey = true;
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view text) {
    beforeValue();
    m_out += escape(text);
    return *this;
}

JsonWriter& JsonWriter::value(double number) {
    beforeValue();
    if (!std::isfinite(number)) {
        m_out += "null";
        return *this;
    }
    // Ten significant digits, as `info --json` and `bench --json` have always printed them (a
    // contract). nlohmann's dump cannot do this: it prints integral doubles as "1.0" and, rounded
    // to ten digits first, about one value in a thousand with 17 digits (398.4835037 becomes
    // 398.48350370000003), so numbers are the one thing written here.
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.10g", number);
    m_out += buffer;
    return *this;
}

JsonWriter& JsonWriter::value(std::int64_t number) {
    beforeValue();
    m_out += std::to_string(number);
    return *this;
}

JsonWriter& JsonWriter::value(bool flag) {
    beforeValue();
    m_out += flag ? "true" : "false";
    return *this;
}

JsonWriter& JsonWriter::null() {
    beforeValue();
    m_out += "null";
    return *this;
}

} // namespace lw::core
