#pragma once

// parallelFor on a persistent pool: the CPU kernels call it several times per frame, so starting
// threads on every call would cost more than small loops take. The pool (workerCount() - 1
// threads) starts on the first call that wants a second thread and lives until the process ends.

#include <cstddef>
#include <memory>
#include <type_traits>

namespace lw::core {

// Threads for CPU work: the hardware concurrency, at least 1.
unsigned workerCount();

namespace detail {
using ParallelInvoke = void (*)(void* body, std::size_t index);
// Type-erased parallelFor: runs invoke(body, i) for i in [0, count).
void parallelForErased(std::size_t count, unsigned threads, ParallelInvoke invoke, void* body);
} // namespace detail

// Runs body(i) for i in [0, count) on the calling thread and up to threads - 1 pool threads
// (threads 0: workerCount()), handing out indices dynamically so uneven items balance. The
// first exception thrown by a body is rethrown once every participant has stopped; items not
// yet started are abandoned. Safe to call from several threads at once and from inside a body
// (the caller always works on its own items, so a nested call cannot wait on a busy pool).
template <typename Body> void parallelFor(std::size_t count, Body&& body, unsigned threads = 0) {
    using BodyType = std::remove_reference_t<Body>;
    if (count == 0)
        return;
    if (count == 1 || threads == 1) {
        for (std::size_t i = 0; i < count; ++i)
            body(i);
        return;
    }
    void* erased = const_cast<void*>(static_cast<const void*>(std::addressof(body)));
    detail::parallelForErased(
        count, threads, [](void* b, std::size_t i) { (*static_cast<BodyType*>(b))(i); }, erased);
}

// Runs body(begin, end) over consecutive ranges covering [0, count), each `grain` items long (the
// last one shorter), handed out as parallelFor hands out indices: for loops whose items are too
// small to hand out one at a time (vertices, pixels, triangles). The ranges, and so which items
// share a call, do not depend on the number of threads.
template <typename Body>
void parallelForRanges(std::size_t count, std::size_t grain, Body&& body, unsigned threads = 0) {
    const std::size_t step = grain == 0 ? 1 : grain;
    parallelFor((count + step - 1) / step,
                [&](std::size_t range) {
                    const std::size_t begin = range * step;
                    body(begin, count - begin < step ? count : begin + step);
                },
                threads);
}

} // namespace lw::core
