// The exported picture: re-rendered panels with the annotations burned in at 2x and 4x the
// window's size (lines and text scale with it), PNG and SVG written atomically, and refused
// exports that leave nothing behind.
#include "link_trap.h"
#include "lw/core/error.h"
#include "lw/core/file_util.h"
#include "lw/core/png_io.h"
#include "lw/render/visible_polylines.h"
#include "lw/report/annotation_overlay.h"
#include "lw/report/export_files.h"
#include "lw/report/svg_export.h"
#include "report_test_support.h"
#include "test_support.h"

#include <filesystem>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

using namespace lw;

namespace {

constexpr int kWindowPanel = 256; // the panel size "on screen" the exports multiply

bool isAnnotationColour(QRgb pixel) {
    const QColor colour = report::OverlayStyle().colour;
    return std::abs(qRed(pixel) - colour.red()) < 40 &&
           std::abs(qGreen(pixel) - colour.green()) < 40 &&
           std::abs(qBlue(pixel) - colour.blue()) < 40;
}

struct PanelCounts {
    int surface = 0;    // grey shaded pixels (iso) or black line pixels (silhouette)
    int annotation = 0; // in the annotation colour
};

PanelCounts countPanel(const QImage& image, int x0, int width, bool iso) {
    PanelCounts counts;
    for (int y = 0; y < image.height(); ++y)
        for (int x = x0; x < x0 + width; ++x) {
            const QRgb p = image.pixel(x, y);
            if (isAnnotationColour(p))
                ++counts.annotation;
            else if (iso ? (qGray(p) < 240 && qRed(p) == qBlue(p)) : qGray(p) < 60)
                ++counts.surface;
        }
    return counts;
}

// Pixels in the annotation colour inside the box where the label's text goes (right of and above
// its anchor, up to 8 reference pixels per character by 1.5 lines).
int labelTextPixels(const QImage& picture, const report::RenderedPanels& panels) {
    const annotation::Annotation label = test::sphereAnnotations()[1];
    const glm::dvec2 at = panels.camera.project(label.anchors[0]).pixel;
    const double scale = report::overlayScale(panels.camera.height());
    int count = 0;
    for (int y = int(at.y - 30 * scale); y < int(at.y); ++y)
        for (int x = int(at.x + 7 * scale); x < int(at.x + 90 * scale); ++x)
            if (picture.valid(x, y) && isAnnotationColour(picture.pixel(x, y)))
                ++count;
    return count;
}

} // namespace

TEST(ReportImage, PanelsAndTextScaleWithTheExportSize) {
    test::ensureGuiApplication();
    int textPixels[2] = {0, 0};
    for (const int factor : {2, 4}) {
        const int size = factor * kWindowPanel;
        const report::RenderedPanels panels = test::renderSphereReview(size);
        const QImage picture = report::composeExportImage(panels, test::sphereAnnotations(),
                                                          report::PanelLayout::SideBySide);
        ASSERT_EQ(picture.width(), 2 * size);
        ASSERT_EQ(picture.height(), size);
        const PanelCounts iso = countPanel(picture, 0, size, true);
        const PanelCounts lines = countPanel(picture, size, size, false);
        SCOPED_TRACE(factor);
        EXPECT_GT(iso.surface, size * size / 10); // the shaded sphere
        EXPECT_GT(lines.surface, size);           // its outline
        EXPECT_GT(iso.annotation, 0);
        EXPECT_GT(lines.annotation, 0); // burned into both panels
        textPixels[factor / 4] = labelTextPixels(picture, panels);
        EXPECT_GT(textPixels[factor / 4], 20 * factor * factor) << "the label's text is missing";
        // Kept for a look (build/test/tests/report/output).
        std::filesystem::create_directories(LINEWORK_TEST_OUTPUT_DIR);
        picture.save(QString(LINEWORK_TEST_OUTPUT_DIR "/review_%1x.png").arg(factor));
    }
    // Text scales with the picture: twice the size, about four times the pixels.
    const double ratio = double(textPixels[1]) / double(textPixels[0]);
    EXPECT_GT(ratio, 2.5);
    EXPECT_LT(ratio, 6.0);
}

