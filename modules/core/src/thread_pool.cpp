#include "lw/core/parallel.h"
#include "lw/core/thread_priority.h"

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace lw::core {
namespace {

// One parallelFor call. It lives on the caller's stack; pool threads touch it only between
// joining (under the pool mutex) and leaving (under the pool mutex), and the caller returns only
// after every thread that joined has left.
struct Job {
    std::size_t count = 0;
    detail::ParallelInvoke invoke = nullptr;
    void* body = nullptr;
    unsigned helpersWanted = 0; // pool threads that may join besides the caller
    unsigned helpersJoined = 0; // guarded by the pool mutex
    unsigned helpersActive = 0; // guarded by the pool mutex
    int callerNice = 0;         // helpers never run the items at a higher priority than this
    std::condition_variable helpersLeft;

    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex errorMutex;
    std::exception_ptr error;

    bool exhausted() const {
        return failed.load(std::memory_order_relaxed) ||
               next.load(std::memory_order_relaxed) >= count;
    }

    // Takes indices until none are left or a body has thrown.
    void work() {
        while (!failed.load(std::memory_order_relaxed)) {
            const std::size_t i = next.fetch_add(1, std::memory_order_relaxed);
            if (i >= count)
                return;
            try {
                invoke(body, i);
            } catch (...) {
                std::lock_guard lock(errorMutex);
                if (!error)
                    error = std::current_exception();
                failed.store(true, std::memory_order_relaxed);
            }
        }
    }
};

// The helpers are only an acceleration: the caller works through its own job and waits just for
// the helpers that actually joined, each of which is running items that finish on their own.
// That is why concurrent callers and nested calls (a body calling parallelFor) cannot deadlock.
class ThreadPool {
public:
    explicit ThreadPool(unsigned threads) {
        m_threads.reserve(threads);
        for (unsigned t = 0; t < threads; ++t)
            m_threads.emplace_back([this] { serve(); });
    }

    ~ThreadPool() {
        {
            std::lock_guard lock(m_mutex);
            m_stopping = true;
        }
        m_wake.notify_all();
        for (std::thread& thread : m_threads)
            thread.join();
    }

    ThreadPool(const ThreadPool&) = delete;
    ThreadPool& operator=(const ThreadPool&) = delete;

    unsigned size() const { return unsigned(m_threads.size()); }

    void run(Job& job) {
        if (job.helpersWanted > 0) {
            {
                std::lock_guard lock(m_mutex);
                m_jobs.push_back(&job);
            }
            for (unsigned h = 0; h < job.helpersWanted; ++h)
                m_wake.notify_one();
        }
        job.work();
        std::unique_lock lock(m_mutex);
        // No helper may join once the caller is done with the items.
        const auto queued = std::find(m_jobs.begin(), m_jobs.end(), &job);
        if (queued != m_jobs.end())
            m_jobs.erase(queued);
        job.helpersLeft.wait(lock, [&] { return job.helpersActive == 0; });
    }

private:
    void serve() {
        std::unique_lock lock(m_mutex);
        for (;;) {
            m_wake.wait(lock, [&] { return m_stopping || !m_jobs.empty(); });
            if (m_stopping)
                return;
            Job& job = *m_jobs.front();
            if (++job.helpersJoined >= job.helpersWanted || job.exhausted())
                m_jobs.pop_front();
            ++job.helpersActive;
            const int callerNice = job.callerNice;
            lock.unlock();
            // A background caller's items stay background on the helper (thread_priority.h);
            // the helper cannot rise again, so a later normal caller does most of its items
            // itself, as it does whenever the helpers are busy.
            lowerCurrentThreadTo(callerNice);
            job.work();
            lock.lock();
            if (--job.helpersActive == 0)
                job.helpersLeft.notify_one();
        }
    }

    std::mutex m_mutex;
    std::condition_variable m_wake;
    std::deque<Job*> m_jobs; // calls that still take helpers, oldest first
    bool m_stopping = false;
    std::vector<std::thread> m_threads;
};

ThreadPool& pool() {
    // Created on first use, joined at exit: the one pool of the process.
    static ThreadPool instance(workerCount() - 1);
    return instance;
}

} // namespace

unsigned workerCount() {
    static const unsigned count = std::max(1u, std::thread::hardware_concurrency());
    return count;
}

namespace detail {

void parallelForErased(std::size_t count, unsigned threads, ParallelInvoke invoke, void* body) {
    if (threads == 0)
        threads = workerCount();
    Job job;
    job.count = count;
    job.invoke = invoke;
    job.body = body;
    const std::size_t participants = std::min<std::size_t>(threads, count);
    if (participants > 1) {
        job.helpersWanted = unsigned(std::min<std::size_t>(participants - 1, pool().size()));
        job.callerNice = currentThreadNice();
    }
    if (job.helpersWanted == 0)
        job.work();
    else
        pool().run(job);
    if (job.error)
        std::rethrow_exception(job.error);
}

} // namespace detail
} // namespace lw::core
