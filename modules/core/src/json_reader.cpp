#include "lw/core/json_reader.h"

#include "lw/core/error.h"

#include <charconv>
#include <cstdint>

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

constexpr int kMaxDepth = 256;

// Recursive descent over the text; every error names the line and column where it was found.
class JsonParser {
public:
    JsonParser(std::string_view text, const std::string& subject)
        : m_text(text), m_subject(subject) {}

    JsonValue document() {
        JsonValue value = parseValue(0);
        skipSpace();
        if (m_pos != m_text.size())
            fail("unexpected text after the end of the document");
        return value;
    }

private:
    [[noreturn]] void fail(const std::string& reason) const {
        int line = 1, column = 1;
        for (std::size_t i = 0; i < m_pos && i < m_text.size(); ++i) {
            column = m_text[i] == '\n' ? 1 : column + 1;
            line += m_text[i] == '\n' ? 1 : 0;
        }
        throw Error(m_subject, "line " + std::to_string(line) + ", column " +
                                   std::to_string(column) + ": " + reason);
    }

    void skipSpace() {
        while (m_pos < m_text.size() && (m_text[m_pos] == ' ' || m_text[m_pos] == '\t' ||
                                         m_text[m_pos] == '\n' || m_text[m_pos] == '\r'))
            ++m_pos;
    }

    bool consume(char c) {
        skipSpace();
        if (m_pos < m_text.size() && m_text[m_pos] == c) {
            ++m_pos;
            return true;
        }
        return false;
    }

    void expect(char c, const char* what) {
        if (!consume(c))
            fail(std::string("expected ") + what);
    }

    bool literal(std::string_view word) {
        if (m_text.substr(m_pos, word.size()) != word)
            return false;
        m_pos += word.size();
        return true;
    }

    JsonValue parseValue(int depth) {
        if (depth > kMaxDepth)
            fail("nested deeper than " + std::to_string(kMaxDepth) + " levels");
        skipSpace();
        if (m_pos >= m_text.size())
            fail("unexpected end of the document");
        const char c = m_text[m_pos];
        if (c == '{')
            return parseObject(depth);
        if (c == '[')
            return parseArray(depth);
        if (c == '"')
            return JsonValue(parseString());
        if (literal("true"))
            return JsonValue(true);
        if (literal("false"))
            return JsonValue(false);
        if (literal("null"))
            return JsonValue();
        if (c == '-' || (c >= '0' && c <= '9'))
            return JsonValue(parseNumber());
        fail(std::string("unexpected character '") + c + "'");
    }

    JsonValue parseObject(int depth) {
        ++m_pos; // '{'
        JsonValue::Object members;
        if (consume('}'))
            return JsonValue(std::move(members));
        do {
            skipSpace();
            if (m_pos >= m_text.size() || m_text[m_pos] != '"')
                fail("expected a member name in double quotes");
            std::string name = parseString();
            expect(':', "':' after a member name");
            members.emplace_back(std::move(name), parseValue(depth + 1));
        } while (consume(','));
        expect('}', "',' or '}' in an object");
        return JsonValue(std::move(members));
    }

    JsonValue parseArray(int depth) {
        ++m_pos; // '['
        JsonValue::Array items;
        if (consume(']'))
            return JsonValue(std::move(items));
        do
            items.push_back(parseValue(depth + 1));
        while (consume(','));
        expect(']', "',' or ']' in an array");
        return JsonValue(std::move(items));
    }