TEST(ReportImage, SinglePanelLayoutsAndTheWrittenPng) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const report::RenderedPanels panels = test::renderSphereReview(kWindowPanel);
    for (const auto layout :
         {report::PanelLayout::IsoPanel, report::PanelLayout::SilhouettePanel}) {
        const QImage picture =
            report::composeExportImage(panels, test::sphereAnnotations(), layout);
        EXPECT_EQ(picture.width(), kWindowPanel);
        const auto path = dir / (layout == report::PanelLayout::IsoPanel ? "iso.png" : "lines.png");
        report::writeExportFile(path, report::encodePngBytes(picture, path),
                                core::Overwrite::Refuse);
        const core::ImageRgba8 read = core::readPng(path);
        EXPECT_EQ(read.width(), kWindowPanel);
        EXPECT_EQ(read, report::toCoreImage(picture.convertToFormat(QImage::Format_RGB32)));
    }
}

TEST(ReportImage, SvgHoldsTheRasterAndVectorAnnotations) {
    test::ensureGuiApplication();
    const QString svg = QString::fromUtf8(report::renderSvg(test::renderSphereReview(kWindowPanel),
                                                            test::sphereAnnotations(),
                                                            report::PanelLayout::SideBySide));
    EXPECT_TRUE(svg.startsWith("<?xml"));
    EXPECT_TRUE(svg.contains("data:image/png;base64,iVBOR")); // the panels, as PNG
    EXPECT_EQ(svg.count("<g transform"), 2);                  // annotations over each panel
    EXPECT_EQ(svg.count(">40.0 mm</text>"), 2);
    EXPECT_EQ(svg.count(">Finding A</text>"), 2);
    EXPECT_EQ(svg.count(">90.0\u00b0</text>"), 2);
    EXPECT_TRUE(svg.trimmed().endsWith("</svg>"));
}

// A ruler placed on a slice shows in the 3D panels too (its points are patient points), its
// caption naming the plane.
TEST(ReportImage, SliceMeasurementsNameTheirPlaneInTheExports) {
    test::ensureGuiApplication();
    const annotation::Annotation ruler = test::sphereSliceRuler();
    const std::string caption = annotation::measurementText(ruler);
    EXPECT_EQ(caption, "40.0 mm \u00b7 " + annotation::placementText(ruler));
    const QString svg = QString::fromUtf8(report::renderSvg(
        test::renderSphereReview(kWindowPanel), {ruler}, report::PanelLayout::SideBySide));
    EXPECT_EQ(svg.count(">" + QString::fromStdString(caption) + "</text>"), 2) << caption;
}

// A slice panel shows the annotations of its slice and of slices within half a spacing, and
// none of another slice; the caption is drawn beside the ruler.
TEST(ReportImage, SliceAnnotationsBurnIntoTheirSliceOnly) {
    test::ensureGuiApplication();
    const annotation::Annotation ruler = test::sphereSliceRuler();
    const glm::dvec3 centre = test::sphereReview().sphere.centre;
    report::SlicePanelFrame view;
    view.orientation = annotation::SliceOrientation::Axial;
    view.spacingMm = 2.0;
    view.toPixel = [&](const glm::dvec3& p) { // 4 px/mm around the sphere's centre
        // (on a row's centre, so the one-pixel line is not split between two rows)
        return glm::dvec2(128.0 + 4.0 * (p.x - centre.x), 128.5 + 4.0 * (p.y - centre.y));
    };
    const auto annotationPixels = [&](double position) {
        QImage panel(256, 256, QImage::Format_ARGB32_Premultiplied);
        panel.fill(Qt::black);
        view.positionMm = position;
        report::burnInSliceAnnotations(panel, {ruler}, view);
        int count = 0;
        for (int y = 0; y < panel.height(); ++y)
            for (int x = 0; x < panel.width(); ++x)
                count += isAnnotationColour(panel.pixel(x, y)) ? 1 : 0;
        return count;
    };
    const int onItsSlice = annotationPixels(centre.z);
    EXPECT_GT(onItsSlice, 50); // the 160 px line (partly under its caption's halo), ticks, text
    EXPECT_EQ(annotationPixels(centre.z + 0.9), onItsSlice); // within half a spacing
    EXPECT_EQ(annotationPixels(centre.z + 2.0), 0);          // the next slice
    EXPECT_EQ(annotationPixels(centre.z - 2.0), 0);
}

