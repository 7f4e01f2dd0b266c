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
    Callback callback;
    double fraction = 0.0;
    std::string message;
    {
        std::lock_guard lock(m_mutex);
        m_done += count;
        if (!m_callback || m_total == 0)
            return;
        fraction = std::min(1.0, double(m_done) / double(m_total));
        const int permille = int(fraction * 1000.0);
        if (permille == m_lastPermille)
            return;
        m_lastPermille = permille;
        callback = m_callback;
        message = m_message;
    }
    callback(fraction, message);
}

void Progress::report(double fraction, const std::string& message) {
    if (m_callback)
        m_callback(fraction, message);
}

void Progress::throwIfCancelled() const {
    if (isCancelled())
        throw Cancelled();
}

} // namespace lw::core
