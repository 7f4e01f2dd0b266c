#pragma once

// Finds out why the UI thread stalls (linework-review-bench --probe-stalls MS; Linux only).
// A timer on the UI thread beats every 2 ms; a watchdog thread notices when the beat is late by
// more than the threshold and, until the beat comes back, samples the UI thread from outside:
// its scheduler state and wait channel, its kernel stack (/proc/self/task/TID/stack, root
// only), and how the stall's time splits into running, waiting for a CPU (schedstat) and
// sleeping. Once per stall it also interrupts the UI thread with a signal whose handler records
// the user-space stack where the thread was. One report per stall goes to stderr when it ends.

#include <QObject>
#include <QTimer>
#include <atomic>
#include <memory>
#include <thread>

namespace lw::gui {

class StallProbe : public QObject {
    Q_OBJECT
public:
    // Construct on the UI thread: it is the thread watched.
    explicit StallProbe(double thresholdMs, QObject* parent = nullptr);
    ~StallProbe() override;
    StallProbe(const StallProbe&) = delete;
    StallProbe& operator=(const StallProbe&) = delete;

private:
    void watch();

    double m_thresholdMs;
    int m_uiThreadId;
    QTimer m_beat;
    std::atomic<long long> m_lastBeatNs{0};
    std::atomic<bool> m_stop{false};
    std::thread m_watchdog;
};

} // namespace lw::gui