// With the silhouette's visible polylines the exports carry it as vectors: paths in the SVG (one
// per polyline, over a raster whose silhouette panel is blank), antialiased strokes in the
// picture where the raster lines were.
TEST(ReportImage, SilhouetteLinesGoInAsVectors) {
    test::ensureGuiApplication();
    report::RenderedPanels panels = test::renderSphereReview(kWindowPanel);
    const QImage rasterLines = panels.silhouette;
    const test::SphereReview& review = test::sphereReview();
    panels.silhouetteLines = render::visiblePolylines(
        review.mesh, panels.camera,
        render::PixelMask::fromImage(report::toCoreImage(rasterLines), {255, 255, 255, 255}));
    ASSERT_FALSE(panels.silhouetteLines.empty());
    const QString svg =
        QString::fromUtf8(report::renderSvg(panels, {}, report::PanelLayout::SideBySide));
    EXPECT_EQ(svg.count("<path d=\"M"), qsizetype(panels.silhouetteLines.size()));
    // The paths sit on the silhouette panel: shifted right by the iso panel's width.
    const QString firstX = svg.mid(svg.indexOf("<path d=\"M") + 10, 12).section(' ', 0, 0);
    EXPECT_GE(firstX.toDouble(), double(panels.iso.width()));

    // The picture: where the raster had line pixels the strokes darken the panel too, and the
    // panel is not the raster (antialiased grey levels appear).
    const QImage picture =
        report::composeExportImage(panels, {}, report::PanelLayout::SilhouettePanel);
    std::size_t linePixels = 0, stroked = 0, grey = 0;
    for (int y = 0; y < picture.height(); ++y)
        for (int x = 0; x < picture.width(); ++x) {
            const int value = qGray(picture.pixel(x, y));
            grey += value > 30 && value < 225 ? 1 : 0;
            if (qGray(rasterLines.pixel(x, y)) < 128) {
                ++linePixels;
                stroked += value < 200 ? 1 : 0;
            }
        }
    ASSERT_GT(linePixels, 100u);
    EXPECT_GE(double(stroked) / double(linePixels), 0.95);
    EXPECT_GT(grey, 100u) << "antialiased strokes";
    const QImage leftOut =
        report::composeExportImage(panels, {}, report::PanelLayout::SilhouettePanel, Qt::white, {},
                                   report::SilhouetteLines::LeftOut);
    std::size_t dark = 0;
    for (int y = 0; y < leftOut.height(); ++y)
        for (int x = 0; x < leftOut.width(); ++x)
            dark += qGray(leftOut.pixel(x, y)) < 250 ? 1 : 0;
    EXPECT_EQ(dark, 0u) << "left out for the PDF to draw as paths: the panel stays blank";
}

// Hidden lines go under the visible ones thin, dashed and grey: along one drawn across the empty
// top of the silhouette panel the picture alternates grey dashes and white gaps, never black; the
// SVG holds them as a dashed group of their own.
TEST(ReportImage, HiddenLinesAreDashedAndGrey) {
    test::ensureGuiApplication();
    report::RenderedPanels panels = test::renderSphereReview(kWindowPanel);
    const test::SphereReview& review = test::sphereReview();
    panels.silhouetteLines = render::visiblePolylines(
        review.mesh, panels.camera,
        render::PixelMask::fromImage(report::toCoreImage(panels.silhouette), {255, 255, 255, 255}));
    ASSERT_FALSE(panels.silhouetteLines.empty());
    panels.silhouetteLineWidth = 2.0;
    render::Polyline hidden;
    hidden.points = {{10.0f, 8.5f}, {float(kWindowPanel) - 10.0f, 8.5f}};
    panels.hiddenLines = {hidden};
    const QImage picture =
        report::composeExportImage(panels, {}, report::PanelLayout::SilhouettePanel);
    int grey = 0, white = 0, dark = 0, transitions = 0;
    bool wasGrey = false;
    for (int x = 12; x < kWindowPanel - 12; ++x) {
        const int value = qGray(picture.pixel(x, 8));
        const bool isGrey = value < 235;
        grey += isGrey ? 1 : 0;
        white += value >= 235 ? 1 : 0;
        dark += value < 100 ? 1 : 0;
        transitions += x > 12 && isGrey != wasGrey ? 1 : 0;
        wasGrey = isGrey;
    }
    EXPECT_EQ(dark, 0) << "grey, not black";
    EXPECT_GT(grey, kWindowPanel / 4);
    EXPECT_GT(white, kWindowPanel / 6) << "gaps between the dashes";
    EXPECT_GE(transitions, kWindowPanel / 8) << "dashes of 8 px and gaps of 6 px at width 2";

    const QString svg =
        QString::fromUtf8(report::renderSvg(panels, {}, report::PanelLayout::SideBySide));
    EXPECT_EQ(svg.count("stroke-dasharray=\"8.000 6.000\""), 1);
    EXPECT_EQ(svg.count("<path d=\"M"), qsizetype(panels.silhouetteLines.size() + 1));
    EXPECT_LT(svg.indexOf("stroke-dasharray"),
              svg.indexOf("stroke-linecap=\"round\" stroke-linejoin"));
}

