// `linework-cli export ... --send NODE` against a real Orthanc: the Secondary Capture and the
// Encapsulated PDF report arrive in the source's study as new series, the PDF inside is the
// exported one byte for byte, what Orthanc stored passes dciodvfy (SKIP without dicom3tools),
// and the refusals: an anonymised export (exit 2, nothing written), a stopped PACS (exit 1
// naming the node).
#include "cli_runner.h"
#include "lw/core/file_util.h"
#include "orthanc_server.h"

#include <cstdio>
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace lw::pacs::test {
namespace {

namespace fs = std::filesystem;
using lw::test::quoted;
using lw::test::runCli;
using CliExportSend = OrthancSuite;

// A source series of its own study, in Orthanc as in a hospital's PACS, and a node file naming
// Orthanc "orthanc" (and a stopped PACS "stopped-pacs").
struct SendFixture {
    lw::test::TempDir dir;
    SyntheticSeries source;
    std::string nodes;

    explicit SendFixture(OrthancServer& server) : source(writeCtSeries(dir / "ct", 8, 32)) {
        for (const fs::path& file : source.files)
            server.upload(file);
        PacsNodeFile file;
        file.workstation.aet = kWorkstationAet;
        file.nodes = {server.node(), {"stopped-pacs", "NOBODY", "127.0.0.1", freeLoopbackPort()}};
        writeNodeFile(dir / "nodes.json", file);
        nodes = " --nodes " + quoted((dir / "nodes.json").string());
    }
    // `export` of the source with the given outputs and options.
    std::string exportCommand(const std::string& options) const {
        return "export " + quoted((dir / "ct").string()) + " --iso -990 --size 96x64" + options +
               nodes;
    }
};

std::string sopInstanceUidOf(const fs::path& file) {
    DcmFileFormat format;
    OFString uid;
    if (format.loadFile(file.c_str()).good())
        format.getDataset()->findAndGetOFString(DCM_SOPInstanceUID, uid);
    return uid.c_str();
}

// How many series Orthanc holds in the study with that UID.
int seriesInStudy(const OrthancServer& server, const std::string& studyUid) {
    const std::string series = server.seriesOfStudy(studyUid);
    int count = 0;
    for (std::size_t from = series.find("\"Type\" : \"Series\""); from != std::string::npos;
         from = series.find("\"Type\" : \"Series\"", from + 1))
        ++count;
    return count;
}

// dciodvfy's report on `file` (it writes to stderr, which runProgram drops: a shell redirects).
std::optional<std::string> dciodvfy(const fs::path& file) {
    if (lw::test::runProgram("sh", "-c 'command -v dciodvfy'").exitCode != 0)
        return std::nullopt;
    return lw::test::runProgram("sh", "-c " + quoted("dciodvfy \"" + file.string() + "\" 2>&1"))
        .out;
}

TEST_F(CliExportSend, StoresTheCaptureAndThePdfInTheSourceStudy) {
    SendFixture fixture(server());
    const fs::path pdf = fixture.dir / "out" / "report.pdf";
    fs::create_directories(pdf.parent_path());
    const auto sent = runCli(fixture.exportCommand(" --pdf " + quoted(pdf.string()) + " --sc " +
                                                   quoted((fixture.dir / "out/sc").string()) +
                                                   " --send orthanc"));
    ASSERT_EQ(sent.exitCode, 0) << sent.err << sent.out;
    std::printf("%s", sent.out.c_str());                              // the write and C-STORE times
    const fs::path encapsulated = fixture.dir / "out" / "report.dcm"; // beside the PDF
    const fs::path capture = fixture.dir / "out" / "sc" / "LWSC0001.dcm";
    for (const fs::path& file : {encapsulated, capture})
        EXPECT_NE(sent.out.find("sent " + file.string() + " to orthanc (LW_ORTHANC@127.0.0.1:" +
                                std::to_string(server().dicomPort()) + "): stored"),
                  std::string::npos)
            << sent.out;

    const std::string pdfInstance = server().instancePath(sopInstanceUidOf(encapsulated));
    const std::string scInstance = server().instancePath(sopInstanceUidOf(capture));
    ASSERT_FALSE(pdfInstance.empty() || scInstance.empty()) << server().log();
    EXPECT_EQ(server().tag(pdfInstance, "SOPClassUID"), UID_EncapsulatedPDFStorage);
    EXPECT_EQ(server().tag(scInstance, "SOPClassUID"), UID_SecondaryCaptureImageStorage);
    const std::string pdfSeries = server().tag(pdfInstance, "SeriesInstanceUID");
    const std::string scSeries = server().tag(scInstance, "SeriesInstanceUID");
    for (const std::string& instance : {pdfInstance, scInstance})
        EXPECT_EQ(server().tag(instance, "StudyInstanceUID"), fixture.source.studyUid);
    EXPECT_NE(pdfSeries, fixture.source.seriesUid);
    EXPECT_NE(scSeries, fixture.source.seriesUid);
    EXPECT_NE(pdfSeries, scSeries);
    EXPECT_EQ(seriesInStudy(server(), fixture.source.studyUid), 3); // the CT, the SC, the PDF

    // The document Orthanc keeps is the exported PDF (then at most the pad byte 0).
    const std::string exported = core::readFileText(pdf);
    const HttpReply document = server().http("GET", pdfInstance + "/content/0042-0011");
    ASSERT_EQ(document.status, 200);
    ASSERT_GE(document.body.size(), exported.size());
    EXPECT_EQ(document.body.substr(0, exported.size()), exported);
    EXPECT_LE(document.body.size(), exported.size() + 1);
}

// What Orthanc stored, fetched back as files, passes dciodvfy without an error line.
TEST_F(CliExportSend, WhatWasSentPassesDciodvfy) {
    SendFixture fixture(server());
    const fs::path out = fixture.dir / "out";
    fs::create_directories(out);
    const auto sent =
        runCli(fixture.exportCommand(" --pdf " + quoted((out / "report.pdf").string()) + " --sc " +
                                     quoted((out / "sc").string()) + " --send orthanc"));
    ASSERT_EQ(sent.exitCode, 0) << sent.err;
    for (const fs::path& file : {out / "report.dcm", out / "sc" / "LWSC0001.dcm"}) {
        const std::string instance = server().instancePath(sopInstanceUidOf(file));
        const HttpReply stored = server().http("GET", instance + "/file");
        ASSERT_EQ(stored.status, 200) << instance;
        const fs::path copy = fixture.dir / ("stored-" + file.filename().string());
        core::writeFileAtomically(copy, stored.body.data(), stored.body.size());
        const std::optional<std::string> report = dciodvfy(copy);
        if (!report)
            GTEST_SKIP() << "dciodvfy is not installed (Debian: apt-get install dicom3tools)";
        std::printf("dciodvfy %s:\n%s", file.filename().c_str(), report->c_str());
        EXPECT_EQ(report->find("\nError"), std::string::npos) << *report;
        EXPECT_NE(report->rfind("Error", 0), 0u) << *report;
    }
}

TEST_F(CliExportSend, AnAnonymisedExportIsNotSentAndNothingIsWritten) {
    SendFixture fixture(server());
    const fs::path out = fixture.dir / "out";
    fs::create_directories(out);
    const auto refused = runCli(
        fixture.exportCommand(" --anonymise --pdf " + quoted((out / "report.pdf").string()) +
                              " --png " + quoted((out / "view.png").string()) + " --send orthanc"));
    EXPECT_EQ(refused.exitCode, 2) << refused.err;
    EXPECT_NE(refused.err.find("an anonymised export cannot be sent to the PACS because it would "
                               "no longer belong to the patient's study"),
              std::string::npos)
        << refused.err;
    EXPECT_TRUE(fs::is_empty(out));
    EXPECT_EQ(seriesInStudy(server(), fixture.source.studyUid), 1);
}

TEST_F(CliExportSend, AStoppedPacsExitsOneNamingTheNodeAndKeepsTheFiles) {
    SendFixture fixture(server());
    const fs::path out = fixture.dir / "out";
    fs::create_directories(out);
    const auto failed = runCli(fixture.exportCommand(
        " --pdf " + quoted((out / "report.pdf").string()) + " --send stopped-pacs --timeout 5"));
    EXPECT_EQ(failed.exitCode, 1);
    EXPECT_NE(failed.err.find("stopped-pacs (NOBODY@127.0.0.1:"), std::string::npos) << failed.err;
    EXPECT_NE(failed.err.find("connection refused"), std::string::npos) << failed.err;
    EXPECT_TRUE(fs::is_regular_file(out / "report.pdf"));
    EXPECT_TRUE(fs::is_regular_file(out / "report.dcm"));
}

TEST_F(CliExportSend, UsageErrorsExitTwoBeforeWriting) {
    SendFixture fixture(server());
    const std::string png = " --png " + quoted((fixture.dir / "view.png").string());
    for (const std::string& options :
         {png + " --send orthanc", png + " --send nosuchnode", png + " --nodes x.json",
          png + " --encapsulated-pdf " + quoted((fixture.dir / "r.dcm").string())}) {
        const auto result = runCli(fixture.exportCommand(options));
        EXPECT_EQ(result.exitCode, 2) << options << "\n" << result.err;
    }
    EXPECT_FALSE(fs::exists(fixture.dir / "view.png"));
}

} // namespace
} // namespace lw::pacs::test
