#include "orthanc_server.h"

#include "dicom_test_writer.h"
#include "lw/core/file_util.h"
#include "lw/pacs/pacs_client.h"

#include <arpa/inet.h>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fcntl.h>
#include <fstream>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sstream>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

namespace lw::pacs::test {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr auto kStartDeadline = std::chrono::seconds(60);
constexpr auto kStopDeadline = std::chrono::seconds(20);

class Socket {
public:
    Socket() : m_fd(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)) {}
    ~Socket() {
        if (m_fd >= 0)
            ::close(m_fd);
    }
    Socket(const Socket&) = delete;
    Socket& operator=(const Socket&) = delete;
    int fd() const { return m_fd; }

private:
    int m_fd;
};

sockaddr_in loopback(std::uint16_t port) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    return address;
}

bool sendAll(int fd, const std::string& data) {
    for (std::size_t sent = 0; sent < data.size();) {
        const ssize_t n = ::send(fd, data.data() + sent, data.size() - sent, MSG_NOSIGNAL);
        if (n <= 0)
            return false;
        sent += std::size_t(n);
    }
    return true;
}

// Built with a stream: GCC 12 warns falsely (-Wrestrict) on a long chain of string additions.
std::string configuration(const fs::path& storage, std::uint16_t dicomPort, std::uint16_t httpPort,
                          std::uint16_t workstationPort) {
    std::ostringstream json;
    json << R"({ "Name": "linework-test", "StorageDirectory": ")" << storage.string()
         << R"(", "IndexDirectory": ")" << storage.string() << R"(", "DicomAet": ")" << kOrthancAet
         << R"(", "DicomPort": )" << dicomPort << R"(, "HttpPort": )" << httpPort
         << R"(, "RemoteAccessAllowed": false, "AuthenticationEnabled": false,
  "DicomCheckCalledAet": true, "DicomCheckModalityHost": true,
  "DicomAlwaysAllowEcho": false, "DicomAlwaysAllowStore": false,
  "DicomModalities": { "workstation": [")"
         << kWorkstationAet << R"(", "127.0.0.1", )" << (workstationPort ? workstationPort : 104)
         << R"(] },
  "Plugins": [], "LuaScripts": [], "StableAge": 1, "ConcurrentJobs": 2,
  "DicomScpTimeout": 30, "SaveJobs": false })";
    return json.str();
}

} // namespace

std::optional<fs::path> orthancBinary() {
    if (const char* path = std::getenv("PATH")) {
        std::string paths = path;
        for (std::size_t start = 0; start <= paths.size();) {
            const std::size_t end = std::min(paths.find(':', start), paths.size());
            const fs::path candidate = fs::path(paths.substr(start, end - start)) / "Orthanc";
            if (::access(candidate.c_str(), X_OK) == 0)
                return candidate;
            start = end + 1;
        }
    }
    if (::access("/usr/sbin/Orthanc", X_OK) == 0)
        return fs::path("/usr/sbin/Orthanc");
    return std::nullopt;
}

