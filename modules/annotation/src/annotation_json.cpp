#include "lw/annotation/annotation_json.h"

#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "lw/core/json_reader.h"
#include "lw/core/json_writer.h"

#include <cmath>
#include <cstdio>
#include <utility>

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

SlicePlacement readSlicePlacement(const JsonValue& value, const Place& place) {
    SlicePlacement slice;
    const JsonValue* plane = nullptr;
    const JsonValue* position = nullptr;
    const JsonValue* spacing = nullptr;
    for (const auto& [name, member] : require(value, JsonValue::Type::Object, place).object()) {
        if (name == "plane")
            plane = &require(member, JsonValue::Type::String, place.member(name));
        else if (name == "position")
            position = &require(member, JsonValue::Type::Number, place.member(name));
        else if (name == "spacing")
            spacing = &require(member, JsonValue::Type::Number, place.member(name));
        else
            place.fail("unknown member \"" + name + "\" (expected plane, position, spacing)");
    }
    const std::pair<const char*, const JsonValue*> required[] = {
        {"plane", plane}, {"position", position}, {"spacing", spacing}};
    for (const auto& [name, found] : required)
        if (!found)
            place.fail(std::string("missing \"") + name +
                       "\" (a slice has a plane, a position and a spacing)");
    const std::optional<SliceOrientation> orientation = parseSliceOrientation(plane->string());
    if (!orientation)
        place.member("plane").fail("unknown plane \"" + plane->string() +
                                   "\" (expected axial, coronal or sagittal)");
    slice.orientation = *orientation;
    slice.positionMm = position->number();
    slice.spacingMm = spacing->number();
    return slice;
}

Annotation readAnnotation(const JsonValue& value, const Place& place, int version) {
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
        else if (name == "slice" && version >= 2)
            annotation.slice = readSlicePlacement(member, place.member(name));
        else if (name == "slice")
            place.fail("\"slice\" needs a file of version 2 or later, this one is version " +
                       std::to_string(version));
        else
            place.fail("unknown member \"" + name + "\" (expected type, points, text, slice)");
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

// The file's version, one this Linework reads: older files stay readable, a newer Linework's
// file is refused rather than read with its new members misunderstood.
int readVersion(const JsonValue& value, const Place& place) {
    const double version = require(value, JsonValue::Type::Number, place).number();
    char text[192];
    if (version > kAnnotationFileVersion) {
        std::snprintf(text, sizeof text,
                      "version %g is not supported: a newer Linework wrote it (this one reads "
                      "versions %d to %d)",
                      version, kOldestAnnotationFileVersion, kAnnotationFileVersion);
        place.fail(text);
    }
    if (version < kOldestAnnotationFileVersion || version != std::floor(version)) {
        std::snprintf(text, sizeof text, "version %g is not supported (expected %d to %d)", version,
                      kOldestAnnotationFileVersion, kAnnotationFileVersion);
        place.fail(text);
    }
    return int(version);
}

} // namespace

std::vector<Annotation> parseAnnotationsJson(std::string_view text, const std::string& subject) {
    const JsonValue document = core::parseJson(text, subject);
    const Place root{subject, ""};
    if (!document.isObject())
        root.fail("expected an object with \"annotations\", found " +
                  std::string(core::jsonTypeName(document.type())));
    const JsonValue* list = nullptr;
    int version = kAnnotationFileVersion; // a file without "version" is read as the newest
    for (const auto& [name, member] : document.object()) {
        if (name == "annotations")
            list = &require(member, JsonValue::Type::Array, {subject, name});
        else if (name == "version")
            version = readVersion(member, root);
        else
            root.fail("unknown member \"" + name + "\" (expected version, annotations)");
    }
    if (!list)
        root.fail("missing \"annotations\"");
    std::vector<Annotation> annotations;
    for (std::size_t i = 0; i < list->array().size(); ++i)
        annotations.push_back(
            readAnnotation(list->array()[i], Place{subject, "annotations"}.item(i), version));
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
        if (annotation.slice)
            json.key("slice")
                .beginObject()
                .field("plane", sliceOrientationName(annotation.slice->orientation))
                .field("position", annotation.slice->positionMm)
                .field("spacing", annotation.slice->spacingMm)
                .endObject();
        json.endObject();
    }
    json.endArray().endObject();
    return json.str() + "\n";
}

} // namespace lw::annotation
