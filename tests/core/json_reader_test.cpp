#include "lw/core/error.h"
#include "lw/core/json_reader.h"
#include "lw/core/json_writer.h"

#include <gtest/gtest.h>

using namespace lw::core;

namespace {

std::string errorOf(const std::string& text) {
    try {
        parseJson(text, "file.json");
    } catch (const Error& error) {
        EXPECT_EQ(error.subject(), "file.json");
        return error.reason();
    }
    ADD_FAILURE() << "accepted: " << text;
    return {};
}

} // namespace

TEST(JsonReader, ReadsWhatJsonWriterWrites) {
    JsonWriter writer;
    writer.beginObject()
        .field("name", "Läsion \"a\"\n\\")
        .field("n", -12.5e-3)
        .field("count", 7)
        .field("yes", true)
        .key("none")
        .null()
        .key("list")
        .beginArray()
        .value(1)
        .beginArray()
        .endArray()
        .beginObject()
        .endObject()
        .endArray()
        .endObject();
    const JsonValue value = parseJson(writer.str(), "memory");
    ASSERT_TRUE(value.isObject());
    EXPECT_EQ(value.find("name")->string(), "Läsion \"a\"\n\\");
    EXPECT_DOUBLE_EQ(value.find("n")->number(), -12.5e-3);
    EXPECT_DOUBLE_EQ(value.find("count")->number(), 7);
    EXPECT_TRUE(value.find("yes")->boolean());
    EXPECT_TRUE(value.find("none")->isNull());
    ASSERT_EQ(value.find("list")->array().size(), 3u);
    EXPECT_TRUE(value.find("list")->array()[1].isArray());
    EXPECT_EQ(value.find("missing"), nullptr);
    EXPECT_EQ(value.object().front().first, "name"); // document order is kept
}

TEST(JsonReader, DecodesUnicodeEscapesAndSurrogatePairs) {
    EXPECT_EQ(parseJson(R"("\u00e4\u20ac\ud83d\ude00\/")", "s").string(),
              "\xc3\xa4\xe2\x82\xac\xf0\x9f\x98\x80/");
}

// Each malformed document is refused with the line and column of the mistake (nlohmann-json's
// wording of the reason) and, below the top level, the path to the value being read.
TEST(JsonReader, RefusesWhatIsNotStrictJsonNamingLineAndColumn) {
    struct Case {
        const char* text;
        const char* reason;
    };
    const Case cases[] = {
        {"{\"a\": 1,}", "line 1, column 9: syntax error while parsing object key"},
        {"[1, 2", "line 1, column 6: syntax error while parsing array - unexpected end of input"},
        {"{\n  \"a\" 1}", "line 2, column 7, in a: syntax error while parsing object separator"},
        {"// comment\n{}", "line 1, column 1: syntax error while parsing value - invalid literal"},
        {"{'a': 1}", "line 1, column 2: syntax error while parsing object key"},
        {"01", "line 1, column 2: syntax error while parsing value - unexpected number literal"},
        {"1.", "expected digit after '.'"},
        {"\"tab\there\"", "control character U+0009 (HT) must be escaped"},
        {"\"\\x\"", "forbidden character after backslash"},
        {"\"\\ud800\"", "surrogate U+D800..U+DBFF must be followed by U+DC00..U+DFFF"},
        {"{} {}", "expected end of input"},
        {"", "line 1, column 1: syntax error while parsing value - unexpected end of input"},
        {"\"open", "missing closing quote"},
        {"\"\xff\"", "ill-formed UTF-8 byte"},
        {"1e999", "line 1, column 5: number overflow parsing '1e999'"},
        {"{\"list\": [\n  {\"x\": [1, 2]},\n  {\"y\": tru}]}",
         "line 3, column 12, in list[1].y: syntax error while parsing value - invalid literal"},
    };
    for (const Case& c : cases)
        EXPECT_NE(errorOf(c.text).find(c.reason), std::string::npos)
            << c.text << " -> " << errorOf(c.text);
}

TEST(JsonReader, RefusesNestingDeeperThanTheLimit) {
    EXPECT_NO_THROW(parseJson(std::string(200, '[') + std::string(200, ']'), "deep"));
    EXPECT_NE(errorOf(std::string(300, '[') + std::string(300, ']')).find("nested deeper"),
              std::string::npos);
}
