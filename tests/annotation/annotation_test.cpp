#include "lw/annotation/annotation_json.h"
#include "lw/annotation/annotation_projection.h"
#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "test_support.h"

#include <cmath>
#include <gtest/gtest.h>
#include <limits>

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
        {R"({"version": 3, "annotations": []})",
         "version 3 is not supported: a newer Linework wrote it (this one reads versions 1 to 2)"},
        {R"({"version": 0, "annotations": []})", "version 0 is not supported (expected 1 to 2)"},
        {R"({"version": 1.5, "annotations": []})", "version 1.5 is not supported"},
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

// ---- annotations on slices ----------------------------------------------------------------

namespace {

Annotation onSlice(Annotation annotation, SliceOrientation orientation, double position,
                   double spacing) {
    annotation.slice = SlicePlacement{orientation, position, spacing};
    return annotation;
}

// A ruler on the axial slice at z = 118.5 (5 mm apart), 42.3 mm long along x.
Annotation axialRuler() {
    return onSlice(make(AnnotationKind::Ruler, {{-10, 20, 118.5}, {32.3, 20, 118.5}}),
                   SliceOrientation::Axial, 118.5, 5.0);
}

} // namespace

TEST(SliceAnnotation, PlanesAndPositionsFollowLps) {
    for (SliceOrientation orientation :
         {SliceOrientation::Axial, SliceOrientation::Coronal, SliceOrientation::Sagittal})
        EXPECT_EQ(parseSliceOrientation(sliceOrientationName(orientation)), orientation);
    EXPECT_EQ(sliceOrientationName(SliceOrientation::Coronal), "coronal");
    EXPECT_FALSE(parseSliceOrientation("Axial"));
    const glm::dvec3 point{1.5, -2.5, 7.0}; // left 1.5, anterior 2.5, superior 7
    EXPECT_EQ(slicePositionOf(SliceOrientation::Axial, point), 7.0);
    EXPECT_EQ(slicePositionOf(SliceOrientation::Coronal, point), -2.5);
    EXPECT_EQ(slicePositionOf(SliceOrientation::Sagittal, point), 1.5);
    // Onto a slice: only the coordinate along the plane's normal changes.
    EXPECT_EQ(pointOnSlice({SliceOrientation::Axial, 118.5, 5.0}, point),
              glm::dvec3(1.5, -2.5, 118.5));
    EXPECT_EQ(pointOnSlice({SliceOrientation::Coronal, 40.0, 1.0}, point),
              glm::dvec3(1.5, 40.0, 7.0));
    EXPECT_EQ(pointOnSlice({SliceOrientation::Sagittal, -3.0, 1.0}, point),
              glm::dvec3(-3.0, -2.5, 7.0));
}

TEST(SliceAnnotation, MeasurementNamesThePlaneAndPosition) {
    EXPECT_EQ(measurementText(axialRuler()), "42.3 mm \u00b7 axial 118.5 mm");
    EXPECT_EQ(placementText(axialRuler()), "axial 118.5 mm");
    const Annotation angle =
        onSlice(make(AnnotationKind::Angle, {{-12.3, 5, 0}, {-12.3, 0, 0}, {-12.3, 0, 5}}),
                SliceOrientation::Sagittal, -12.3, 0.7);
    EXPECT_EQ(measurementText(angle), "90.0\u00b0 \u00b7 sagittal -12.3 mm");
    // A label or an arrow has no value; on a slice it still says where it is.
    const Annotation label = onSlice(make(AnnotationKind::Label, {{0, 40.04, 0}}, "x"),
                                     SliceOrientation::Coronal, 40.04, 1);
    EXPECT_EQ(measurementText(label), "coronal 40.0 mm");
    // Placed in 3D: as before slices.
    Annotation inSpace = axialRuler();
    inSpace.slice.reset();
    EXPECT_EQ(measurementText(inSpace), "42.3 mm");
    EXPECT_EQ(placementText(inSpace), "");
}

TEST(SliceAnnotation, ValidationKeepsTheAnchorsOnTheirPlane) {
    EXPECT_NO_THROW(validate(axialRuler(), "a"));
    const auto reasonOf = [](const Annotation& annotation) {
        try {
            validate(annotation, "a");
        } catch (const lw::core::Error& error) {
            return error.reason();
        }
        return std::string("accepted");
    };
    Annotation off = axialRuler();
    off.anchors[1].z = 118.5 + 2.5; // half the spacing: still on the slice
    EXPECT_EQ(reasonOf(off), "accepted");
    off.anchors[1].z = 118.5 + 2.6;
    EXPECT_NE(reasonOf(off).find("a point lies 2.6 mm from its axial slice"), std::string::npos)
        << reasonOf(off);
    Annotation noSpacing = axialRuler();
    noSpacing.slice->spacingMm = 0.0;
    EXPECT_NE(reasonOf(noSpacing).find("spacing is not a positive number"), std::string::npos);
    Annotation nowhere = axialRuler();
    nowhere.slice->positionMm = std::numeric_limits<double>::infinity();
    EXPECT_NE(reasonOf(nowhere).find("position is not a finite number"), std::string::npos);
}

