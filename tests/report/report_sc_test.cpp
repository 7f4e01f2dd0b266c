// DICOM Secondary Capture and Encapsulated PDF: new series in the source's study that Linework's
// own import (or DCMTK) reads back as such, and (report_sc_tests, SKIP without dicom3tools) that
// dciodvfy passes without errors.
#include "cli_runner.h"
#include "dicom_test_writer.h"
#include "link_trap.h"
#include "lw/core/error.h"
#include "lw/dicom/dicom_scanner.h"
#include "lw/input/open_input.h"
#include "lw/report/encapsulated_pdf.h"
#include "lw/report/pdf_report.h"
#include "lw/report/secondary_capture.h"
#include "report_test_support.h"
#include "test_support.h"

#include <cstdio>
#include <cstring>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <gtest/gtest.h>

using namespace lw;

namespace {

constexpr const char* kStudyUid = "1.2.826.0.1.3680043.9.4245.999.1";

// Three 16 x 16 CT slices of one series in `folder`, opened through lw::input as the CLI does.
input::OpenedVolume writeAndOpenSourceSeries(const std::filesystem::path& folder) {
    std::filesystem::create_directories(folder);
    const std::string seriesUid = dicom::test::makeTestUid();
    for (int k = 0; k < 3; ++k) {
        dicom::test::TestSlice slice;
        slice.rows = slice.columns = 16;
        slice.pixels = dicom::test::rampPixels(16, 16, -1000 + 100 * k, 7);
        slice.position = glm::dvec3(0, 0, 2.5 * k);
        slice.studyUid = kStudyUid;
        slice.seriesUid = seriesUid;
        slice.patientName = "Doe^Jane";
        slice.patientId = "LW-0042";
        slice.seriesNumber = 4;
        dicom::test::writeTestSlice(folder / ("ct" + std::to_string(k) + ".dcm"), slice);
    }
    return input::openInput(folder.string());
}

QImage capturedPicture() {
    return report::composeExportImage(test::renderSphereReview(128), test::sphereAnnotations(),
                                      report::PanelLayout::SideBySide);
}

std::vector<std::filesystem::path>
writeCapture(const input::OpenedVolume& source, const std::filesystem::path& folder,
             core::Overwrite overwrite = core::Overwrite::Refuse) {
    report::SecondaryCaptureSeries series;
    series.source = source.dicom.value();
    series.derivationDescription = "Linework silhouette method 3, iso-value 300 HU";
    series.softwareVersion = "0.1.0";
    return report::writeSecondaryCapture(folder, {capturedPicture()}, series, overwrite);
}

// A small but real PDF report of odd length (the pad byte after it is tested).
QByteArray oddLengthPdf() {
    report::ReportInfo info;
    info.method = "Linework silhouette method 3, iso-value 300 HU";
    QByteArray pdf = report::renderPdfReport(info, capturedPicture(), test::sphereAnnotations());
    if (pdf.size() % 2 == 0)
        pdf.append('\n'); // after %%EOF: still the same PDF to a reader
    return pdf;
}

std::filesystem::path writeEncapsulated(const input::OpenedVolume& source,
                                        const std::filesystem::path& path, const QByteArray& pdf) {
    report::EncapsulatedPdfSeries series;
    series.source = source.dicom.value();
    series.softwareVersion = "0.1.0";
    report::writeEncapsulatedPdf(path, pdf, series, core::Overwrite::Refuse);
    return path;
}

std::string stringOf(DcmDataset& dataset, const DcmTagKey& tag) {
    OFString value;
    dataset.findAndGetOFString(tag, value);
    return value.c_str();
}

// dciodvfy's report on `file` (stderr, which runProgram drops, turned into stdout by a shell).
std::string dciodvfy(const std::filesystem::path& file) {
    return test::runProgram("sh", "-c " + test::quoted("dciodvfy \"" + file.string() + "\" 2>&1"))
        .out;
}

} // namespace

