#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

namespace lw::core {

// Shared cancellation flag: the UI (or a newer request) sets it, workers poll it.
class CancelToken {
public:
    void cancel() noexcept { m_cancelled.store(true, std::memory_order_relaxed); }
    bool isCancelled() const noexcept { return m_cancelled.load(std::memory_order_relaxed); }

private:
    std::atomic<bool> m_cancelled{false};
};

// Progress reporting for long work. Thread-safe: workers on several threads may call step() and
// report(). The callback receives a fraction in [0, 1] and a short message; it is throttled to
// whole per-mille changes so a 10 000-file scan does not flood the UI thread. Calls of the
// callback never overlap, and step()'s come in increasing order, so it needs no lock of its own
// (it may report into another Progress; a callback that steps its own Progress would deadlock).
class Progress {
public:
    using Callback = std::function<void(double fraction, const std::string& message)>;

    Progress() = default;
    Progress(Callback callback, std::shared_ptr<const CancelToken> cancel = {});

    void setTotal(std::size_t total, std::string message = {});
    void step(std::size_t count = 1);
    void report(double fraction, const std::string& message);

    bool isCancelled() const noexcept { return m_cancel && m_cancel->isCancelled(); }
    // The token this progress watches, for a sub-progress that reports into this one.
    std::shared_ptr<const CancelToken> cancelToken() const { return m_cancel; }
    // Throws Cancelled when cancellation was requested.
    void throwIfCancelled() const;

private:
    Callback m_callback;
    std::shared_ptr<const CancelToken> m_cancel;
    std::mutex m_mutex;
    std::recursive_mutex m_callbackMutex; // serialises the callback (report() inside it is fine)
    std::size_t m_total = 0;
    std::size_t m_done = 0;
    int m_lastPermille = -1;
    std::string m_message;
};

} // namespace lw::core
