#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lw::core {

// A small streaming JSON writer for the CLI's machine-readable output. It tracks nesting so
// commas are placed correctly; keys are only valid inside objects. Strings are escaped by
// nlohmann-json (invalid UTF-8 becomes U+FFFD); doubles are written with 10 significant digits
// ("%.10g"; NaN and infinities as null), the format the CLI's JSON has always had.
class JsonWriter {
public:
    explicit JsonWriter(int indent = 2) : m_indent(indent) {}

    JsonWriter& beginObject();
    JsonWriter& endObject();
    JsonWriter& beginArray();
    JsonWriter& endArray();
    JsonWriter& key(std::string_view name);

    JsonWriter& value(std::string_view text);
    JsonWriter& value(const char* text) { return value(std::string_view(text)); }
    JsonWriter& value(const std::string& text) { return value(std::string_view(text)); }
    JsonWriter& value(double number);
    JsonWriter& value(std::int64_t number);
    JsonWriter& value(int number) { return value(std::int64_t(number)); }
    JsonWriter& value(std::size_t number) { return value(std::int64_t(number)); }
    JsonWriter& value(bool flag);
    JsonWriter& null();

    template <typename T> JsonWriter& field(std::string_view name, const T& v) {
        key(name);
        return value(v);
    }

    const std::string& str() const { return m_out; }

    static std::string escape(std::string_view text);

private:
    void beforeValue();
    void newline();
    void closeLevel(char bracket);

    struct Level {
        bool isObject;
        bool empty = true;
    };
    std::string m_out;
    std::vector<Level> m_stack;
    bool m_afterKey = false;
    int m_indent;
};

} // namespace lw::core
