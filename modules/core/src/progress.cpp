#include "lw/core/progress.h"

#include "lw/core/error.h"

namespace lw::core {

Progress::Progress(Callback callback, std::shared_ptr<const CancelToken> cancel)
    : m_callback(std::move(callback)), m_cancel(std::move(cancel)) {}

void Progress::setTotal(std::size_t total, std::string message) {
    std::lock_guard lock(m_mutex);
    m_total = total;
    m_done = 0;
    m_lastPermille = -1;
    m_message = std::move(message);
}

void Progress::step(std::size_t count) {
    std::unique_lock lock(m_mutex);
    m_done += count;
    if (!m_callback || m_total == 0)
        return;
    const double fraction = std::min(1.0, double(m_done) / double(m_total));
    const int permille = int(fraction * 1000.0);
    if (permille == m_lastPermille)
        return;
    m_lastPermille = permille;
    const std::string message = m_message;
    // The callback runs outside m_mutex (the other workers' steps go on meanwhile) but under
    // m_callbackMutex, taken before m_mutex is let go: callbacks never overlap (they need not
    // be thread-safe), and they come in the order of the fractions.
    std::lock_guard callbackLock(m_callbackMutex);
    lock.unlock();
    m_callback(fraction, message);
}

void Progress::report(double fraction, const std::string& message) {
    if (!m_callback)
        return;
    std::lock_guard callbackLock(m_callbackMutex);
    m_callback(fraction, message);
}

void Progress::throwIfCancelled() const {
    if (isCancelled())
        throw Cancelled();
}

} // namespace lw::core
