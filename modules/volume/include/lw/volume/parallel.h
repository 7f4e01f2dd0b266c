#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace lw::volume {

// Number of worker threads for CPU work (hardware concurrency, at least 1).
inline unsigned workerCount() { return std::max(1u, std::thread::hardware_concurrency()); }

// Runs body(i) for i in [0, count) on up to workerCount() threads, handing out indices
// dynamically so uneven items balance. The first exception thrown by a body is rethrown
// after all threads stopped; the other items are abandoned.
template <typename Body> void parallelFor(std::size_t count, Body&& body, unsigned threads = 0) {
    if (threads == 0)
        threads = workerCount();
    threads = unsigned(std::min<std::size_t>(threads, count));
    if (threads <= 1) {
        for (std::size_t i = 0; i < count; ++i)
            body(i);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::exception_ptr error;
    std::mutex errorMutex;
    auto worker = [&] {
        while (!failed.load(std::memory_order_relaxed)) {
            const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
            if (i >= count)
                return;
            try {
                body(i);
            } catch (...) {
                std::lock_guard lock(errorMutex);
                if (!error)
                    error = std::current_exception();
                failed = true;
            }
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    for (unsigned t = 1; t < threads; ++t)
        pool.emplace_back(worker);
    worker();
    for (auto& thread : pool)
        thread.join();
    if (error)
        std::rethrow_exception(error);
}

} // namespace lw::volume
