// C-GET into the managed store against a real Orthanc: everything arrives, nothing twice, only
// what is missing after files were lost or a retrieve was cancelled, and a full disk refused.
#include "lw/core/file_util.h"
#include "lw/pacs/retrieve.h"
#include "orthanc_server.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>

namespace lw::pacs::test {
namespace {

namespace fs = std::filesystem;
class OrthancRetrieve : public OrthancSuite {
protected:
    // C-MOVE of the first series with the storage SCP listening on `port`.
    static RetrieveRequest moveRequest(const fs::path& store, std::uint16_t port) {
        RetrieveRequest request{first().studyUid, first().seriesUid, store};
        request.method = RetrieveMethod::Move;
        request.storagePort = port;
        return request;
    }
};

std::string sopInstanceUid(const fs::path& file) {
    DcmFileFormat dicom;
    if (dicom.loadFile(file.c_str()).bad())
        return "unreadable";
    OFString uid;
    dicom.getDataset()->findAndGetOFString(DCM_SOPInstanceUID, uid);
    return uid.c_str();
}

std::size_t countFiles(const fs::path& folder, const std::string& extension) {
    std::size_t count = 0;
    if (fs::exists(folder))
        for (const auto& entry : fs::recursive_directory_iterator(folder))
            count += entry.path().extension() == extension;
    return count;
}

TEST_F(OrthancRetrieve, SeriesArrivesWholeThenNothingTwice) {
    lw::test::TempDir store;
    const RetrieveRequest request{first().studyUid, first().seriesUid, store.path()};
    std::vector<RetrieveProgress> progress;
    const RetrieveResult result =
        retrieve(server().node(), request, options(),
                 [&](const RetrieveProgress& p) { progress.push_back(p); });
    EXPECT_TRUE(result.message.empty()) << result.message;
    EXPECT_EQ(result.instances, 6u);
    EXPECT_EQ(result.transferred, 6u);
    EXPECT_EQ(result.skipped, 0u);
    ASSERT_EQ(result.files.size(), 6u);
    ASSERT_EQ(progress.size(), 6u);
    EXPECT_EQ(progress.back().done, 6u);
    EXPECT_EQ(progress.back().toTransfer, 6u);
    for (const fs::path& file : result.files) // named by the SOP Instance UID it holds
        EXPECT_EQ(sopInstanceUid(file) + ".dcm", file.filename().string());
    EXPECT_EQ(countFiles(store.path(), ".part"), 0u);

    const RetrieveResult again = retrieve(server().node(), request, options());
    EXPECT_EQ(again.transferred, 0u);
    EXPECT_EQ(again.skipped, 6u);
    EXPECT_TRUE(again.complete());
}

TEST_F(OrthancRetrieve, OnlyTheMissingInstancesComeAgain) {
    lw::test::TempDir store;
    const RetrieveRequest request{first().studyUid, "", store.path()};
    const RetrieveResult whole = retrieve(server().node(), request, options());
    ASSERT_EQ(whole.transferred, 9u) << whole.message;
    fs::remove(whole.files[1]);
    fs::remove(whole.files[7]); // one of each series
    const RetrieveResult again = retrieve(server().node(), request, options());
    EXPECT_EQ(again.transferred, 2u) << again.message;
    EXPECT_EQ(again.skipped, 7u);
    EXPECT_TRUE(fs::exists(whole.files[1]));
    EXPECT_TRUE(fs::exists(whole.files[7]));
}

TEST_F(OrthancRetrieve, CancelKeepsWholeFilesAndTheNextRetrieveResumes) {
    lw::test::TempDir store;
    const RetrieveRequest request{first().studyUid, first().seriesUid, store.path()};
    core::CancelToken cancel;
    const RetrieveResult cancelled = retrieve(
        server().node(), request, options(),
        [&](const RetrieveProgress& p) {
            if (p.done == 2)
                cancel.cancel();
        },
        &cancel);
    EXPECT_TRUE(cancelled.cancelled);
    EXPECT_FALSE(cancelled.complete());
    EXPECT_GE(cancelled.transferred, 2u);
    EXPECT_LT(cancelled.transferred, 6u) << "the cancel did not stop the transfer";
    EXPECT_EQ(countFiles(store.path(), ".dcm"), cancelled.transferred);
    EXPECT_EQ(countFiles(store.path(), ".part"), 0u);

    const RetrieveResult resumed = retrieve(server().node(), request, options());
    EXPECT_TRUE(resumed.complete()) << resumed.message;
    EXPECT_EQ(resumed.skipped, cancelled.transferred);
    EXPECT_EQ(resumed.transferred, 6u - cancelled.transferred);
}

TEST_F(OrthancRetrieve, NotEnoughDiskSpaceRefusesBeforeTransferring) {
    lw::test::TempDir store;
    RetrieveRequest request{first().studyUid, first().seriesUid, store.path()};
    request.reserveBytes = std::uint64_t(1) << 62; // more than any disk has
    try {
        retrieve(server().node(), request, options());
        FAIL() << "retrieve started without the space it needs";
    } catch (const PacsError& error) {
        EXPECT_EQ(error.kind(), PacsFailure::DiskFull);
        EXPECT_NE(error.reason().find("not enough disk space"), std::string::npos) << error.what();
    }
    EXPECT_EQ(countFiles(store.path(), ".dcm"), 0u);
}

TEST_F(OrthancRetrieve, MoveDeliversToTheStorageScpAndResumes) {
    lw::test::TempDir store;
    const RetrieveRequest request = moveRequest(store.path(), storagePort());
    std::size_t reported = 0;
    const RetrieveResult result =
        retrieve(server().node(), request, options(), [&](const RetrieveProgress&) { ++reported; });
    EXPECT_TRUE(result.message.empty()) << result.message;
    EXPECT_EQ(result.transferred, 6u);
    EXPECT_EQ(reported, 6u);
    ASSERT_EQ(result.files.size(), 6u);
    for (const fs::path& file : result.files)
        EXPECT_EQ(sopInstanceUid(file) + ".dcm", file.filename().string());
    fs::remove(result.files[2]);
    const RetrieveResult again = retrieve(server().node(), request, options());
    EXPECT_EQ(again.transferred, 1u) << again.message;
    EXPECT_EQ(again.skipped, 5u);
}

// Orthanc sends to the port it lists for the workstation; nothing listens there.
TEST_F(OrthancRetrieve, MoveToAStorageScpThePacsCannotReachSaysSo) {
    lw::test::TempDir store;
    const RetrieveRequest request = moveRequest(store.path(), freeLoopbackPort()); // not Orthanc's
    const RetrieveResult result = retrieve(server().node(), request, options());
    EXPECT_EQ(result.transferred, 0u);
    EXPECT_FALSE(result.complete());
    EXPECT_NE(result.message.find("C-MOVE"), std::string::npos) << result.message;
    EXPECT_EQ(countFiles(store.path(), ".dcm"), 0u);
}

// The calling AE title is the move destination too; Orthanc does not know this one.
TEST_F(OrthancRetrieve, MoveWithAnUnknownCallingAeTitleIsRejected) {
    lw::test::TempDir store;
    const RetrieveRequest request = moveRequest(store.path(), storagePort());
    try {
        retrieve(server().node(), request, {"STRANGER", std::chrono::seconds(10)});
        FAIL() << "an unknown AE title retrieved";
    } catch (const PacsError& error) {
        EXPECT_EQ(error.kind(), PacsFailure::CallingAeRejected) << error.what();
        EXPECT_NE(error.reason().find("STRANGER"), std::string::npos) << error.what();
    }
}

TEST(OrthancStopped, RetrieveSaysConnectionRefused) {
    if (!orthancBinary())
        GTEST_SKIP() << "Orthanc is not installed";
    PacsNode node;
    {
        OrthancServer server;
        node = server.node();
    } // stopped here
    lw::test::TempDir store;
    try {
        retrieve(node, {"1.2.3", "", store.path()}, {kWorkstationAet, std::chrono::seconds(5)});
        FAIL() << "retrieve from a stopped Orthanc did not fail";
    } catch (const PacsError& error) {
        EXPECT_EQ(error.kind(), PacsFailure::ConnectionRefused) << error.what();
    }
}

} // namespace
} // namespace lw::pacs::test
