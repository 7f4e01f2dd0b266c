#include "bench/stall_probe.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cxxabi.h>
#include <deque>
#include <dlfcn.h>
#include <execinfo.h>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <sys/syscall.h>
#include <unistd.h>
#include <vector>

namespace lw::gui {
namespace {

long long nowNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

std::string readText(const std::string& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The user-space stack the signal handler records (one stall at a time).
constexpr int kMaxFrames = 48;
std::array<void*, kMaxFrames> g_frames{};
std::atomic<int> g_frameCount{0};
std::atomic<bool> g_wantFrames{false};

void recordFrames(int) {
    if (g_wantFrames.exchange(false))
        g_frameCount.store(backtrace(g_frames.data(), kMaxFrames));
}

int probeSignal() {
    return SIGRTMIN + 7;
}

// schedstat: nanoseconds on a CPU, nanoseconds runnable but waiting for one.
struct SchedTimes {
    long long at = 0;
    long long running = 0;
    long long waiting = 0;
};

SchedTimes schedTimes(const std::string& task) {
    SchedTimes times;
    times.at = nowNs();
    std::istringstream(readText(task + "/schedstat")) >> times.running >> times.waiting;
    return times;
}

char schedulerState(const std::string& task) {
    const std::string stat = readText(task + "/stat");
    const auto close = stat.rfind(')');
    return close != std::string::npos && close + 2 < stat.size() ? stat[close + 2] : '?';
}

std::string symbolised(void* address) {
    Dl_info info{};
    if (!dladdr(address, &info) || !info.dli_fname)
        return "?";
    std::string name = "?";
    if (info.dli_sname) {
        int status = 0;
        char* demangled = abi::__cxa_demangle(info.dli_sname, nullptr, nullptr, &status);
        name = status == 0 && demangled ? demangled : info.dli_sname;
        std::free(demangled);
    }
    char line[512];
    std::snprintf(line, sizeof line, "%s(+0x%zx) %s", info.dli_fname,
                  std::size_t(static_cast<char*>(address) - static_cast<char*>(info.dli_fbase)),
                  name.substr(0, 200).c_str());
    return line;
}

// What the watchdog saw during one stall.
struct Episode {
    long long beatBeforeNs = 0;
    SchedTimes start;
    std::map<char, int> states;
    std::map<std::string, int> kernelStacks; // "wchan | stack" -> samples
    std::map<std::vector<void*>, int> userStacks;
    std::map<std::string, int> runnableThreads; // the process's other threads seen running
};

// The process's threads other than `except` that are runnable now, by name.
void countRunnableThreads(int except, std::map<std::string, int>& counts) {
    for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) {
        if (entry.path().filename() == std::to_string(except))
            continue;
        if (schedulerState(entry.path().string()) != 'R')
            continue;
        std::string name = readText(entry.path().string() + "/comm");
        if (!name.empty() && name.back() == '\n')
            name.pop_back();
        ++counts[name];
    }
}

void reportEpisode(const Episode& episode, const SchedTimes& end, long long beatAfterNs) {
    const double ms = double(beatAfterNs - episode.beatBeforeNs) / 1e6;
    std::fprintf(
        stderr,
        "stall-probe: %.1f ms stall: on CPU %.1f ms, waiting for a CPU %.1f ms, "
        "rest (sleeping or blocked) %.1f ms; states:",
        ms, double(end.running - episode.start.running) / 1e6,
        double(end.waiting - episode.start.waiting) / 1e6,
        ms - double(end.running - episode.start.running + end.waiting - episode.start.waiting) /
                 1e6);
    for (const auto& [state, count] : episode.states)
        std::fprintf(stderr, " %c=%d", state, count);
    std::fprintf(stderr, "\n");
    for (const auto& [stack, count] : episode.kernelStacks)
        std::fprintf(stderr, "stall-probe:   %d x kernel: %s\n", count, stack.c_str());
    for (const auto& [name, count] : episode.runnableThreads)
        std::fprintf(stderr, "stall-probe:   other thread runnable: %s x %d\n", name.c_str(),
                     count);
    for (const auto& [frames, count] : episode.userStacks) {
        std::fprintf(stderr, "stall-probe:   %d x user stack:\n", count);
        for (std::size_t i = 0; i < frames.size() && i < 24; ++i)
            std::fprintf(stderr, "stall-probe:     #%zu %s\n", i, symbolised(frames[i]).c_str());
    }
    std::fflush(stderr);
}

std::string oneLine(std::string text) {
    std::replace(text.begin(), text.end(), '\n', ' ');
    return text;
}

} // namespace

StallProbe::StallProbe(double thresholdMs, QObject* parent)
    : QObject(parent), m_thresholdMs(thresholdMs), m_uiThreadId(int(::syscall(SYS_gettid))) {
    void* warm[2];
    backtrace(warm, 2); // loads libgcc's unwinder now, not inside the handler
    struct sigaction action {};
    action.sa_handler = recordFrames;
    action.sa_flags = SA_RESTART;
    sigaction(probeSignal(), &action, nullptr);
    m_lastBeatNs = nowNs();
    m_beat.setTimerType(Qt::PreciseTimer);
    m_beat.setInterval(2);
    connect(&m_beat, &QTimer::timeout, this, [this] { m_lastBeatNs = nowNs(); });
    m_beat.start();
    m_watchdog = std::thread([this] { watch(); });
}

StallProbe::~StallProbe() {
    m_stop = true;
    m_watchdog.join();
}

void StallProbe::watch() {
    const std::string task = "/proc/self/task/" + std::to_string(m_uiThreadId);
    const auto threshold = (long long)(m_thresholdMs * 1e6);
    std::deque<SchedTimes> recent; // the last second, to find the times at the stall's start
    std::optional<Episode> episode;
    int sample = 0;
    while (!m_stop) {
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
        const long long beat = m_lastBeatNs.load();
        const SchedTimes times = schedTimes(task);
        if (episode && beat != episode->beatBeforeNs) {
            reportEpisode(*episode, times, beat);
            episode.reset();
        }
        if (!episode && times.at - beat > threshold) {
            episode = Episode{beat, times, {}, {}, {}, {}};
            g_wantFrames = false;
            g_frameCount = 0;
            sample = 0;
            for (const SchedTimes& earlier : recent)
                if (earlier.at <= beat)
                    episode->start = earlier;
        }
        if (episode) {
            ++episode->states[schedulerState(task)];
            ++episode->kernelStacks[readText(task + "/wchan") + " | " +
                                    oneLine(readText(task + "/stack"))];
            // A user stack and the other threads every 4th sample (reading every thread's
            // stat costs the CPU being measured): the signal's handler fills the stack when
            // the thread next returns to user space.
            if (const int frames = g_frameCount.exchange(0); frames > 0)
                ++episode
                      ->userStacks[std::vector<void*>(g_frames.begin(), g_frames.begin() + frames)];
            if (sample++ % 4 == 0 && !g_wantFrames) {
                countRunnableThreads(m_uiThreadId, episode->runnableThreads);
                g_wantFrames = true;
                ::syscall(SYS_tgkill, ::getpid(), m_uiThreadId, probeSignal());
            }
        }
        recent.push_back(times);
        if (recent.size() > 1000)
            recent.pop_front();
    }
}

} // namespace lw::gui
