#pragma once

// Host memory page-locked in place (cudaHostRegister) for as long as the object lives. A copy
// between the device and such memory runs at the bus's speed straight into it; into pageable
// memory the runtime stages it through a page-locked buffer of its own, and into fresh pageable
// memory it runs at the speed of the page faults. Locking costs a few ms for tens of MB, so it
// pays for memory that is written again and again (the thick-slice copies the review keeps).
// Public header: no CUDA types.

#include "lw/kernels/cuda/cuda_status.h"

#include <cstddef>

namespace lw::kernels::cuda {

class PageLockedHostRange {
public:
    PageLockedHostRange() = default;
    ~PageLockedHostRange();
    PageLockedHostRange(PageLockedHostRange&& other) noexcept;
    PageLockedHostRange& operator=(PageLockedHostRange&& other) noexcept;
    PageLockedHostRange(const PageLockedHostRange&) = delete;
    PageLockedHostRange& operator=(const PageLockedHostRange&) = delete;

    // Locks [data, data + bytes), which must stay allocated until this object is destroyed or
    // unlocked. Fails (and locks nothing) where the driver refuses: no device, a limit on locked
    // memory, or pages of the range locked already by someone else.
    CudaStatus lock(void* data, std::size_t bytes);
    void unlock();
    bool locked() const { return m_data != nullptr; }
    void* data() const { return m_data; }
    std::size_t bytes() const { return m_bytes; }

private:
    void* m_data = nullptr;
    std::size_t m_bytes = 0;
};

} // namespace lw::kernels::cuda
