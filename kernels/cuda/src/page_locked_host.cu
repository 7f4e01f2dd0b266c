#include "dispatch.h"
#include "lw/kernels/cuda/page_locked_host.h"

#include <utility>

namespace lw::kernels::cuda {

PageLockedHostRange::~PageLockedHostRange() {
    unlock();
}

PageLockedHostRange::PageLockedHostRange(PageLockedHostRange&& other) noexcept
    : m_data(std::exchange(other.m_data, nullptr)), m_bytes(std::exchange(other.m_bytes, 0)) {}

PageLockedHostRange& PageLockedHostRange::operator=(PageLockedHostRange&& other) noexcept {
    if (this != &other) {
        unlock();
        m_data = std::exchange(other.m_data, nullptr);
        m_bytes = std::exchange(other.m_bytes, 0);
    }
    return *this;
}

CudaStatus PageLockedHostRange::lock(void* data, std::size_t bytes) {
    unlock();
    if (!data || bytes == 0)
        return CudaStatus::failure(CudaStatus::Code::Failed, "page-locking host memory",
                                   "an empty range");
    // Portable: any device's copies may use it; mapped: a kernel may read it where a renderer
    // maps the same volume (MarchingCubesCuda::setMappedVolume finds it locked already).
    const cudaError_t locked =
        cudaHostRegister(data, bytes, cudaHostRegisterPortable | cudaHostRegisterMapped);
    if (locked != cudaSuccess) {
        cudaGetLastError(); // not sticky: the caller goes on with pageable memory
        return dispatch::statusOf(locked, "cudaHostRegister(page-locked copy)");
    }
    m_data = data;
    m_bytes = bytes;
    return CudaStatus::success();
}

void PageLockedHostRange::unlock() {
    if (!m_data)
        return;
    cudaHostUnregister(m_data); // nothing to report from a destructor; the pages stay valid
    cudaGetLastError();
    m_data = nullptr;
    m_bytes = 0;
}

} // namespace lw::kernels::cuda
