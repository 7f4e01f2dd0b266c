#include "lw/annotation/annotation_json.h"
#include "lw/annotation/annotation_projection.h"
#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace lw::annotation;

namespace {

Annotation make(AnnotationKind kind, std::vector<glm::dvec3> anchors, std::string text = {}) {
    return {kind, std::move(anchors), std::move(text)};
}

// The reason of the core::Error that parsing `json` as "notes.json" throws.
std::string parseError(const std::string& json) {
    try {
        parseAnnotationsJson(json, "notes.json");
    } catch (const lw::core::Error& error) {
        EXPECT_EQ(error.subject(), "notes.json");
        return error.reason();
    }
    ADD_FAILURE() << "accepted: " << json;
    return {};
}

} // namespace

TEST(Annotation, MeasurementsFollowFromTheAnchors) {
    const Annotation ruler = make(AnnotationKind::Ruler, {{1, 2, 3}, {4, 6, 15}});
    EXPECT_DOUBLE_EQ(rulerLengthMm(ruler), 13.0);
    EXPECT_EQ(measurementText(ruler), "13.0 mm");
    EXPECT_EQ(measurementText(make(AnnotationKind::Ruler, {{0, 0, 0}, {0, 0, 0.04}})), "0.0 mm");
    const Annotation right = make(AnnotationKind::Angle, {{5, 0, 0}, {0, 0, 0}, {0, 0, -2}});
    EXPECT_NEAR(angleDegrees(right), 90.0, 1e-12);
    EXPECT_EQ(measurementText(right), "90.0\u00b0");
    EXPECT_NEAR(angleDegrees(make(AnnotationKind::Angle, {{1, 0, 0}, {0, 0, 0}, {-1, 1e-9, 0}})),
                180.0, 1e-6);
    EXPECT_NEAR(angleDegrees(make(AnnotationKind::Angle, {{1, 0, 0}, {0, 0, 0}, {1, 1, 0}})), 45.0,
                1e-12);
    EXPECT_EQ(angleDegrees(make(AnnotationKind::Angle, {{0, 0, 0}, {0, 0, 0}, {1, 1, 0}})), 0.0);
    EXPECT_EQ(measurementText(make(AnnotationKind::Label, {{0, 0, 0}}, "x")), "");
}

TEST(Annotation, JsonRoundTripKeepsKindsPointsAndText) {
    const std::vector<Annotation> annotations = {
        make(AnnotationKind::Label, {{-12.5, 30.25, 101}}, "Läsion \"A\""),
        make(AnnotationKind::Arrow, {{0, 0, 0}, {1, 2, 3}}, "tip"),
        make(AnnotationKind::Ruler, {{-20, 0.125, 7}, {20, -0.5, 7}}),
        make(AnnotationKind::Angle, {{1, 0, 0}, {0, 0, 0}, {0, 1, 0}}),
    };
    const std::vector<Annotation> read = parseAnnotationsJson(annotationsToJson(annotations), "x");
    ASSERT_EQ(read.size(), annotations.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
        EXPECT_EQ(read[i].kind, annotations[i].kind);
        EXPECT_EQ(read[i].text, annotations[i].text);
        EXPECT_EQ(read[i].anchors, annotations[i].anchors);
    }
}

// Every refused file names the file and the place in it, so the user can find the mistake.
TEST(Annotation, BadFilesAreRefusedNamingTheFileAndThePlace) {
    struct Case {
        const char* json;
        const char* reason;
    };
    const Case cases[] = {
        {R"({"annotations": [ {"type": "ruler", "points": [[0,0,0]]} ]})",
         "annotations[0]: a ruler needs 2 points, not 1"},
        {R"({"annotations": [ {"type": "label", "points": [[0,0,0]]} ]})", "a label needs a text"},
        {R"({"annotations": [ {"type": "circle", "points": []} ]})",
         "annotations[0].type: unknown type \"circle\""},
        {R"({"annotations": [ {"type": "arrow", "points": [[0,0,0],[1,1]]} ]})",
         "annotations[0].points[1]: a point is [x, y, z]"},
        {R"({"annotations": [ {"type": "arrow", "points": [[0,0,0],[1,"a",1]]} ]})",
         "annotations[0].points[1][1]: expected number, found string"},
        {R"({"annotations": [ {"type": "label", "points": [[0,0,0]], "txt": "a"} ]})",
         "unknown member \"txt\""},
        {R"({"annotations": [ {"points": [[0,0,0]]} ]})", "missing \"type\""},
        {R"({"version": 2, "annotations": []})", "version 2 is not supported"},
        {R"([])", "expected an object with \"annotations\", found array"},
        {R"({})", "missing \"annotations\""},
        {"{\"annotations\": [\n  {\"type\": \"ruler\",}\n]}", "line 2, column 20"},
    };
    for (const Case& c : cases) {
        const std::string reason = parseError(c.json);
        EXPECT_NE(reason.find(c.reason), std::string::npos) << c.json << "\n -> " << reason;
    }
}