// The PDF inside is the report byte for byte (its length in EncapsulatedDocumentLength, then a
// pad byte 0), in a new DOC series of the source's study with the source's patient.
TEST(EncapsulatedPdf, HoldsThePdfInANewSeriesOfTheSameStudy) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const input::OpenedVolume source = writeAndOpenSourceSeries(dir / "ct");
    const QByteArray pdf = oddLengthPdf();
    DcmFileFormat file;
    ASSERT_TRUE(file.loadFile(writeEncapsulated(source, dir / "report.dcm", pdf).c_str()).good());
    DcmDataset& dataset = *file.getDataset();
    EXPECT_EQ(stringOf(dataset, DCM_SOPClassUID), "1.2.840.10008.5.1.4.1.1.104.1");
    EXPECT_EQ(stringOf(dataset, DCM_StudyInstanceUID), kStudyUid);
    EXPECT_EQ(stringOf(dataset, DCM_PatientID), "LW-0042");
    EXPECT_EQ(stringOf(dataset, DCM_PatientName), "Doe^Jane");
    EXPECT_NE(stringOf(dataset, DCM_SeriesInstanceUID), source.dicom->seriesInstanceUid);
    EXPECT_EQ(stringOf(dataset, DCM_SeriesNumber), "1005");
    EXPECT_EQ(stringOf(dataset, DCM_Modality), "DOC");
    EXPECT_EQ(stringOf(dataset, DCM_MIMETypeOfEncapsulatedDocument), "application/pdf");
    EXPECT_EQ(stringOf(dataset, DCM_BurnedInAnnotation), "YES");
    EXPECT_EQ(stringOf(dataset, DCM_DocumentTitle), "Linework report");
    Uint32 length = 0;
    ASSERT_TRUE(dataset.findAndGetUint32(DCM_EncapsulatedDocumentLength, length).good());
    EXPECT_EQ(length, Uint32(pdf.size()));
    const Uint8* document = nullptr;
    unsigned long count = 0;
    ASSERT_TRUE(dataset.findAndGetUint8Array(DCM_EncapsulatedDocument, document, &count).good());
    ASSERT_EQ(count, std::size_t(pdf.size()) + 1);
    EXPECT_EQ(QByteArray(reinterpret_cast<const char*>(document), pdf.size()), pdf);
    EXPECT_EQ(document[pdf.size()], 0);
}

TEST(EncapsulatedPdf, RefusesWhatItCannotWrapAndKeepsExistingFiles) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const input::OpenedVolume source = writeAndOpenSourceSeries(dir / "ct");
    const std::filesystem::path path =
        writeEncapsulated(source, dir / "report.dcm", oddLengthPdf());
    const auto bytes = core::readFileBytes(path);
    EXPECT_THROW(writeEncapsulated(source, path, oddLengthPdf()), core::Error); // exists already
    EXPECT_EQ(core::readFileBytes(path), bytes);
    try {
        writeEncapsulated(source, dir / "text.dcm", "not a PDF");
        ADD_FAILURE() << "wrapped a text";
    } catch (const core::Error& error) {
        EXPECT_EQ(error.subject(), (dir / "text.dcm").string());
        EXPECT_NE(error.reason().find("not a PDF"), std::string::npos) << error.what();
    }
    input::OpenedVolume phantom;
    phantom.dicom = input::DicomIdentity{}; // no study to join
    EXPECT_THROW(writeEncapsulated(phantom, dir / "phantom.dcm", oddLengthPdf()), core::Error);
    EXPECT_FALSE(std::filesystem::exists(dir / "text.dcm"));
    EXPECT_FALSE(std::filesystem::exists(dir / "phantom.dcm"));
}

TEST(EncapsulatedPdfValidation, DciodvfyReportsNoErrors) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const std::string output = dciodvfy(writeEncapsulated(writeAndOpenSourceSeries(dir / "ct"),
                                                          dir / "report.dcm", oddLengthPdf()));
    EXPECT_NE(output.find("EncapsulatedPDF"), std::string::npos) << output; // validated as such
    EXPECT_EQ(output.find("Error"), std::string::npos) << output;
    std::printf("dciodvfy:\n%s", output.c_str());
}

TEST(SecondaryCapture, ReimportsAsANewSeriesOfTheSameStudy) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const input::OpenedVolume source = writeAndOpenSourceSeries(dir / "ct");
    ASSERT_TRUE(source.dicom);
    EXPECT_EQ(source.dicom->studyInstanceUid, kStudyUid);
    const auto files = writeCapture(source, dir / "sc");
    ASSERT_EQ(files.size(), 1u);
    EXPECT_EQ(files[0].filename(), "LWSC0001.dcm");

    const dicom::DicomIndex index = dicom::scanDicom(dir.path());
    ASSERT_EQ(index.patients.size(), 1u);
    EXPECT_EQ(index.patients[0].patientId, "LW-0042");
    EXPECT_EQ(index.patients[0].name, "Doe^Jane");
    ASSERT_EQ(index.patients[0].studies.size(), 1u); // the capture joined the source's study
    const dicom::StudyInfo& study = index.patients[0].studies[0];
    EXPECT_EQ(study.studyInstanceUid, kStudyUid);
    ASSERT_EQ(study.series.size(), 2u);
    const dicom::SeriesInfo* capture = nullptr;
    for (const dicom::SeriesInfo& series : study.series)
        if (series.seriesInstanceUid != source.dicom->seriesInstanceUid)
            capture = &series;
    ASSERT_NE(capture, nullptr);
    EXPECT_EQ(capture->seriesNumber, 1004);
    ASSERT_EQ(capture->instances.size(), 1u);
    const dicom::InstanceInfo& instance = capture->instances[0];
    EXPECT_EQ(instance.sopClassUid, "1.2.840.10008.5.1.4.1.1.7");
    EXPECT_EQ(instance.samplesPerPixel, 3);
    EXPECT_EQ(instance.columns, 256);
    EXPECT_EQ(instance.rows, 128);
    EXPECT_NE(instance.sopInstanceUid, "");
}

