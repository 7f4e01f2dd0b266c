#pragma once

// Background work yields the CPU to the threads a person waits for. On the 2-core machine the
// GUI's volume loading, marching cubes and frames keep both cores busy for minutes; at the same
// priority the UI thread, the Qt pool threads that paint for it and the X server each wait their
// turn behind them (measured: UI stalls of 100-290 ms, see app/gui/README.md). A background
// thread runs at nice 10, which the scheduler weighs at about a tenth of nice 0: it still gets
// every cycle the interactive threads leave idle.
//
// Linux only (a thread's nice value is its own there); elsewhere these do nothing. An
// unprivileged thread cannot raise its priority again, so lowering is one way; threads started
// afterwards inherit the lowered value.

namespace lw::core {

inline constexpr int kBackgroundNice = 10;

// The calling thread's nice value (0 where the platform has none per thread).
int currentThreadNice();

// Lowers the calling thread to `nice` when it runs at a higher priority (a smaller nice value);
// never raises it.
void lowerCurrentThreadTo(int nice);

inline void lowerCurrentThreadToBackground() {
    lowerCurrentThreadTo(kBackgroundNice);
}

} // namespace lw::core
