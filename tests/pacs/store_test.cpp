// C-STORE of a Secondary Capture and an Encapsulated PDF to a real Orthanc, read back through
// its REST API.
#include "dicom_test_writer.h"
#include "lw/core/file_util.h"
#include "lw/pacs/store_scu.h"
#include "orthanc_server.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>

namespace lw::pacs::test {
namespace {

namespace fs = std::filesystem;
using OrthancStore = OrthancSuite;

// A minimal Encapsulated PDF in the seeded study (the report's, once it writes one).
void writeEncapsulatedPdf(const fs::path& path, const std::string& studyUid,
                          const std::string& sopUid) {
    DcmFileFormat file;
    DcmDataset* data = file.getDataset();
    data->putAndInsertString(DCM_SOPClassUID, UID_EncapsulatedPDFStorage);
    data->putAndInsertString(DCM_SOPInstanceUID, sopUid.c_str());
    data->putAndInsertString(DCM_StudyInstanceUID, studyUid.c_str());
    data->putAndInsertString(DCM_SeriesInstanceUID, dicom::test::makeTestUid().c_str());
    data->putAndInsertString(DCM_PatientID, "LW-TEST");
    data->putAndInsertString(DCM_PatientName, "Test^Linework");
    data->putAndInsertString(DCM_Modality, "DOC");
    data->putAndInsertString(DCM_MIMETypeOfEncapsulatedDocument, "application/pdf");
    data->putAndInsertString(DCM_DocumentTitle, "Linework report");
    static const char kPdf[] = "%PDF-1.4\n1 0 obj<<>>endobj\ntrailer<<>>\n%%EOF\n";
    std::string pdf = kPdf;
    if (pdf.size() % 2)
        pdf.push_back('\0');
    data->putAndInsertUint8Array(DCM_EncapsulatedDocument,
                                 reinterpret_cast<const Uint8*>(pdf.data()), pdf.size());
    ASSERT_TRUE(file.saveFile(path.c_str(), EXS_LittleEndianExplicit).good());
}

TEST_F(OrthancStore, SecondaryCaptureAndPdfAreAcceptedAndReadBack) {
    lw::test::TempDir dir;
    dicom::test::TestSlice sc;
    sc.sopClassUid = UID_SecondaryCaptureImageStorage;
    sc.modality = "OT";
    sc.studyUid = first().studyUid;
    sc.sopInstanceUid = dicom::test::makeTestUid();
    dicom::test::writeTestSlice(dir / "sc.dcm", sc);
    const std::string pdfUid = dicom::test::makeTestUid();
    writeEncapsulatedPdf(dir / "report.dcm", first().studyUid, pdfUid);

    const std::vector<StoreOutcome> outcomes =
        storeFiles(server().node(), {dir / "sc.dcm", dir / "report.dcm"}, options());
    ASSERT_EQ(outcomes.size(), 2u);
    for (const StoreOutcome& outcome : outcomes) {
        EXPECT_TRUE(outcome.accepted) << outcome.file << ": " << outcome.message;
        EXPECT_EQ(outcome.status, 0) << outcome.message;
        // Orthanc has it: its REST API finds the instance by its UID, with its SOP class.
        const std::string instance = server().instancePath(outcome.sopInstanceUid);
        ASSERT_FALSE(instance.empty()) << outcome.sopInstanceUid;
        const std::string sopClass = outcome.file.filename() == "sc.dcm"
                                         ? UID_SecondaryCaptureImageStorage
                                         : UID_EncapsulatedPDFStorage;
        EXPECT_EQ(server().tag(instance, "SOPClassUID"), sopClass);
    }
    EXPECT_EQ(outcomes[1].sopInstanceUid, pdfUid);
}

TEST_F(OrthancStore, UnreadableFileIsNamed) {
    lw::test::TempDir dir;
    const std::string text = "not DICOM";
    core::writeFileAtomically(dir / "junk.dcm", text.data(), text.size());
    try {
        storeFiles(server().node(), {dir / "junk.dcm"}, options());
        FAIL() << "a non-DICOM file was sent";
    } catch (const core::Error& error) {
        EXPECT_NE(std::string(error.what()).find("junk.dcm"), std::string::npos) << error.what();
    }
}

} // namespace
} // namespace lw::pacs::test
