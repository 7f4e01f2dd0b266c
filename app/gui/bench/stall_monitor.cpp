#include "bench/stall_monitor.h"

#include <algorithm>

namespace lw::gui {

StallMonitor::StallMonitor(int intervalMs, QObject* parent)
    : QObject(parent), m_intervalMs(intervalMs) {
    m_timer.setTimerType(Qt::PreciseTimer);
    m_timer.setInterval(intervalMs);
    connect(&m_timer, &QTimer::timeout, this, &StallMonitor::tick);
}

void StallMonitor::start() {
    m_longestMs = 0.0;
    m_stalls.clear();
    m_markedStalls = 0;
    m_clock.start();
    m_lastNs = 0;
    m_timer.start();
}

void StallMonitor::stop() {
    m_timer.stop();
}

int StallMonitor::stallsOver(double thresholdMs) const {
    return int(std::count_if(m_stalls.begin(), m_stalls.end(),
                             [thresholdMs](double ms) { return ms > thresholdMs; }));
}

double StallMonitor::longestSinceMarkMs() const {
    double longest = 0.0;
    for (qsizetype i = m_markedStalls; i < m_stalls.size(); ++i)
        longest = std::max(longest, m_stalls[i]);
    return longest;
}

void StallMonitor::tick() {
    const qint64 now = m_clock.nsecsElapsed();
    const double lateMs = double(now - m_lastNs) / 1e6 - m_intervalMs;
    m_lastNs = now;
    if (lateMs > m_intervalMs) {
        m_stalls.append(lateMs);
        m_longestMs = std::max(m_longestMs, lateMs);
    }
}

} // namespace lw::gui