    double parseNumber() {
        // JSON's grammar is stricter than from_chars: no leading '+', no leading zeros, digits
        // on both sides of the point.
        const std::size_t start = m_pos;
        const auto digits = [&] {
            const std::size_t from = m_pos;
            while (m_pos < m_text.size() && m_text[m_pos] >= '0' && m_text[m_pos] <= '9')
                ++m_pos;
            return m_pos - from;
        };
        if (m_text[m_pos] == '-')
            ++m_pos;
        const std::size_t integerStart = m_pos;
        const std::size_t integerDigits = digits();
        if (integerDigits == 0 || (integerDigits > 1 && m_text[integerStart] == '0'))
            fail("malformed number");
        if (m_pos < m_text.size() && m_text[m_pos] == '.') {
            ++m_pos;
            if (digits() == 0)
                fail("malformed number: digits expected after '.'");
        }
        if (m_pos < m_text.size() && (m_text[m_pos] == 'e' || m_text[m_pos] == 'E')) {
            ++m_pos;
            if (m_pos < m_text.size() && (m_text[m_pos] == '+' || m_text[m_pos] == '-'))
                ++m_pos;
            if (digits() == 0)
                fail("malformed number: digits expected in the exponent");
        }
        double value = 0.0;
        const auto [end, error] =
            std::from_chars(m_text.data() + start, m_text.data() + m_pos, value);
        if (error != std::errc() || end != m_text.data() + m_pos)
            fail("number out of range");
        return value;
    }

    unsigned hex4() {
        if (m_pos + 4 > m_text.size())
            fail("truncated \\u escape");
        unsigned code = 0;
        const auto [end, error] =
            std::from_chars(m_text.data() + m_pos, m_text.data() + m_pos + 4, code, 16);
        if (error != std::errc() || end != m_text.data() + m_pos + 4)
            fail("malformed \\u escape");
        m_pos += 4;
        return code;
    }

    static void appendUtf8(std::string& out, std::uint32_t code) {
        if (code < 0x80) {
            out += char(code);
        } else if (code < 0x800) {
            out += char(0xC0 | (code >> 6));
            out += char(0x80 | (code & 0x3F));
        } else if (code < 0x10000) {
            out += char(0xE0 | (code >> 12));
            out += char(0x80 | ((code >> 6) & 0x3F));
            out += char(0x80 | (code & 0x3F));
        } else {
            out += char(0xF0 | (code >> 18));
            out += char(0x80 | ((code >> 12) & 0x3F));
            out += char(0x80 | ((code >> 6) & 0x3F));
            out += char(0x80 | (code & 0x3F));
        }
    }

    // \uXXXX, joining a UTF-16 surrogate pair into one code point.
    void unicodeEscape(std::string& out) {
        std::uint32_t code = hex4();
        if (code >= 0xD800 && code < 0xDC00) {
            if (!literal("\\u"))
                fail("unpaired UTF-16 surrogate in a \\u escape");
            const unsigned low = hex4();
            if (low < 0xDC00 || low > 0xDFFF)
                fail("unpaired UTF-16 surrogate in a \\u escape");
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
        } else if (code >= 0xDC00 && code < 0xE000) {
            fail("unpaired UTF-16 surrogate in a \\u escape");
        }
        appendUtf8(out, code);
    }

    std::string parseString() {
        ++m_pos; // opening quote
        std::string out;
        while (true) {
            if (m_pos >= m_text.size())
                fail("unterminated string");
            const char c = m_text[m_pos++];
            if (c == '"')
                return out;
            if (static_cast<unsigned char>(c) < 0x20)
                fail("control character inside a string (escape it)");
            if (c != '\\') {
                out += c;
                continue;
            }
            if (m_pos >= m_text.size())
                fail("unterminated string");
            const char e = m_text[m_pos++];
            switch (e) {
            case '"':
                out += '"';
                break;
            case '\\':
                out += '\\';
                break;
            case '/':
                out += '/';
                break;
            case 'b':
                out += '\b';
                break;
            case 'f':
                out += '\f';
                break;
            case 'n':
                out += '\n';
                break;
            case 'r':
                out += '\r';
                break;
            case 't':
                out += '\t';
                break;
            case 'u':
                unicodeEscape(out);
                break;
            default:
                fail(std::string("unknown escape '\\") + e + "'");
            }
        }
    }

    std::string_view m_text;
    const std::string& m_subject;
    std::size_t m_pos = 0;
};

} // namespace

JsonValue parseJson(std::string_view text, const std::string& subject) {
    return JsonParser(text, subject).document();
}

} // namespace lw::core
