#include "lw/core/thread_priority.h"

#ifdef __linux__
#include <cerrno>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

namespace lw::core {

#ifdef __linux__

namespace {
// PRIO_PROCESS with a thread id addresses that one thread on Linux (not POSIX: there it would
// be the whole process).
id_t currentThreadId() {
    return id_t(::syscall(SYS_gettid));
}
} // namespace

int currentThreadNice() {
    errno = 0;
    const int nice = ::getpriority(PRIO_PROCESS, currentThreadId());
    return errno == 0 ? nice : 0;
}

void lowerCurrentThreadTo(int nice) {
    if (currentThreadNice() < nice)
        ::setpriority(PRIO_PROCESS, currentThreadId(), nice); // a failure leaves it as it was
}

#else

int currentThreadNice() {
    return 0;
}

void lowerCurrentThreadTo(int) {}

#endif

} // namespace lw::core