// The slab a slice shows is [position - spacing/2, position + spacing/2).
TEST(SliceAnnotation, ShowsOnSlicesWithinHalfASpacing) {
    const Annotation ruler = axialRuler(); // z = 118.5
    EXPECT_TRUE(showsOnSlice(ruler, SliceOrientation::Axial, 118.5, 5.0));
    EXPECT_FALSE(showsOnSlice(ruler, SliceOrientation::Axial, 113.5, 5.0)); // the slice below
    EXPECT_FALSE(showsOnSlice(ruler, SliceOrientation::Axial, 123.5, 5.0)); // and above
    // At the boundary: 118.5 is the upper edge of the slice at 116 (left out) and the lower
    // edge of the slice at 121 (kept).
    EXPECT_FALSE(showsOnSlice(ruler, SliceOrientation::Axial, 116.0, 5.0));
    EXPECT_TRUE(showsOnSlice(ruler, SliceOrientation::Axial, std::nextafter(116.0, 200.0), 5.0));
    EXPECT_TRUE(showsOnSlice(ruler, SliceOrientation::Axial, 121.0, 5.0));
    EXPECT_FALSE(showsOnSlice(ruler, SliceOrientation::Axial, std::nextafter(121.0, 200.0), 5.0));
    // Thinner slices of another view: within half of their spacing.
    EXPECT_TRUE(showsOnSlice(ruler, SliceOrientation::Axial, 118.75, 0.625));
    EXPECT_FALSE(showsOnSlice(ruler, SliceOrientation::Axial, 119.0, 0.625));
    // Another orientation never shows it, even where its points would fit the slab (y = 20).
    EXPECT_FALSE(showsOnSlice(ruler, SliceOrientation::Coronal, 20.0, 5.0));
}

// A point exactly between two slices of a regular stack shows on one of them, never on both.
TEST(SliceAnnotation, EachPointShowsOnExactlyOneSliceOfAStack) {
    const double first = 100.0;
    const double spacing = 1.25; // binary-exact, so the halfway points are exactly halfway
    for (const double z : {100.0, 101.875, 102.5, 103.0, 104.375, 111.2}) {
        const Annotation label = onSlice(make(AnnotationKind::Label, {{0, 0, z}}, "x"),
                                         SliceOrientation::Axial, z, spacing);
        int shown = 0;
        for (int k = 0; k < 20; ++k)
            shown += showsOnSlice(label, SliceOrientation::Axial, first + k * spacing, spacing);
        EXPECT_EQ(shown, 1) << z;
    }
}

TEST(SliceAnnotation, ThreeDAnnotationsShowOnSlicesHoldingAllTheirPoints) {
    const Annotation flat = make(AnnotationKind::Ruler, {{0, 0, 50.2}, {30, 40, 49.9}});
    EXPECT_TRUE(showsOnSlice(flat, SliceOrientation::Axial, 50.0, 1.0));
    EXPECT_FALSE(showsOnSlice(flat, SliceOrientation::Axial, 51.0, 1.0));
    EXPECT_FALSE(showsOnSlice(flat, SliceOrientation::Axial, 50.0, 0.3)); // 50.2 is outside
    // A ruler across the head is drawn on no slice (it would look shorter than it measures)...
    const Annotation across = make(AnnotationKind::Ruler, {{0, 0, 10}, {0, 0, 150}});
    for (double z = 0.0; z <= 160.0; z += 2.5)
        EXPECT_FALSE(showsOnSlice(across, SliceOrientation::Axial, z, 2.5)) << z;
    // ...but on the sagittal and coronal slices through x = 0 and y = 0 it lies in the plane.
    EXPECT_TRUE(showsOnSlice(across, SliceOrientation::Sagittal, 0.0, 1.0));
    EXPECT_TRUE(showsOnSlice(across, SliceOrientation::Coronal, 0.0, 1.0));
}

