#pragma once

// A real Orthanc (Debian's `orthanc`) for the PACS tests: its own process group, a temporary
// JSON configuration on free loopback ports, a temporary storage folder, known AE titles and
// DicomCheckCalledAet on. The constructor returns once Orthanc answers on HTTP (/system) and
// DICOM (a C-ECHO); the destructor stops it (SIGTERM to the group, SIGKILL if it lingers).
//
// Orthanc 1.10 has no option to bind its DICOM port to one address: it listens on every
// interface, so the configuration accepts only the AE titles below, from 127.0.0.1
// (DicomCheckModalityHost), and nothing from unknown AE titles (echo and store included).
// HTTP answers loopback only (RemoteAccessAllowed false).
#include "lw/pacs/pacs_client.h"
#include "lw/pacs/pacs_node.h"
#include "test_support.h"

#include <cstdint>
#include <filesystem>
#include <gtest/gtest.h>
#include <memory>
#include <optional>
#include <string>
#include <sys/types.h>
#include <vector>

namespace lw::pacs::test {

// The workstation's AE title the tests call with; Orthanc lists it as a modality.
inline constexpr const char* kWorkstationAet = "LW_TEST_WS";
inline constexpr const char* kOrthancAet = "LW_ORTHANC";

// Orthanc's binary (PATH, then /usr/sbin), or nothing when it is not installed.
std::optional<std::filesystem::path> orthancBinary();

// A TCP port on 127.0.0.1 that nothing listens on right now.
std::uint16_t freeLoopbackPort();

struct HttpReply {
    int status = 0;
    std::string body;
};

class OrthancServer {
public:
    // `workstationStoragePort`: where the workstation's storage SCP would listen (C-MOVE).
    explicit OrthancServer(std::uint16_t workstationStoragePort = 0);
    ~OrthancServer();
    OrthancServer(const OrthancServer&) = delete;
    OrthancServer& operator=(const OrthancServer&) = delete;

    PacsNode node() const { return {"orthanc", kOrthancAet, "127.0.0.1", m_dicomPort}; }
    std::uint16_t dicomPort() const { return m_dicomPort; }
    std::uint16_t httpPort() const { return m_httpPort; }

    HttpReply http(const std::string& method, const std::string& path,
                   const std::string& body = {}) const;
    // POST /instances; returns Orthanc's ID of the instance. Fails the test on refusal.
    std::string upload(const std::filesystem::path& file) const;
    // Orthanc's REST path of the instance with that SOP Instance UID ("/instances/ID"), or ""
    // when it has none.
    std::string instancePath(const std::string& sopInstanceUid) const;
    // A string attribute of a study, series or instance ("/instances/ID") as Orthanc stored it
    // (its simplified tags, by keyword: "StudyInstanceUID"), or "" when it has none.
    std::string tag(const std::string& resourcePath, const std::string& keyword) const;
    // Orthanc's series of the study with that Study Instance UID, as its REST API lists them
    // (GET /studies/ID/series: JSON, one object per series with its "MainDicomTags"), or "".
    std::string seriesOfStudy(const std::string& studyInstanceUid) const;
    // Orthanc's log so far (for a failing test's message).
    std::string log() const;

private:
    void start();
    void waitUntilAnswering();
    void stop();

    lw::test::TempDir m_folder;
    std::uint16_t m_dicomPort = 0;
    std::uint16_t m_httpPort = 0;
    pid_t m_pid = -1;
};

// A synthetic uncompressed CT series (the tests' DICOM writer), `slices` files in `folder`;
// returns their paths. Every slice has its own pixels (a ramp offset by the slice).
struct SyntheticSeries {
    std::string studyUid;
    std::string seriesUid;
    std::vector<std::filesystem::path> files;
};
SyntheticSeries writeCtSeries(const std::filesystem::path& folder, int slices, int size,
                              const std::string& studyUid = {});

// A suite's Orthanc, started once for the suite and seeded with one study of two synthetic CT
// series (6 and 3 slices of 32x32) through its REST API; stopped after the suite. It lists the
// workstation's AE title at 127.0.0.1:storagePort() (C-MOVE's destination).
class OrthancSuite : public testing::Test {
protected:
    static void SetUpTestSuite();
    static void TearDownTestSuite();
    static OrthancServer& server() { return *s_server; }
    static const SyntheticSeries& first() { return *s_first; }
    static const SyntheticSeries& second() { return *s_second; }
    static CallOptions options() { return {kWorkstationAet, std::chrono::seconds(10)}; }
    // Where Orthanc sends C-MOVE's instances: the workstation's storage SCP, free when started.
    static std::uint16_t storagePort() { return s_storagePort; }

private:
    // Per suite, set up and torn down by gtest on one thread (not shared across suites).
    static inline std::unique_ptr<lw::test::TempDir> s_files;
    static inline std::unique_ptr<OrthancServer> s_server;
    static inline std::unique_ptr<SyntheticSeries> s_first, s_second;
    static inline std::uint16_t s_storagePort = 0;
};

} // namespace lw::pacs::test
