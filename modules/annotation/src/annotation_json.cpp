#include "lw/annotation/annotation_json.h"

#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "lw/core/json_reader.h"
#include "lw/core/json_writer.h"

#include <cstdio>

namespace lw::annotation {
namespace {

using core::JsonValue;

// Errors name the file and the place in it: "FILE: annotations[2].points: ...".
struct Place {
    const std::string& subject;
    std::string path;

    [[noreturn]] void fail(const std::string& reason) const {
        throw core::Error(subject, path.empty() ? reason : path + ": " + reason);
    }
    Place member(const std::string& name) const { return {subject, path + "." + name}; }
    Place item(std::size_t index) const {
        return {subject, path + "[" + std::to_string(index) + "]"};
    }
};

const JsonValue& require(const JsonValue& value, JsonValue::Type type, const Place& place) {
    if (value.type() != type)
        place.fail(std::string("expected ") + core::jsonTypeName(type) + ", found " +
                   core::jsonTypeName(value.type()));
    return value;
}

glm::dvec3 readPoint(const JsonValue& value, const Place& place) {
    const auto& items = require(value, JsonValue::Type::Array, place).array();
    if (items.size() != 3)
        place.fail("a point is [x, y, z] (LPS, mm), found " + std::to_string(items.size()) +
                   " numbers");
    glm::dvec3 point{0.0};
    for (int i = 0; i < 3; ++i)
        point[i] = require(items[std::size_t(i)], JsonValue::Type::Number, place.item(i)).number();
    return point;
}

Annotation readAnnotation(const JsonValue& value, const Place& place) {
    Annotation annotation;
    const JsonValue* type = nullptr;
    const JsonValue* points = nullptr;
    for (const auto& [name, member] : require(value, JsonValue::Type::Object, place).object()) {
        if (name == "type")
            type = &require(member, JsonValue::Type::String, place.member(name));
        else if (name == "points")
            points = &require(member, JsonValue::Type::Array, place.member(name));
        else if (name == "text")
            annotation.text = require(member, JsonValue::Type::String, place.member(name)).string();
        else
            place.fail("unknown member \"" + name + "\" (expected type, points, text)");
    }
    if (!type)
        place.fail("missing \"type\" (label, arrow, ruler or angle)");
    const std::optional<AnnotationKind> kind = parseKind(type->string());
    if (!kind)
        place.member("type").fail("unknown type \"" + type->string() +
                                  "\" (expected label, arrow, ruler or angle)");
    annotation.kind = *kind;
    if (!points)
        place.fail("missing \"points\"");
    for (std::size_t i = 0; i < points->array().size(); ++i)
        annotation.anchors.push_back(readPoint(points->array()[i], place.member("points").item(i)));
    try {
        validate(annotation, place.subject);
    } catch (const core::Error& error) {
        place.fail(error.reason()); // the same reason, with the place in the file
    }
    return annotation;
}

} // namespace

std::vector<Annotation> parseAnnotationsJson(std::string_view text, const std::string& subject) {
    const JsonValue document = core::parseJson(text, subject);
    const Place root{subject, ""};
    if (!document.isObject())
        root.fail("expected an object with \"annotations\", found " +
                  std::string(core::jsonTypeName(document.type())));
    const JsonValue* list = nullptr;
    for (const auto& [name, member] : document.object()) {
        if (name == "annotations") {
            list = &require(member, JsonValue::Type::Array, {subject, name});
        } else if (name == "version") {
            const double version =
                require(member, JsonValue::Type::Number, {subject, name}).number();
            if (version != kAnnotationFileVersion) {
                char text[96];
                std::snprintf(text, sizeof text, "version %g is not supported (expected %d)",
                              version, kAnnotationFileVersion);
                root.fail(text);
            }
        } else {
            root.fail("unknown member \"" + name + "\" (expected version, annotations)");
        }
    }
    if (!list)
        root.fail("missing \"annotations\"");
    std::vector<Annotation> annotations;
    for (std::size_t i = 0; i < list->array().size(); ++i)
        annotations.push_back(
            readAnnotation(list->array()[i], Place{subject, "annotations"}.item(i)));
    return annotations;
}

std::vector<Annotation> readAnnotationsFile(const std::filesystem::path& path) {
    return parseAnnotationsJson(core::readFileText(path, kMaxAnnotationFileBytes), path.string());
}

std::string annotationsToJson(const std::vector<Annotation>& annotations) {
    core::JsonWriter json;
    json.beginObject().field("version", kAnnotationFileVersion).key("annotations").beginArray();
    for (const Annotation& annotation : annotations) {
        json.beginObject().field("type", kindName(annotation.kind)).key("points").beginArray();
        for (const glm::dvec3& anchor : annotation.anchors)
            json.beginArray().value(anchor.x).value(anchor.y).value(anchor.z).endArray();
        json.endArray();
        if (!annotation.text.empty())
            json.field("text", annotation.text);
        json.endObject();
    }
    json.endArray().endObject();
    return json.str() + "\n";
}

} // namespace lw::annotation