// An existing file is kept byte for byte, and nothing else appears in the folder.
TEST(ReportExportRefused, ExistingFileIsKeptAndNothingIsLeftBehind) {
    test::TempDir dir;
    const auto path = dir / "review.png";
    core::writeFileAtomically(path, "original", 8);
    EXPECT_THROW(report::writeExportFile(path, QByteArray("new"), core::Overwrite::Refuse),
                 core::Error);
    EXPECT_EQ(core::readFileText(path), "original");
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), {}), 1);
    report::writeExportFile(path, QByteArray("new"), core::Overwrite::Allow); // --force
    EXPECT_EQ(core::readFileText(path), "new");
}

TEST(ReportExportRefused, MissingFolderIsNamedAndNothingIsCreated) {
    test::TempDir dir;
    try {
        report::writeExportFile(dir / "absent" / "a.pdf", QByteArray("x"), core::Overwrite::Refuse);
        FAIL() << "wrote into a missing folder";
    } catch (const core::Error& error) {
        EXPECT_NE(std::string(error.what()).find("absent"), std::string::npos);
    }
    EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

TEST(ReportExportRefused, ReadOnlyFolderGivesAClearMessageAndStaysEmpty) {
    if (::geteuid() == 0)
        GTEST_SKIP() << "running as root: permissions do not stop root from writing";
    test::TempDir dir;
    const auto folder = dir / "readonly";
    std::filesystem::create_directory(folder);
    ::chmod(folder.c_str(), 0555);
    try {
        core::checkWritableTarget(folder / "a.png", core::Overwrite::Refuse);
        ADD_FAILURE() << "a read-only folder was accepted";
    } catch (const core::Error& error) {
        EXPECT_NE(error.reason().find("cannot write into the folder"), std::string::npos);
    }
    EXPECT_THROW(
        report::writeExportFile(folder / "a.png", QByteArray("x"), core::Overwrite::Refuse),
        core::Error);
    EXPECT_TRUE(std::filesystem::is_empty(folder));
    ::chmod(folder.c_str(), 0755);
}

// An export file is written only as a plain file of the chosen folder: never through a link
// (wherever it points) and never as the folder itself or its parent; refused before writing,
// with the file and the reason, and even where overwriting was agreed.
TEST(ReportExportRefused, NothingIsWrittenOutsideTheChosenFolder) {
    test::TempDir dir;
    const test::LinkTrap trap(dir.path(), "review.png");
    for (const std::string& kind : test::LinkTrap::kinds()) {
        SCOPED_TRACE(kind);
        const auto path = trap.link(kind);
        for (const core::Overwrite overwrite : {core::Overwrite::Refuse, core::Overwrite::Allow}) {
            try {
                report::writeExportFile(path, QByteArray("new"), overwrite);
                ADD_FAILURE() << "wrote through a link";
            } catch (const core::Error& error) {
                EXPECT_EQ(error.subject(), path.string());
                EXPECT_NE(error.reason().find("symbolic link"), std::string::npos) << error.what();
            }
            EXPECT_TRUE(trap.untouched());
        }
    }
    for (const char* name : {"..", "."}) {
        SCOPED_TRACE(name);
        EXPECT_THROW(
            report::writeExportFile(trap.exports() / name, QByteArray("x"), core::Overwrite::Allow),
            core::Error);
        EXPECT_TRUE(trap.untouched());
    }
}