// DCMTK reads the file back: the pixels are the picture's, row by row, RGB interleaved, and the
// attributes that make it a derived series of the source's study are there.
TEST(SecondaryCapture, DcmtkReadsBackThePictureAndTheDerivation) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const auto files = writeCapture(writeAndOpenSourceSeries(dir / "ct"), dir / "sc");
    DcmFileFormat file;
    ASSERT_TRUE(file.loadFile(files.at(0).c_str()).good());
    DcmDataset& dataset = *file.getDataset();
    const QImage expected = capturedPicture().convertToFormat(QImage::Format_RGB888);
    Uint16 rows = 0, columns = 0;
    dataset.findAndGetUint16(DCM_Rows, rows);
    dataset.findAndGetUint16(DCM_Columns, columns);
    ASSERT_EQ(int(rows), expected.height());
    ASSERT_EQ(int(columns), expected.width());
    const Uint8* pixels = nullptr;
    unsigned long count = 0;
    ASSERT_TRUE(dataset.findAndGetUint8Array(DCM_PixelData, pixels, &count).good());
    ASSERT_EQ(count, std::size_t(rows) * columns * 3);
    for (int y = 0; y < expected.height(); ++y)
        ASSERT_EQ(std::memcmp(pixels + std::size_t(y) * columns * 3, expected.constScanLine(y),
                              std::size_t(columns) * 3),
                  0)
            << "row " << y;
    OFString value;
    dataset.findAndGetOFString(DCM_DerivationDescription, value);
    EXPECT_EQ(value, "Linework silhouette method 3, iso-value 300 HU");
    dataset.findAndGetOFString(DCM_StudyInstanceUID, value);
    EXPECT_EQ(value, kStudyUid);
    dataset.findAndGetOFString(DCM_BurnedInAnnotation, value);
    EXPECT_EQ(value, "YES");
    dataset.findAndGetOFStringArray(DCM_ImageType, value);
    EXPECT_EQ(value, "DERIVED\\SECONDARY");
}

TEST(SecondaryCapture, RefusedWritesLeaveNothingBehind) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const input::OpenedVolume source = writeAndOpenSourceSeries(dir / "ct");
    const auto first = writeCapture(source, dir / "sc");
    const auto bytes = core::readFileBytes(first[0]);
    EXPECT_THROW(writeCapture(source, dir / "sc"), core::Error); // exists already
    EXPECT_EQ(core::readFileBytes(first[0]), bytes);
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir / "sc"), {}), 1);
    EXPECT_NO_THROW(writeCapture(source, dir / "sc", core::Overwrite::Allow)); // --force
    // A folder whose parent is missing: named, nothing created.
    EXPECT_THROW(writeCapture(source, dir / "absent" / "sc"), core::Error);
    EXPECT_FALSE(std::filesystem::exists(dir / "absent"));
    // Not DICOM: no study to join.
    input::OpenedVolume phantom;
    phantom.dicom = input::DicomIdentity{};
    EXPECT_THROW(writeCapture(phantom, dir / "sc2"), core::Error);
    EXPECT_FALSE(std::filesystem::exists(dir / "sc2"));
}

// The series' first file name is a link in the chosen folder: refused for every kind of link
// (and when replacing was agreed), before anything is written.
TEST(SecondaryCapture, ALinkInTheFolderIsNeverWrittenThrough) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const input::OpenedVolume source = writeAndOpenSourceSeries(dir / "ct");
    const test::LinkTrap trap(dir.path(), report::secondaryCaptureFileName(1));
    for (const std::string& kind : test::LinkTrap::kinds()) {
        SCOPED_TRACE(kind);
        const auto link = trap.link(kind);
        for (const core::Overwrite overwrite : {core::Overwrite::Refuse, core::Overwrite::Allow}) {
            try {
                report::checkSecondaryCaptureTarget(trap.exports(), overwrite);
                ADD_FAILURE() << "the check accepted a link";
            } catch (const core::Error& error) {
                EXPECT_EQ(error.subject(), link.string());
            }
            try {
                writeCapture(source, trap.exports(), overwrite);
                ADD_FAILURE() << "wrote through a link";
            } catch (const core::Error& error) {
                EXPECT_NE(error.reason().find("symbolic link"), std::string::npos) << error.what();
            }
            EXPECT_TRUE(trap.untouched());
        }
    }
}

TEST(SecondaryCaptureValidation, DciodvfyReportsNoErrors) {
    test::ensureGuiApplication();
    test::TempDir dir;
    const auto files = writeCapture(writeAndOpenSourceSeries(dir / "ct"), dir / "sc");
    const std::string output = dciodvfy(files.at(0));
    EXPECT_NE(output.find("SCImage"), std::string::npos) << output; // validated as SC
    EXPECT_EQ(output.find("Error"), std::string::npos) << output;
    std::printf("dciodvfy:\n%s", output.c_str());
}
