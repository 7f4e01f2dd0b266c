// The PDF report read back with poppler: pdftotext finds the header, the measurements and the
// comment; pdftoppm's pages are not blank. (CTest runs these as report_pdf_tests, SKIP without
// poppler-utils.)
#include "cli_runner.h"
#include "lw/core/file_util.h"
#include "lw/report/export_files.h"
#include "lw/report/pdf_report.h"
#include "report_test_support.h"
#include "test_support.h"

#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace lw;

namespace {

// What `program arguments` prints on stdout.
std::string run(const std::string& program, const std::string& arguments) {
    return test::runProgram(program, arguments).out;
}

report::ReportInfo sampleInfo() {
    report::ReportInfo info;
    info.identity = input::DicomIdentity{.patientName = "Doe^Jane",
                                         .patientId = "LW-0042",
                                         .patientBirthDate = "19700102",
                                         .patientSex = "F",
                                         .studyInstanceUid = "1.2.3",
                                         .studyDate = "20261101",
                                         .studyDescription = "CT HEAD",
                                         .seriesDescription = "Bone 1 mm",
                                         .modality = "CT",
                                         .seriesNumber = 3};
    info.method = "Linework silhouette method 3, iso-value 300";
    info.comment = "Stable since the last study; no new finding.";
    info.softwareVersion = "9.8.7";
    return info;
}

// Dark pixels of a page rendered by pdftoppm as a greyscale PGM (binary, 8 bit).
int darkPixels(const std::filesystem::path& pgm) {
    std::ifstream in(pgm, std::ios::binary);
    std::string magic;
    int width = 0, height = 0, maxValue = 0;
    in >> magic >> width >> height >> maxValue;
    in.get();
    int dark = 0;
    for (int i = 0; i < width * height; ++i)
        dark += in.get() < 128 ? 1 : 0;
    return magic == "P5" ? dark : -1;
}

std::filesystem::path writeReport(const test::TempDir& dir, const report::ReportInfo& info) {
    const report::RenderedPanels panels = test::renderSphereReview(512);
    const QImage picture = report::composeExportImage(panels, test::sphereAnnotations(),
                                                      report::PanelLayout::SideBySide);
    const auto path = dir / "report.pdf";
    report::writeExportFile(path, report::renderPdfReport(info, picture, test::sphereAnnotations()),
                            core::Overwrite::Refuse);
    return path;
}

} // namespace

TEST(ReportPdf, TextHoldsHeaderMeasurementsAndComment) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const auto pdf = writeReport(dir, sampleInfo());
    const std::string text = run("pdftotext", "-layout " + test::quoted(pdf.string()) + " -");
    for (const char* expected :
         {"Linework report", "Doe^Jane", "LW-0042", "1970-01-02", "2026-11-01", "CT HEAD",
          "Bone 1 mm", "iso-value 300", "40.0 mm", "90.0°", "Finding A", "ruler", "angle",
          "Stable since the last study; no new finding.", "Linework 9.8.7", "page 2 of 2"})
        EXPECT_NE(text.find(expected), std::string::npos) << expected << " missing in:\n" << text;
    EXPECT_NE(run("pdfinfo", test::quoted(pdf.string())).find("Pages:           2"),
              std::string::npos);
}

TEST(ReportPdf, AnonymisedReportLeavesThePatientOut) {
    test::ensureGuiApplication();
    test::TempDir dir;
    report::ReportInfo info = sampleInfo();
    info.anonymise = true;
    const std::string text = run("pdftotext", test::quoted(writeReport(dir, info).string()) + " -");
    EXPECT_EQ(text.find("Doe^Jane"), std::string::npos);
    EXPECT_EQ(text.find("LW-0042"), std::string::npos);
    EXPECT_EQ(text.find("1970-01-02"), std::string::npos);
    EXPECT_NE(text.find("(anonymised)"), std::string::npos);
    EXPECT_NE(text.find("CT HEAD"), std::string::npos); // the study stays
}

TEST(ReportPdf, PagesAreNotBlank) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const auto pdf = writeReport(dir, sampleInfo());
    run("pdftoppm",
        "-r 40 -gray " + test::quoted(pdf.string()) + " " + test::quoted((dir / "page").string()));
    const int first = darkPixels(dir / "page-1.pgm");
    const int second = darkPixels(dir / "page-2.pgm");
    EXPECT_GT(first, 1000) << "page 1: header text and the picture";
    EXPECT_GT(second, 200) << "page 2: the table and the comment";
}

// The measurement list names the plane and position of a measurement made on a slice.
TEST(ReportPdf, SliceMeasurementsNameTheirPlane) {
    test::ensureGuiApplication();
    test::TempDir dir;
    // The longest a measurement gets: an angle on a sagittal slice at a negative position.
    annotation::Annotation angle{
        annotation::AnnotationKind::Angle, {{-123.4, 5, 0}, {-123.4, 0, 0}, {-123.4, 0, 5}}, {}};
    angle.slice = annotation::SlicePlacement{annotation::SliceOrientation::Sagittal, -123.4, 0.7};
    const std::vector<annotation::Annotation> annotations = {test::sphereSliceRuler(), angle};
    const auto path = dir / "slice.pdf";
    report::writeExportFile(path, report::renderPdfReport(sampleInfo(), QImage(), annotations),
                            core::Overwrite::Refuse);
    const std::string text = run("pdftotext", test::quoted(path.string()) + " -");
    EXPECT_EQ(annotation::measurementText(angle), "90.0\u00b0 \u00b7 sagittal -123.4 mm");
    for (const annotation::Annotation& item : annotations) { // each on one line of its cell
        const std::string expected = annotation::measurementText(item);
        EXPECT_NE(text.find(expected), std::string::npos) << expected << " missing in:\n" << text;
    }
}

// A long table is not cut off: it continues on further pages with the table's header row again,
// and every page's footer counts them all.
TEST(ReportPdf, ManyAnnotationsContinueOnFurtherPages) {
    test::ensureGuiApplication();
    test::TempDir dir;
    std::vector<annotation::Annotation> rulers;
    for (int i = 0; i < 90; ++i)
        rulers.push_back({annotation::AnnotationKind::Ruler, {{0, 0, 0}, {0, 0, 10.0 + i}}, {}});
    const auto path = dir / "long.pdf";
    report::writeExportFile(path, report::renderPdfReport(sampleInfo(), QImage(), rulers),
                            core::Overwrite::Refuse);
    const std::string info = run("pdfinfo", test::quoted(path.string()));
    const std::size_t pagesAt = info.find("Pages:");
    ASSERT_NE(pagesAt, std::string::npos);
    const int pages = std::stoi(info.substr(pagesAt + 6));
    EXPECT_GE(pages, 3);
    const std::string text = run("pdftotext", "-layout " + test::quoted(path.string()) + " -");
    EXPECT_NE(text.find("99.0 mm"), std::string::npos); // the last ruler
    EXPECT_NE(text.find("Stable since the last study"), std::string::npos);
    EXPECT_NE(text.find("page " + std::to_string(pages) + " of " + std::to_string(pages)),
              std::string::npos);
    std::size_t headers = 0;
    for (std::size_t at = text.find("Points (LPS, mm)"); at != std::string::npos;
         at = text.find("Points (LPS, mm)", at + 1))
        ++headers;
    EXPECT_GE(headers, 2u); // the header row again where the table continues
}
