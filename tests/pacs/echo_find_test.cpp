// C-ECHO and C-FIND through modules/pacs against a real Orthanc, and each way an echo fails.
#include "lw/core/error.h"
#include "orthanc_server.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

namespace lw::pacs::test {
namespace {

using OrthancEcho = OrthancSuite;
using OrthancFind = OrthancSuite;

TEST_F(OrthancEcho, Accepted) {
    const EchoResult result = echo(server().node(), options());
    EXPECT_TRUE(result.ok) << result.message;
    EXPECT_EQ(result.message, "accepted");
}

TEST_F(OrthancEcho, RefusedWhenNothingListens) {
    PacsNode node = server().node();
    node.port = freeLoopbackPort();
    const EchoResult result = echo(node, options());
    ASSERT_FALSE(result.ok);
    EXPECT_EQ(result.failure, PacsFailure::ConnectionRefused);
    EXPECT_NE(result.message.find("connection refused"), std::string::npos) << result.message;
}

TEST_F(OrthancEcho, CalledAeTitleNotRecognised) {
    PacsNode node = server().node();
    node.calledAet = "NOT_ORTHANC";
    const EchoResult result = echo(node, options());
    ASSERT_FALSE(result.ok);
    EXPECT_EQ(result.failure, PacsFailure::CalledAeRejected) << result.message;
    EXPECT_NE(result.message.find("NOT_ORTHANC"), std::string::npos) << result.message;
}

// With DicomCheckModalityHost on, Orthanc rejects the association of an AE title it does not
// list (without it, it accepts the association and aborts the request: PacsFailure::Aborted).
TEST_F(OrthancEcho, UnknownCallingAeTitleIsRejected) {
    const EchoResult result = echo(server().node(), {"STRANGER", std::chrono::seconds(10)});
    ASSERT_FALSE(result.ok);
    EXPECT_EQ(result.failure, PacsFailure::CallingAeRejected) << result.message;
    EXPECT_NE(result.message.find("STRANGER"), std::string::npos) << result.message;
}

// A socket that listens but never answers: the kernel completes the connection, no A-ASSOCIATE
// reply ever comes.
TEST_F(OrthancEcho, TimesOutWhenThePeerNeverAnswers) {
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t length = sizeof address;
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    ASSERT_EQ(::listen(fd, 4), 0);
    ASSERT_EQ(::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length), 0);
    const PacsNode silent{"silent", "SILENT", "127.0.0.1", ntohs(address.sin_port)};
    const EchoResult result = echo(silent, {kWorkstationAet, std::chrono::seconds(1)});
    ::close(fd);
    ASSERT_FALSE(result.ok);
    EXPECT_EQ(result.failure, PacsFailure::TimedOut) << result.message;
}

TEST_F(OrthancFind, StudiesByPatientIdModalityAndName) {
    StudyQuery query;
    query.patientId = "LW-TEST";
    query.modality = "CT";
    const std::vector<StudyRecord> studies = findStudies(server().node(), query, options());
    ASSERT_EQ(studies.size(), 1u);
    EXPECT_EQ(studies[0].studyInstanceUid, first().studyUid);
    EXPECT_EQ(studies[0].patientName, "Test^Linework");
    EXPECT_EQ(studies[0].numberOfInstances, 9);
    query.modality = "MR";
    EXPECT_TRUE(findStudies(server().node(), query, options()).empty());
    query = {};
    query.patientName = "Nobody*";
    EXPECT_TRUE(findStudies(server().node(), query, options()).empty());
}

TEST_F(OrthancFind, SeriesOfAStudyAndTheirInstances) {
    const std::vector<SeriesRecord> series =
        findSeries(server().node(), first().studyUid, options());
    ASSERT_EQ(series.size(), 2u);
    for (const SeriesRecord& s : series)
        EXPECT_EQ(s.numberOfInstances, s.seriesInstanceUid == first().seriesUid ? 6 : 3)
            << s.seriesInstanceUid;
    EXPECT_EQ(
        findInstances(server().node(), first().studyUid, second().seriesUid, options()).size(), 3u);
    EXPECT_EQ(findInstances(server().node(), first().studyUid, "", options()).size(), 9u);
}

TEST_F(OrthancFind, CancelSendsCancelAndThrowsCancelled) {
    core::CancelToken cancel;
    cancel.cancel();
    EXPECT_THROW(findInstances(server().node(), first().studyUid, "", options(), &cancel),
                 core::Cancelled);
    // The association ended cleanly: the next query works.
    EXPECT_EQ(findInstances(server().node(), first().studyUid, "", options()).size(), 9u);
}

TEST_F(OrthancFind, DateRangeParsing) {
    EXPECT_EQ(parseDateRange("20200101-20201231"),
              std::make_pair(std::string("20200101"), std::string("20201231")));
    EXPECT_EQ(parseDateRange("-20201231").first, "");
    EXPECT_EQ(parseDateRange("20200101").second, "20200101");
    EXPECT_THROW(parseDateRange("2020-01-01"), core::Error);
}

} // namespace
} // namespace lw::pacs::test