TEST(Annotation, ReadingAFileNamesItOnError) {
    lw::test::TempDir dir;
    try {
        readAnnotationsFile(dir / "absent.json");
        FAIL() << "a missing file was read";
    } catch (const lw::core::Error& error) {
        EXPECT_NE(std::string(error.what()).find("absent.json"), std::string::npos);
    }
    const std::string text = R"({"annotations": [{"type": "ruler", "points": [[0,0,0],[0,3,4]]}]})";
    lw::core::writeFileAtomically(dir / "a.json", text.data(), text.size());
    const auto read = readAnnotationsFile(dir / "a.json");
    ASSERT_EQ(read.size(), 1u);
    EXPECT_EQ(measurementText(read[0]), "5.0 mm");
}

// What `export --annotations FILE.json` tells a user about a bad file: the file, then the line
// and column of a syntax error or the key whose value has the wrong type.
TEST(Annotation, FileErrorsNameTheFileTheLineAndTheKey) {
    lw::test::TempDir dir;
    const auto errorOf = [&](const std::string& name, const std::string& text) {
        lw::core::writeFileAtomically(dir / name, text.data(), text.size());
        try {
            readAnnotationsFile(dir / name);
        } catch (const lw::core::Error& error) {
            EXPECT_EQ(error.subject(), (dir / name).string());
            return error.reason();
        }
        ADD_FAILURE() << name << " was read";
        return std::string();
    };
    const std::string syntax =
        errorOf("syntax.json", "{\"annotations\": [\n  {\"type\": \"ruler\"\n   \"points\": []}]}");
    EXPECT_NE(syntax.find("line 3, column 11, in annotations[0]: syntax error"), std::string::npos)
        << syntax;
    const std::string type = errorOf("type.json", R"({"annotations": [{"type": "label",
        "points": [[0,0,0]], "text": 12}]})");
    EXPECT_NE(type.find("annotations[0].text: expected string, found number"), std::string::npos)
        << type;

    // One byte over the limit is refused before it is read (the reason says so, not a parse error).
    std::string big(kMaxAnnotationFileBytes + 1, ' ');
    big.replace(0, 19, R"({"annotations": []})");
    const std::string reason = errorOf("big.json", big);
    EXPECT_NE(reason.find("more than the limit of 16777216 bytes"), std::string::npos) << reason;
    big.resize(kMaxAnnotationFileBytes); // at the limit: read, trailing spaces and all
    lw::core::writeFileAtomically(dir / "limit.json", big.data(), big.size());
    EXPECT_TRUE(readAnnotationsFile(dir / "limit.json").empty());
}

TEST(Annotation, ProjectionPutsAnchorsWhereTheCameraSeesThem) {
    lw::render::CameraSetup setup;
    setup.bounds = {{-50, -50, -50}, {50, 50, 50}};
    const lw::render::Camera camera(setup, 400, 200);
    const Annotation ruler = make(AnnotationKind::Ruler, {{0, 0, 0}, {10, 0, 5}});
    const ProjectedAnnotation projected = projectAnnotation(ruler, camera);
    ASSERT_EQ(projected.points.size(), 2u);
    EXPECT_TRUE(projected.inFront);
    EXPECT_NEAR(projected.points[0].x, 200.0, 1e-9); // the target is the viewport's centre
    EXPECT_NEAR(projected.points[0].y, 100.0, 1e-9);
    EXPECT_GT(projected.points[1].x, 200.0); // +x (patient's left) is screen right from the front
    EXPECT_LT(projected.points[1].y, 100.0); // +z (superior) is screen up
    EXPECT_EQ(projected.measurement, measurementText(ruler));
    // An anchor behind the eye (perspective) cannot be drawn.
    const glm::dvec3 behind = camera.eye() - 10.0 * camera.forward();
    EXPECT_FALSE(projectAnnotation(make(AnnotationKind::Label, {behind}, "x"), camera).inFront);
}
