#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace lw::core {

// A parsed JSON document (RFC 8259), small and strict: files a user hands the CLI (annotations)
// are read with it. The counterpart of JsonWriter. nlohmann-json parses; this keeps its types out
// of the headers.
class JsonValue {
public:
    enum class Type { Null, Bool, Number, String, Array, Object };
    using Array = std::vector<JsonValue>;
    using Object = std::vector<std::pair<std::string, JsonValue>>; // in document order

    JsonValue() = default;
    explicit JsonValue(bool flag) : m_value(flag) {}
    explicit JsonValue(double number) : m_value(number) {}
    explicit JsonValue(std::string text) : m_value(std::move(text)) {}
    explicit JsonValue(Array items) : m_value(std::move(items)) {}
    explicit JsonValue(Object members) : m_value(std::move(members)) {}

    Type type() const { return Type(m_value.index()); }
    bool isNull() const { return type() == Type::Null; }
    bool isNumber() const { return type() == Type::Number; }
    bool isString() const { return type() == Type::String; }
    bool isArray() const { return type() == Type::Array; }
    bool isObject() const { return type() == Type::Object; }

    // Each accessor requires its type (std::bad_variant_access otherwise): check type() first.
    bool boolean() const { return std::get<bool>(m_value); }
    double number() const { return std::get<double>(m_value); }
    const std::string& string() const { return std::get<std::string>(m_value); }
    const Array& array() const { return std::get<Array>(m_value); }
    const Object& object() const { return std::get<Object>(m_value); }
    // The member named `key` of an object; nullptr when absent or when this is no object.
    const JsonValue* find(std::string_view key) const;

private:
    std::variant<std::monostate, bool, double, std::string, Array, Object> m_value;
};

// "null", "boolean", "number", "string", "array", "object": for messages.
const char* jsonTypeName(JsonValue::Type type);

// Parses one JSON document with nlohmann-json. Throws Error(subject, "line L, column C, in
// PATH: reason") for anything that is not strict JSON (trailing commas, comments, single quotes,
// bad escapes, invalid UTF-8, text after the end); C is where the parser stopped, the end of the
// token that does not fit; PATH ("annotations[2].points") names the value being read and is left
// out at the top level. Nesting deeper than 256 levels is refused too (Error(subject, "nested
// deeper than 256 levels")).
JsonValue parseJson(std::string_view text, const std::string& subject);

} // namespace lw::core
