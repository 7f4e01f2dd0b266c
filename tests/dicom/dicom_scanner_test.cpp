// Scanner unit tests on folders and DICOMDIRs the tests write themselves, so every count and
// every error below is known in advance.
#include "dicom_test_writer.h"
#include "lw/core/error.h"
#include "lw/core/progress.h"
#include "lw/dicom/dicom_scanner.h"
#include "test_support.h"

#include <algorithm>
#include <dcmtk/dcmdata/dcddirif.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcmetinf.h>
#include <dcmtk/dcmdata/dcsequen.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <fstream>
#include <gtest/gtest.h>

namespace fs = std::filesystem;
using namespace lw;
using dicom::test::TestSlice;

namespace {

struct SeriesSpec {
    std::string patientId = "P1";
    std::string patientName = "Doe^Jane";
    std::string studyUid;
    std::string seriesUid;
    int seriesNumber = 1;
    int slices = 3;
};

// Writes `spec.slices` axial slices 2 mm apart named <prefix>1, <prefix>2, ... into `dir`.
std::vector<fs::path> writeSeries(const fs::path& dir, const SeriesSpec& spec,
                                  const std::string& prefix = "IM") {
    fs::create_directories(dir);
    std::vector<fs::path> paths;
    for (int i = 0; i < spec.slices; ++i) {
        TestSlice s;
        s.patientId = spec.patientId;
        s.patientName = spec.patientName;
        s.studyUid = spec.studyUid;
        s.seriesUid = spec.seriesUid;
        s.seriesNumber = spec.seriesNumber;
        s.instanceNumber = i + 1;
        s.position = glm::dvec3(0.0, 0.0, 2.0 * i);
        s.pixels = dicom::test::rampPixels(s.rows, s.columns, i * 100);
        paths.push_back(dir / (prefix + std::to_string(i + 1)));
        dicom::test::writeTestSlice(paths.back(), s);
    }
    return paths;
}

SeriesSpec newSeries(int number, int slices, std::string studyUid = dicom::test::makeTestUid()) {
    SeriesSpec spec;
    spec.studyUid = std::move(studyUid);
    spec.seriesUid = dicom::test::makeTestUid();
    spec.seriesNumber = number;
    spec.slices = slices;
    return spec;
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

const dicom::FileError* findError(const dicom::DicomIndex& index, const std::string& fileSuffix) {
    for (const auto& e : index.errors)
        if (e.file.size() >= fileSuffix.size() &&
            e.file.compare(e.file.size() - fileSuffix.size(), fileSuffix.size(), fileSuffix) == 0)
            return &e;
    return nullptr;
}

bool anyWarningContains(const dicom::DicomIndex& index, const std::string& text) {
    return std::any_of(index.warnings.begin(), index.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

struct DirRecord {
    std::string type;
    std::string fileId; // backslash-separated, as on media
    std::string sopClassInFile;
    std::string seriesUid;
};

// A DICOMDIR written record by record, without offsets and in the given order: the odd
// layouts (reordered, no offsets, hostile paths) that DicomDirInterface refuses to produce.
void writeRawDicomdir(const fs::path& path, const std::vector<DirRecord>& records) {
    DcmFileFormat file;
    DcmDataset* dataset = file.getDataset();
    dataset->putAndInsertString(DCM_FileSetID, "LWTEST");
    auto* sequence = new DcmSequenceOfItems(DCM_DirectoryRecordSequence);
    for (const auto& r : records) {
        auto* item = new DcmItem();
        item->putAndInsertString(DCM_DirectoryRecordType, r.type.c_str());
        if (!r.fileId.empty())
            item->putAndInsertString(DCM_ReferencedFileID, r.fileId.c_str());
        if (!r.sopClassInFile.empty())
            item->putAndInsertString(DCM_ReferencedSOPClassUIDInFile, r.sopClassInFile.c_str());
        if (!r.seriesUid.empty())
            item->putAndInsertString(DCM_SeriesInstanceUID, r.seriesUid.c_str());
        sequence->append(item);
    }
    dataset->insert(sequence);
    file.getMetaInfo()->putAndInsertString(DCM_MediaStorageSOPClassUID,
                                           UID_MediaStorageDirectoryStorage);
    file.getMetaInfo()->putAndInsertString(DCM_MediaStorageSOPInstanceUID,
                                           dicom::test::makeTestUid().c_str());
    const OFCondition status = file.saveFile(OFFilename(path.c_str()), EXS_LittleEndianExplicit);
    ASSERT_TRUE(status.good()) << status.text();
}

void writeDcmtkDicomdir(const fs::path& root, const std::vector<std::string>& relativeFiles) {
    DicomDirInterface dir;
    dir.enableInventMode(OFTrue); // the test slices lack e.g. StudyDate, which the profile wants
    const fs::path dicomdir = root / "DICOMDIR";
    OFCondition status = dir.createNewDicomDir(DicomDirInterface::AP_GeneralPurpose,
                                               OFFilename(dicomdir.c_str()), "LWTEST");
    ASSERT_TRUE(status.good()) << status.text();
    for (const auto& file : relativeFiles) {
        status = dir.addDicomFile(OFFilename(file.c_str()), OFFilename(root.c_str()));
        ASSERT_TRUE(status.good()) << file << ": " << status.text();
    }
    status = dir.writeDicomDir();
    ASSERT_TRUE(status.good()) << status.text();
}

} // namespace

TEST(DicomScanner, NestedFoldersWithJunkGroupAndReportErrors) {
    test::TempDir dir;
    const auto studyUid = dicom::test::makeTestUid();
    writeSeries(dir / "a" / "b", newSeries(2, 3, studyUid));
    writeSeries(dir / "c", newSeries(1, 2, studyUid));
    writeText(dir / "README.txt", "not a DICOM file\n");
    writeText(dir / "c" / "empty.dcm", "");
    writeText(dir / "a" / "garbage.bin", std::string(4096, '\x5a'));

    const dicom::DicomIndex index = dicom::scanDicom(dir.path());
    EXPECT_FALSE(index.fromDicomdir);
    EXPECT_EQ(index.filesExamined, 8u);
    ASSERT_EQ(index.patients.size(), 1u);
    ASSERT_EQ(index.patients[0].studies.size(), 1u);
    EXPECT_EQ(index.seriesCount(), 2u);
    EXPECT_EQ(index.instanceCount(), 5u);

    // Series ordered by number, instances by InstanceNumber.
    const auto& series = index.patients[0].studies[0].series;
    EXPECT_EQ(series[0].seriesNumber, 1);
    EXPECT_EQ(series[0].instances.size(), 2u);
    EXPECT_EQ(series[1].seriesNumber, 2);
    ASSERT_EQ(series[1].instances.size(), 3u);
    for (int i = 0; i < 3; ++i)
        EXPECT_EQ(series[1].instances[i].instanceNumber, i + 1);
    EXPECT_EQ(index.findSeries(series[1].seriesInstanceUid), &series[1]);
    EXPECT_EQ(index.findSeries("1.2.3.does.not.exist"), nullptr);
    EXPECT_EQ(index.allSeries().size(), 2u);

    ASSERT_EQ(index.errors.size(), 3u);
    for (const char* junk : {"README.txt", "empty.dcm", "garbage.bin"}) {
        const auto* error = findError(index, junk);
        ASSERT_NE(error, nullptr) << junk;
        EXPECT_FALSE(error->reason.empty()) << junk;
    }
}

TEST(DicomScanner, GroupsPatientsStudiesAndDropsDuplicateObjects) {
    test::TempDir dir;
    SeriesSpec a = newSeries(1, 2);
    SeriesSpec b = newSeries(1, 1);
    SeriesSpec c = newSeries(3, 1);
    c.patientId = "P2";
    c.patientName = "Adams^Al";
    const auto aFiles = writeSeries(dir / "a", a);
    writeSeries(dir / "b", b);
    writeSeries(dir / "c", c);
    // The same object copied elsewhere: one instance, one warning.
    fs::create_directories(dir / "copy");
    fs::copy_file(aFiles[0], dir / "copy" / "IM1");

    const dicom::DicomIndex index = dicom::scanDicom(dir.path());
    ASSERT_EQ(index.patients.size(), 2u);
    // Sorted by name: Adams before Doe.
    EXPECT_EQ(index.patients[0].patientId, "P2");
    EXPECT_EQ(index.patients[0].name, "Adams^Al");
    EXPECT_EQ(index.patients[0].studies.size(), 1u);
    EXPECT_EQ(index.patients[1].patientId, "P1");
    EXPECT_EQ(index.patients[1].studies.size(), 2u);
    EXPECT_EQ(index.instanceCount(), 4u);
    EXPECT_TRUE(index.errors.empty());
    EXPECT_TRUE(anyWarningContains(index, "duplicate SOPInstanceUID"));

    // Same input, same order: nothing depends on thread timing.
    const dicom::DicomIndex again = dicom::scanDicom(dir.path());
    const auto first = index.allSeries();
    const auto second = again.allSeries();
    ASSERT_EQ(first.size(), second.size());
    for (std::size_t i = 0; i < first.size(); ++i) {
        EXPECT_EQ(first[i]->seriesInstanceUid, second[i]->seriesInstanceUid);
        ASSERT_EQ(first[i]->instances.size(), second[i]->instances.size());
        for (std::size_t k = 0; k < first[i]->instances.size(); ++k)
            EXPECT_EQ(first[i]->instances[k].path, second[i]->instances[k].path);
    }
}

TEST(DicomScanner, SingleFileAndInputChecks) {
    test::TempDir dir;
    const auto files = writeSeries(dir.path(), newSeries(7, 1));
    const dicom::DicomIndex index = dicom::scanDicom(files[0]);
    EXPECT_EQ(index.instanceCount(), 1u);
    EXPECT_EQ(index.filesExamined, 1u);
    EXPECT_EQ(index.allSeries()[0]->seriesNumber, 7);

    writeText(dir / "notes.txt", "hello");
    EXPECT_THROW(dicom::scanDicom(dir / "notes.txt"), core::Error);
    EXPECT_THROW(dicom::scanDicom(dir / "missing"), core::Error);

    EXPECT_TRUE(dicom::looksLikeDicomInput(dir.path()));
    EXPECT_TRUE(dicom::looksLikeDicomInput(files[0])); // no suffix: the DICM magic says it
    EXPECT_FALSE(dicom::looksLikeDicomInput(dir / "notes.txt"));
    EXPECT_FALSE(dicom::looksLikeDicomInput(dir / "missing"));
}

TEST(DicomScanner, SymlinkLoopDoesNotHang) {
    test::TempDir dir;
    writeSeries(dir / "s", newSeries(1, 2));
    std::error_code ec;
    fs::create_directory_symlink(dir.path(), dir / "s" / "loop", ec);
    if (ec)
        GTEST_SKIP() << "cannot create symlinks here: " << ec.message();
    const dicom::DicomIndex index = dicom::scanDicom(dir.path());
    EXPECT_EQ(index.instanceCount(), 2u);
}

TEST(DicomScanner, ProgressAndCancellation) {
    test::TempDir dir;
    writeSeries(dir.path(), newSeries(1, 6));

    double last = -1.0;
    core::Progress progress([&](double fraction, const std::string&) { last = fraction; });
    dicom::scanDicom(dir.path(), &progress);
    EXPECT_DOUBLE_EQ(last, 1.0);

    auto token = std::make_shared<core::CancelToken>();
    token->cancel();
    core::Progress cancelled([](double, const std::string&) {}, token);
    EXPECT_THROW(dicom::scanDicom(dir.path(), &cancelled), core::Cancelled);
}

TEST(DicomScanner, DicomdirFromDcmtkWithMissingFile) {
    test::TempDir dir;
    const auto studyUid = dicom::test::makeTestUid();
    writeSeries(dir / "SUB1", newSeries(1, 3, studyUid));
    writeSeries(dir / "SUB2", newSeries(2, 2, studyUid));
    writeDcmtkDicomdir(dir.path(), {"SUB1/IM1", "SUB1/IM2", "SUB1/IM3", "SUB2/IM1", "SUB2/IM2"});
    if (HasFatalFailure())
        return;
    fs::remove(dir / "SUB1" / "IM3");
    // Not referenced by the DICOMDIR, so not part of the file-set.
    writeSeries(dir / "SUB3", newSeries(3, 1, studyUid));

    const dicom::DicomIndex index = dicom::scanDicom(dir / "DICOMDIR");
    EXPECT_TRUE(index.fromDicomdir);
    EXPECT_EQ(index.seriesCount(), 2u);
    EXPECT_EQ(index.instanceCount(), 4u);
    EXPECT_EQ(index.filesExamined, 4u);
    ASSERT_EQ(index.errors.size(), 1u);
    EXPECT_EQ(fs::path(index.errors[0].file).filename(), "IM3");
    EXPECT_EQ(index.errors[0].reason, "referenced by DICOMDIR but missing");

    // A folder scan of the same tree skips the DICOMDIR itself (it holds no image).
    const dicom::DicomIndex folder = dicom::scanDicom(dir.path());
    EXPECT_EQ(folder.instanceCount(), 5u);
    EXPECT_TRUE(folder.errors.empty());
    EXPECT_TRUE(anyWarningContains(folder, "DICOMDIR"));
}

TEST(DicomScanner, DicomdirMatchesFileNamesCaseInsensitively) {
    test::TempDir dir;
    writeSeries(dir / "SUB1", newSeries(1, 2));
    writeDcmtkDicomdir(dir.path(), {"SUB1/IM1", "SUB1/IM2"});
    if (HasFatalFailure())
        return;
    // A CD copied onto a case-sensitive disk by a tool that lower-cased the names.
    fs::rename(dir / "SUB1" / "IM1", dir / "SUB1" / "im1");
    fs::rename(dir / "SUB1", dir / "sub1");
    const dicom::DicomIndex index = dicom::scanDicom(dir / "DICOMDIR");
    EXPECT_EQ(index.instanceCount(), 2u);
    EXPECT_TRUE(index.errors.empty()) << index.errors[0].file << ": " << index.errors[0].reason;
}

TEST(DicomScanner, DicomdirPathsMustStayInsideTheFileSet) {
    test::TempDir dir;
    const fs::path root = dir / "media";
    writeSeries(root / "SUB", newSeries(1, 1));
    writeSeries(dir / "OUTSIDE", newSeries(2, 1)); // exists, but outside the file-set
    // Reversed hierarchy and no offsets, as some writers produce.
    writeRawDicomdir(root / "DICOMDIR", {{"IMAGE", "..\\OUTSIDE\\IM1", "", ""},
                                         {"IMAGE", "SUB\\IM1", "", ""},
                                         {"IMAGE", "SUB\\..\\..\\OUTSIDE\\IM1", "", ""},
                                         {"SERIES", "", "", "1.2.3.4.5.6"},
                                         {"PATIENT", "", "", ""}});
    if (HasFatalFailure())
        return;
    const dicom::DicomIndex index = dicom::scanDicom(root / "DICOMDIR");
    EXPECT_EQ(index.instanceCount(), 1u);
    ASSERT_EQ(index.errors.size(), 2u);
    for (const auto& error : index.errors)
        EXPECT_NE(error.reason.find("leaves the file-set root"), std::string::npos) << error.reason;
    // The listed series 1.2.3.4.5.6 has no file: said once, not silently dropped.
    EXPECT_TRUE(anyWarningContains(index, "lists 1 series"));
}

// Issue 10, paths: a ReferencedFileID is relative to the file-set root. Absolute IDs (either
// separator), drive letters and links inside the file-set that point out of it are refused
// with the reason, and the file outside is never read, although it exists.
TEST(DicomScanner, DicomdirReferencesCannotEscapeByAbsolutePathsDrivesOrLinks) {
    test::TempDir dir;
    const fs::path root = dir / "media";
    writeSeries(root / "SUB", newSeries(1, 1));
    writeSeries(dir / "OUTSIDE", newSeries(2, 1));
    std::error_code ec;
    fs::create_directory_symlink(dir / "OUTSIDE", root / "LINKDIR", ec);
    if (!ec)
        fs::create_symlink(dir / "OUTSIDE" / "IM1", root / "SUB" / "LINKFILE", ec);
    if (ec)
        GTEST_SKIP() << "cannot create symlinks here: " << ec.message();
    const std::string outside = (dir / "OUTSIDE" / "IM1").string();
    writeRawDicomdir(root / "DICOMDIR", {{"IMAGE", "\\OUTSIDE\\IM1", "", ""},
                                         {"IMAGE", outside, "", ""},
                                         {"IMAGE", "C:\\OUTSIDE\\IM1", "", ""},
                                         {"IMAGE", "C:OUTSIDE\\IM1", "", ""},
                                         {"IMAGE", "LINKDIR\\IM1", "", ""},
                                         {"IMAGE", "SUB\\LINKFILE", "", ""},
                                         {"IMAGE", "SUB\\IM1", "", ""}});
    if (HasFatalFailure())
        return;
    const dicom::DicomIndex index = dicom::scanDicom(root / "DICOMDIR");
    EXPECT_EQ(index.instanceCount(), 1u); // SUB/IM1 only
    int refusedIds = 0, refusedLinks = 0;
    for (const auto& error : index.errors) {
        refusedIds += error.reason.find("leaves the file-set root") != std::string::npos;
        refusedLinks += error.reason.find("through a link) outside") != std::string::npos;
    }
    EXPECT_EQ(refusedIds, 4);
    EXPECT_EQ(refusedLinks, 2);
    EXPECT_EQ(index.errors.size(), 6u);
}

TEST(DicomScanner, NestedDicomdirsAreFollowedOnceEvenInACycle) {
    test::TempDir dir;
    writeSeries(dir / "S1" / "SER", newSeries(1, 2));
    writeSeries(dir / "S2", newSeries(2, 1));
    const std::string dirClass = UID_MediaStorageDirectoryStorage;
    // Root -> S1/DIRFILE (paths relative to the root, as Philips writes them) -> images and,
    // to make a cycle, the root DICOMDIR again.
    writeRawDicomdir(dir / "DICOMDIR", {{"STUDY", "S1\\DIRFILE", dirClass, ""},
                                        {"IMAGE", "S2\\IM1", "", ""},
                                        {"STUDY", "S9\\DIRFILE", dirClass, ""}});
    writeRawDicomdir(dir / "S1" / "DIRFILE", {{"IMAGE", "S1\\SER\\IM1", "", ""},
                                              {"IMAGE", "SER\\IM2", "", ""}, // relative to DIRFILE
                                              {"STUDY", "DICOMDIR", dirClass, ""}});
    if (HasFatalFailure())
        return;
    const dicom::DicomIndex index = dicom::scanDicom(dir / "DICOMDIR");
    EXPECT_EQ(index.seriesCount(), 2u);
    EXPECT_EQ(index.instanceCount(), 3u);
    ASSERT_EQ(index.errors.size(), 1u); // S9/DIRFILE
    EXPECT_EQ(index.errors[0].reason, "referenced by DICOMDIR but missing");
    EXPECT_TRUE(anyWarningContains(index, "cycle"));
}

TEST(DicomScanner, EmptyDicomdirGivesAnEmptyIndex) {
    test::TempDir dir;
    writeRawDicomdir(dir / "DICOMDIR", {});
    if (HasFatalFailure())
        return;
    const dicom::DicomIndex index = dicom::scanDicom(dir / "DICOMDIR");
    EXPECT_TRUE(index.fromDicomdir);
    EXPECT_EQ(index.seriesCount(), 0u);
    EXPECT_TRUE(index.errors.empty());
    EXPECT_TRUE(anyWarningContains(index, "no directory records"));
}

TEST(DicomScanner, ScanDicomFilesReadsExactlyTheseFiles) {
    test::TempDir dir;
    const SeriesSpec spec = newSeries(4, 4);
    std::vector<fs::path> files = writeSeries(dir / "s", spec);
    // A second series in the same folder that the list does not name: it must stay out.
    writeSeries(dir / "s", newSeries(5, 2), "OTHER");
    writeText(dir / "s" / "junk.dcm", "not DICOM");
    files.push_back(dir / "s" / "junk.dcm");
    files.push_back(dir / "s" / "gone.dcm");
    std::reverse(files.begin(), files.end()); // caller order does not matter

    double last = -1.0;
    core::Progress progress([&](double fraction, const std::string&) { last = fraction; });
    const dicom::DicomIndex index = dicom::scanDicomFiles(files, &progress);
    EXPECT_DOUBLE_EQ(last, 1.0);
    EXPECT_EQ(index.filesExamined, files.size());
    ASSERT_EQ(index.seriesCount(), 1u);
    const dicom::SeriesInfo* series = index.findSeries(spec.seriesUid);
    ASSERT_NE(series, nullptr);
    ASSERT_EQ(series->instances.size(), 4u);
    for (int i = 0; i < 4; ++i)
        EXPECT_EQ(series->instances[std::size_t(i)].instanceNumber, i + 1);

    ASSERT_EQ(index.errors.size(), 2u);
    const auto* missing = findError(index, "gone.dcm");
    ASSERT_NE(missing, nullptr);
    EXPECT_EQ(missing->reason, "file is missing");
    const auto* junk = findError(index, "junk.dcm");
    ASSERT_NE(junk, nullptr);
    EXPECT_FALSE(junk->reason.empty());
}

TEST(DicomScanner, ScanDicomFilesEmptyListAndCancellation) {
    const dicom::DicomIndex empty = dicom::scanDicomFiles({});
    EXPECT_EQ(empty.seriesCount(), 0u);
    EXPECT_TRUE(empty.errors.empty());

    test::TempDir dir;
    const auto files = writeSeries(dir.path(), newSeries(1, 6));
    auto token = std::make_shared<core::CancelToken>();
    token->cancel();
    core::Progress cancelled([](double, const std::string&) {}, token);
    EXPECT_THROW(dicom::scanDicomFiles(files, &cancelled), core::Cancelled);
}

namespace {

// DirectoryRecordType (0004,1430) is CS, at most 16 characters. A record type whose length is
// enlarged beyond that (a fuzzer found one of 64 bytes) makes DCMTK's own check of the value
// throw std::out_of_range from inside its parser (issue 10).
const std::string kOverlongRecordType = "PATIENT" + std::string(57, 'X');

} // namespace

TEST(DicomScanner, DamagedDicomdirRecordBecomesCoreError) {
    test::TempDir dir;
    writeSeries(dir / "S1", newSeries(1, 2));
    writeRawDicomdir(dir / "DICOMDIR",
                     {{kOverlongRecordType, "", "", ""}, {"IMAGE", "S1\\IM1", "", ""}});
    if (HasFatalFailure())
        return;
    // The DICOMDIR is the whole input: the scan fails, with core::Error naming it and never
    // with the library's own exception type.
    try {
        (void)dicom::scanDicom(dir / "DICOMDIR");
        ADD_FAILURE() << "a damaged DICOMDIR was accepted";
    } catch (const core::Error& error) {
        EXPECT_EQ(fs::path(error.subject()).filename(), "DICOMDIR");
        EXPECT_NE(error.reason().find("damaged DICOMDIR"), std::string::npos) << error.reason();
    } catch (const std::exception& other) {
        ADD_FAILURE() << "escaped exception: " << other.what();
    }
    EXPECT_NO_THROW((void)dicom::looksLikeDicomInput(dir / "DICOMDIR"));
}

// A top-level DICOMDIR cut off inside its last record (a copy that stopped short): the records
// DCMTK parsed before the cut are used, the one it stopped in is not.
TEST(DicomScanner, TruncatedTopLevelDicomdirKeepsTheWholeRecords) {
    test::TempDir dir;
    const SeriesSpec first = newSeries(1, 2);
    writeSeries(dir / "S1", first);
    writeSeries(dir / "S2", newSeries(2, 1));
    writeRawDicomdir(
        dir / "DICOMDIR",
        {{"IMAGE", "S1\\IM1", "", ""}, {"IMAGE", "S1\\IM2", "", ""}, {"IMAGE", "S2\\IM1", "", ""}});
    if (HasFatalFailure())
        return;
    fs::resize_file(dir / "DICOMDIR", fs::file_size(dir / "DICOMDIR") - 6);
    const dicom::DicomIndex index = dicom::scanDicom(dir / "DICOMDIR");
    EXPECT_EQ(index.instanceCount(), 2u);
    EXPECT_NE(index.findSeries(first.seriesUid), nullptr);
    const dicom::FileError* error = findError(index, "DICOMDIR");
    ASSERT_NE(error, nullptr);
    EXPECT_NE(error->reason.find("the 2 records before the damage are used"), std::string::npos)
        << error->reason;
}

TEST(DicomScanner, DamagedNestedDicomdirIsReportedAndTheRestScanned) {
    test::TempDir dir;
    writeSeries(dir / "S1", newSeries(1, 2));
    writeSeries(dir / "S2", newSeries(2, 1));
    const std::string dirClass = UID_MediaStorageDirectoryStorage;
    writeRawDicomdir(dir / "DICOMDIR",
                     {{"STUDY", "S1\\DIRFILE", dirClass, ""}, {"IMAGE", "S2\\IM1", "", ""}});
    writeRawDicomdir(dir / "S1" / "DIRFILE",
                     {{kOverlongRecordType, "", "", ""}, {"IMAGE", "S1\\IM1", "", ""}});
    if (HasFatalFailure())
        return;
    const dicom::DicomIndex index = dicom::scanDicom(dir / "DICOMDIR");
    EXPECT_EQ(index.instanceCount(), 1u); // S2/IM1
    const dicom::FileError* error = findError(index, "DIRFILE");
    ASSERT_NE(error, nullptr);
    EXPECT_NE(error->reason.find("damaged DICOMDIR"), std::string::npos) << error->reason;
}
