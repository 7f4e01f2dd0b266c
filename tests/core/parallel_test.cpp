// core::parallelFor on its persistent pool: results, exceptions, nesting, concurrent callers,
// and no thread started per call.
#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/core/thread_priority.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <gtest/gtest.h>
#include <mutex>
#include <numeric>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

namespace lw::core {
namespace {

// The threads that ran the bodies of `work`, the caller's included.
template <typename Work> std::set<std::thread::id> threadsUsedBy(Work&& work) {
    std::mutex mutex;
    std::set<std::thread::id> ids;
    work([&] {
        std::lock_guard lock(mutex);
        ids.insert(std::this_thread::get_id());
    });
    return ids;
}

// Long enough that the pool threads wake up and join before the caller has done every item.
void busyFor(std::chrono::microseconds duration) {
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end) {
    }
}

TEST(ParallelFor, VisitsEveryIndexOnce) {
    for (unsigned threads : {0u, 1u, 2u, 8u}) {
        std::vector<std::atomic<int>> hits(10007);
        parallelFor(
            hits.size(), [&](std::size_t i) { hits[i].fetch_add(1); }, threads);
        for (const auto& h : hits)
            ASSERT_EQ(h.load(), 1) << threads << " threads";
    }
}

TEST(ParallelFor, SumsLikeASerialLoop) {
    std::vector<std::uint64_t> values(100000);
    std::iota(values.begin(), values.end(), 1);
    std::atomic<std::uint64_t> sum{0};
    parallelFor(values.size(), [&](std::size_t i) { sum += values[i]; });
    EXPECT_EQ(sum.load(), std::uint64_t(100000) * 100001 / 2);
}

TEST(ParallelFor, PropagatesTheExceptionOfABody) {
    for (unsigned threads : {1u, 4u}) {
        std::atomic<int> ran{0};
        try {
            parallelFor(
                1000,
                [&](std::size_t i) {
                    ++ran;
                    if (i == 37)
                        throw Error("item 37", "failed on purpose");
                },
                threads);
            FAIL() << "no exception with " << threads << " threads";
        } catch (const Error& e) {
            EXPECT_EQ(e.subject(), "item 37");
            EXPECT_EQ(e.reason(), "failed on purpose");
        }
        if (threads == 1)
            EXPECT_EQ(ran.load(), 38); // stops at the failing item
        else
            EXPECT_GE(ran.load(), 1);
    }
    EXPECT_NO_THROW(parallelFor(0, [](std::size_t) { throw std::logic_error("never called"); }));
    // The pool is still usable after a failure.
    std::atomic<int> after{0};
    parallelFor(64, [&](std::size_t) { ++after; });
    EXPECT_EQ(after.load(), 64);
}

TEST(ParallelFor, OneThreadRunsOnTheCallerInOrder) {
    std::vector<std::size_t> order;
    const auto ids = threadsUsedBy([&](auto record) {
        parallelFor(
            100,
            [&](std::size_t i) {
                record();
                order.push_back(i);
            },
            1);
    });
    ASSERT_EQ(ids.size(), 1u);
    EXPECT_EQ(*ids.begin(), std::this_thread::get_id());
    std::vector<std::size_t> expected(100);
    std::iota(expected.begin(), expected.end(), 0);
    EXPECT_EQ(order, expected);
}

TEST(ParallelFor, NeverMoreParticipantsThanThreads) {
    for (unsigned threads : {2u, 3u}) {
        std::atomic<int> inside{0};
        std::atomic<int> most{0};
        parallelFor(
            2000,
            [&](std::size_t) {
                const int now = ++inside;
                int seen = most.load();
                while (now > seen && !most.compare_exchange_weak(seen, now)) {
                }
                std::this_thread::yield();
                --inside;
            },
            threads);
        EXPECT_LE(most.load(), int(threads));
    }
}

TEST(ParallelFor, NestedCallsDoNotDeadlock) {
    std::atomic<std::size_t> sum{0};
    parallelFor(16, [&](std::size_t i) {
        parallelFor(100, [&](std::size_t j) {
            parallelFor(3, [&](std::size_t k) { sum += i * 10000 + j * 10 + k; });
        });
    });
    std::size_t expected = 0;
    for (std::size_t i = 0; i < 16; ++i)
        for (std::size_t j = 0; j < 100; ++j)
            for (std::size_t k = 0; k < 3; ++k)
                expected += i * 10000 + j * 10 + k;
    EXPECT_EQ(sum.load(), expected);
}

TEST(ParallelFor, ConcurrentCallersFromSeveralThreads) {
    constexpr int kCallers = 4;
    std::vector<std::uint64_t> sums(kCallers, 0);
    std::vector<std::thread> callers;
    for (int c = 0; c < kCallers; ++c)
        callers.emplace_back([&, c] {
            for (int round = 0; round < 50; ++round) {
                std::atomic<std::uint64_t> sum{0};
                parallelFor(64, [&](std::size_t i) {
                    busyFor(std::chrono::microseconds(20));
                    sum += i + std::size_t(c);
                });
                sums[std::size_t(c)] += sum.load();
            }
        });
    for (std::thread& caller : callers)
        caller.join();
    for (int c = 0; c < kCallers; ++c)
        EXPECT_EQ(sums[std::size_t(c)], 50u * (63u * 64u / 2 + 64u * std::uint64_t(c))) << c;
}

TEST(ParallelFor, ManySmallCallsReuseTheSameThreads) {
    const auto ids = threadsUsedBy([](auto record) {
        for (int call = 0; call < 500; ++call)
            parallelFor(8, [&](std::size_t) {
                busyFor(std::chrono::microseconds(50));
                record();
            });
    });
    // The caller plus the pool: a thread per call would show up as hundreds of ids.
    EXPECT_LE(ids.size(), std::size_t(workerCount()));
    if (workerCount() > 1) {
        EXPECT_GT(ids.size(), 1u) << "the pool never joined in";
    }
}

TEST(ParallelFor, WorkerCountIsAtLeastOne) {
    EXPECT_GE(workerCount(), 1u);
}

#ifdef __linux__
// Per thread and one way: the lowered thread stays lowered, the test's own thread does not move.
TEST(ThreadPriority, BackgroundIsPerThreadAndOneWay) {
    const int mine = currentThreadNice();
    int lowered = -1, afterRaise = -1;
    std::thread([&] {
        lowerCurrentThreadToBackground();
        lowered = currentThreadNice();
        lowerCurrentThreadTo(0); // "lower" to a higher priority: nothing happens
        afterRaise = currentThreadNice();
    }).join();
    EXPECT_EQ(lowered, std::max(mine, kBackgroundNice));
    EXPECT_EQ(afterRaise, lowered);
    EXPECT_EQ(currentThreadNice(), mine);
}

// A background caller's items never run at a higher priority on a pool helper.
TEST(ThreadPriority, HelpersRunABackgroundCallersItemsInTheBackground) {
    if (workerCount() < 2)
        GTEST_SKIP() << "one core: parallelFor has no helpers";
    std::mutex mutex;
    std::set<std::thread::id> threads;
    int highestPriority = 100; // the smallest nice value seen running an item
    std::thread([&] {
        lowerCurrentThreadToBackground();
        parallelFor(64, [&](std::size_t) {
            busyFor(std::chrono::microseconds(500));
            std::lock_guard lock(mutex);
            threads.insert(std::this_thread::get_id());
            highestPriority = std::min(highestPriority, currentThreadNice());
        });
    }).join();
    EXPECT_GT(threads.size(), 1u) << "no helper joined: the check below proved nothing";
    EXPECT_GE(highestPriority, kBackgroundNice);
}
#endif

} // namespace
} // namespace lw::core