TEST(SliceAnnotation, JsonVersion2KeepsThePlacement) {
    const std::vector<Annotation> annotations = {
        axialRuler(),
        make(AnnotationKind::Label, {{-12.5, 30.25, 101}}, "in 3D"),
        onSlice(make(AnnotationKind::Arrow, {{-12.3, 5, 0}, {-12.3, 0, 7}}, "tip"),
                SliceOrientation::Sagittal, -12.3, 0.7),
    };
    const std::string json = annotationsToJson(annotations);
    EXPECT_NE(json.find("\"version\": 2"), std::string::npos) << json;
    EXPECT_NE(json.find("\"plane\": \"sagittal\""), std::string::npos) << json;
    const std::vector<Annotation> read = parseAnnotationsJson(json, "x");
    ASSERT_EQ(read.size(), annotations.size());
    for (std::size_t i = 0; i < read.size(); ++i) {
        EXPECT_EQ(read[i].anchors, annotations[i].anchors);
        ASSERT_EQ(read[i].slice.has_value(), annotations[i].slice.has_value()) << i;
        if (!read[i].slice)
            continue;
        EXPECT_EQ(read[i].slice->orientation, annotations[i].slice->orientation);
        EXPECT_EQ(read[i].slice->positionMm, annotations[i].slice->positionMm);
        EXPECT_EQ(read[i].slice->spacingMm, annotations[i].slice->spacingMm);
    }
    EXPECT_EQ(measurementText(read[0]), "42.3 mm \u00b7 axial 118.5 mm");
}

TEST(SliceAnnotation, Version1FilesAreReadAs3D) {
    const std::vector<Annotation> read = parseAnnotationsJson(
        R"({"version": 1, "annotations": [{"type": "ruler", "points": [[0,0,0],[0,3,4]]}]})", "x");
    ASSERT_EQ(read.size(), 1u);
    EXPECT_FALSE(read[0].slice);
    EXPECT_EQ(measurementText(read[0]), "5.0 mm");
}

TEST(SliceAnnotation, BadSlicesAreRefusedNamingThePlace) {
    const auto file = [](const std::string& version, const std::string& slice) {
        return R"({"version": )" + version +
               R"(, "annotations": [{"type": "label", "points": [[0,0,118.5]], "text": "a", )" +
               R"("slice": )" + slice + "}]}";
    };
    const std::string good = R"({"plane": "axial", "position": 118.5, "spacing": 5})";
    EXPECT_EQ(parseAnnotationsJson(file("2", good), "x").size(), 1u);
    struct Case {
        std::string json;
        const char* reason;
    };
    const Case cases[] = {
        {file("1", good), "annotations[0]: \"slice\" needs a file of version 2 or later"},
        {file("2", R"({"plane": "oblique", "position": 1, "spacing": 5})"),
         "annotations[0].slice.plane: unknown plane \"oblique\""},
        {file("2", R"({"plane": "axial", "position": 118.5})"),
         "annotations[0].slice: missing \"spacing\""},
        {file("2", R"({"plane": "axial", "position": 118.5, "spacing": 5, "thickness": 1})"),
         "annotations[0].slice: unknown member \"thickness\""},
        {file("2", R"({"plane": "axial", "position": "118.5", "spacing": 5})"),
         "annotations[0].slice.position: expected number, found string"},
        {file("2", R"({"plane": "axial", "position": 100, "spacing": 5})"),
         "annotations[0]: a point lies 18.5 mm from its axial slice"},
        {file("2", R"({"plane": "axial", "position": 118.5, "spacing": -1})"),
         "annotations[0]: the slice's spacing is not a positive number"},
        {file("2", R"("axial")"), "annotations[0].slice: expected object, found string"},
    };
    for (const Case& c : cases) {
        const std::string reason = parseError(c.json);
        EXPECT_NE(reason.find(c.reason), std::string::npos) << c.json << "\n -> " << reason;
    }
}

TEST(SliceAnnotation, ProjectionThroughAPixelMapping) {
    // An axial slice panel at 2 px/mm whose pixel (0, 0) is patient (-100, -100).
    const PatientToPixel toPixel = [](const glm::dvec3& p) {
        return glm::dvec2((p.x + 100.0) * 2.0, (p.y + 100.0) * 2.0);
    };
    const ProjectedAnnotation projected = projectAnnotation(axialRuler(), toPixel);
    ASSERT_EQ(projected.points.size(), 2u);
    EXPECT_EQ(projected.points[0], glm::dvec2(180.0, 240.0));
    EXPECT_NEAR(projected.points[1].x, 264.6, 1e-9);
    EXPECT_TRUE(projected.inFront);
    EXPECT_EQ(projected.measurement, "42.3 mm \u00b7 axial 118.5 mm");
}
