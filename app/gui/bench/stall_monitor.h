#pragma once

// Measures how long the UI thread's event loop is blocked: a timer asks to fire every
// `intervalMs`; each tick that arrives late by more than that was held up by work on the UI
// thread. The longest lateness is the longest stall the user could feel (the goal: < 50 ms).

#include <QElapsedTimer>
#include <QObject>
#include <QTimer>

namespace lw::gui {

class StallMonitor : public QObject {
    Q_OBJECT
public:
    explicit StallMonitor(int intervalMs = 5, QObject* parent = nullptr);

    void start();
    void stop();
    // Longest lateness of a tick since start() (ms), and how many ticks were over `thresholdMs`.
    double longestStallMs() const { return m_longestMs; }
    int stallsOver(double thresholdMs) const;
    // Splits a measurement in phases: the longest stall since the last mark() (or start()). A
    // stall under way at the mark counts to the phase after it (its tick arrives then).
    void mark() { m_markedStalls = m_stalls.size(); }
    double longestSinceMarkMs() const;

private:
    void tick();

    int m_intervalMs;
    QTimer m_timer;
    QElapsedTimer m_clock;
    qint64 m_lastNs = 0;
    double m_longestMs = 0.0;
    QList<double> m_stalls; // lateness of every tick over one interval
    qsizetype m_markedStalls = 0;
};

} // namespace lw::gui