std::uint16_t freeLoopbackPort() {
    Socket socket;
    sockaddr_in address = loopback(0);
    socklen_t length = sizeof address;
    if (::bind(socket.fd(), reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
        ::getsockname(socket.fd(), reinterpret_cast<sockaddr*>(&address), &length) != 0)
        throw std::runtime_error("cannot find a free loopback port");
    return ntohs(address.sin_port);
}

OrthancServer::OrthancServer(std::uint16_t workstationStoragePort) {
    m_dicomPort = freeLoopbackPort();
    m_httpPort = freeLoopbackPort();
    fs::create_directories(m_folder / "storage");
    const std::string config =
        configuration(m_folder / "storage", m_dicomPort, m_httpPort, workstationStoragePort);
    core::writeFileAtomically(m_folder / "orthanc.json", config.data(), config.size());
    start();
    try {
        waitUntilAnswering();
    } catch (...) {
        stop();
        throw;
    }
}

OrthancServer::~OrthancServer() {
    stop();
}

void OrthancServer::start() {
    const std::optional<fs::path> binary = orthancBinary();
    if (!binary)
        throw std::runtime_error("Orthanc is not installed");
    const fs::path logFile = m_folder / "orthanc.log";
    const fs::path config = m_folder / "orthanc.json";
    const pid_t test = ::getpid();
    m_pid = ::fork();
    if (m_pid < 0)
        throw std::runtime_error("fork failed");
    if (m_pid == 0) {
        ::setpgid(0, 0); // its own group: stopping it stops whatever it started
        // A test binary that crashes or is killed runs no destructor: Orthanc goes with it.
        ::prctl(PR_SET_PDEATHSIG, SIGTERM);
        if (::getppid() != test)
            ::_exit(1);
        const int out = ::open(logFile.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
        ::dup2(out, STDOUT_FILENO);
        ::dup2(out, STDERR_FILENO);
        ::execl(binary->c_str(), "Orthanc", config.c_str(), static_cast<char*>(nullptr));
        ::_exit(127);
    }
    ::setpgid(m_pid, m_pid);
}

// Waits for the event, not a time: each round tries HTTP /system and then a C-ECHO, and
// fails at once when the process died.
void OrthancServer::waitUntilAnswering() {
    const auto deadline = Clock::now() + kStartDeadline;
    auto pause = std::chrono::milliseconds(5);
    while (Clock::now() < deadline) {
        int status = 0;
        if (::waitpid(m_pid, &status, WNOHANG) == m_pid) {
            m_pid = -1;
            throw std::runtime_error("Orthanc exited while starting; its log:\n" + log());
        }
        if (http("GET", "/system").status == 200 &&
            pacs::echo(node(), {kWorkstationAet, std::chrono::seconds(5)}).ok)
            return;
        std::this_thread::sleep_for(pause); // between polls only; the loop ends on the answer
        pause = std::min(pause * 2, std::chrono::milliseconds(200));
    }
    throw std::runtime_error("Orthanc did not answer within 60 s; its log:\n" + log());
}

void OrthancServer::stop() {
    if (m_pid <= 0)
        return;
    ::kill(-m_pid, SIGTERM);
    const auto deadline = Clock::now() + kStopDeadline;
    int status = 0;
    while (::waitpid(m_pid, &status, WNOHANG) == 0) {
        if (Clock::now() > deadline) {
            ::kill(-m_pid, SIGKILL);
            ::waitpid(m_pid, &status, 0);
            break;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    m_pid = -1;
}

HttpReply OrthancServer::http(const std::string& method, const std::string& path,
                              const std::string& body) const {
    Socket socket;
    const sockaddr_in address = loopback(m_httpPort);
    if (::connect(socket.fd(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0)
        return {};
    const std::string request =
        method + " " + path + " HTTP/1.0\r\nHost: 127.0.0.1\r\nConnection: close\r\n" +
        "Content-Length: " + std::to_string(body.size()) + "\r\n\r\n" + body;
    if (!sendAll(socket.fd(), request))
        return {};
    std::string reply;
    char buffer[65536];
    for (ssize_t n; (n = ::recv(socket.fd(), buffer, sizeof buffer, 0)) > 0;)
        reply.append(buffer, std::size_t(n));
    const std::size_t headerEnd = reply.find("\r\n\r\n");
    if (reply.compare(0, 5, "HTTP/") != 0 || headerEnd == std::string::npos)
        return {};
    return {std::atoi(reply.c_str() + reply.find(' ') + 1), reply.substr(headerEnd + 4)};
}

namespace {

// The string value after `"key"` in Orthanc's JSON (its REST answers are flat enough for this).
std::string stringAfterKey(const std::string& body, const std::string& key) {
    const std::size_t at = body.find("\"" + key + "\"");
    if (at == std::string::npos)
        return {};
    const std::size_t open = body.find('"', body.find(':', at) + 1);
    return body.substr(open + 1, body.find('"', open + 1) - open - 1);
}

} // namespace

std::string OrthancServer::upload(const fs::path& file) const {
    const HttpReply reply = http("POST", "/instances", core::readFileText(file));
    EXPECT_EQ(reply.status, 200) << "POST /instances of " << file << ": " << reply.body;
    return stringAfterKey(reply.body, "ID");
}

std::string OrthancServer::instancePath(const std::string& sopInstanceUid) const {
    const HttpReply found = http("POST", "/tools/lookup", sopInstanceUid);
    if (found.status != 200 || found.body.find("\"Instance\"") == std::string::npos)
        return {};
    return stringAfterKey(found.body, "Path");
}

std::string OrthancServer::tag(const std::string& resourcePath, const std::string& keyword) const {
    const HttpReply tags = http("GET", resourcePath + "/simplified-tags");
    return tags.status == 200 ? stringAfterKey(tags.body, keyword) : std::string();
}

std::string OrthancServer::seriesOfStudy(const std::string& studyInstanceUid) const {
    const HttpReply found = http("POST", "/tools/lookup", studyInstanceUid);
    if (found.status != 200 || found.body.find("\"Study\"") == std::string::npos)
        return {};
    return http("GET", stringAfterKey(found.body, "Path") + "/series").body;
}

std::string OrthancServer::log() const {
    try {
        return core::readFileText(m_folder / "orthanc.log");
    } catch (const std::exception& error) {
        return error.what();
    }
}

SyntheticSeries writeCtSeries(const fs::path& folder, int slices, int size,
                              const std::string& studyUid) {
    SyntheticSeries series{
        studyUid.empty() ? dicom::test::makeTestUid() : studyUid, dicom::test::makeTestUid(), {}};
    fs::create_directories(folder);
    dicom::test::TestSlice slice;
    slice.rows = slice.columns = size;
    slice.studyUid = series.studyUid;
    slice.seriesUid = series.seriesUid;
    for (int z = 0; z < slices; ++z) {
        slice.sopInstanceUid = dicom::test::makeTestUid();
        slice.position = glm::dvec3(0, 0, z);
        slice.instanceNumber = z + 1;
        slice.pixels = dicom::test::rampPixels(size, size, z * 7 - 1000);
        series.files.push_back(folder / (std::to_string(z) + ".dcm"));
        dicom::test::writeTestSlice(series.files.back(), slice);
    }
    return series;
}

void OrthancSuite::SetUpTestSuite() {
    if (!orthancBinary())
        GTEST_SKIP() << "Orthanc is not installed (Debian: apt-get install orthanc)";
    s_files = std::make_unique<lw::test::TempDir>();
    s_first = std::make_unique<SyntheticSeries>(writeCtSeries(*s_files / "first", 6, 32));
    s_second = std::make_unique<SyntheticSeries>(
        writeCtSeries(*s_files / "second", 3, 32, s_first->studyUid));
    s_storagePort = freeLoopbackPort();
    s_server = std::make_unique<OrthancServer>(s_storagePort);
    for (const SyntheticSeries* series : {s_first.get(), s_second.get()})
        for (const fs::path& file : series->files)
            s_server->upload(file);
}

void OrthancSuite::TearDownTestSuite() {
    s_server.reset();
    s_first.reset();
    s_second.reset();
    s_files.reset();
}

} // namespace lw::pacs::test
