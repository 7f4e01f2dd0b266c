#pragma once

// Host dispatch helpers of the CUDA back-end (CUDA types allowed here, never in public headers):
// status from a CUDA error naming the call or kernel, a check after every launch, RAII device
// and pinned buffers, events for stage times.

#include "lw/kernels/cuda/cuda_status.h"

#include <algorithm>
#include <cstddef>
#include <cuda_runtime.h>
#include <string>
#include <utility>

namespace lw::kernels::cuda::dispatch {

inline CudaStatus statusOf(cudaError_t error, const char* where) {
    if (error == cudaSuccess)
        return CudaStatus::success();
    const CudaStatus::Code code =
        error == cudaErrorMemoryAllocation
            ? CudaStatus::Code::OutOfMemory
            : (error == cudaErrorNoDevice || error == cudaErrorInsufficientDriver
                   ? CudaStatus::Code::NoDevice
                   : CudaStatus::Code::Failed);
    return CudaStatus::failure(
        code, where, std::string(cudaGetErrorName(error)) + ": " + cudaGetErrorString(error));
}

// After a kernel launch: the launch error (configuration, resources). Asynchronous faults show
// up at the next synchronising call, which is checked the same way.
inline CudaStatus checkLaunch(const char* kernel) {
    return statusOf(cudaGetLastError(), kernel);
}

#define LW_CUDA_TRY(expr, where)                                                                   \
    do {                                                                                           \
        const ::lw::kernels::cuda::CudaStatus lwStatus_ =                                          \
            ::lw::kernels::cuda::dispatch::statusOf((expr), (where));                              \
        if (!lwStatus_.ok())                                                                       \
            return lwStatus_;                                                                      \
    } while (0)

#define LW_CUDA_LAUNCHED(kernel)                                                                   \
    do {                                                                                           \
        const ::lw::kernels::cuda::CudaStatus lwStatus_ =                                          \
            ::lw::kernels::cuda::dispatch::checkLaunch(kernel);                                    \
        if (!lwStatus_.ok())                                                                       \
            return lwStatus_;                                                                      \
    } while (0)

// Device memory of `T`, grown on demand and never shrunk (repeated frames allocate nothing).
template <typename T> class DeviceBuffer {
public:
    DeviceBuffer() = default;
    ~DeviceBuffer() { release(); }
    DeviceBuffer(const DeviceBuffer&) = delete;
    DeviceBuffer& operator=(const DeviceBuffer&) = delete;

    // Ensures room for `count` elements; the contents are lost when it grows.
    CudaStatus reserve(std::size_t count, const char* what) {
        if (count <= m_capacity)
            return CudaStatus::success();
        release();
        const std::size_t grown = count + count / 8; // slack for the next, slightly larger frame
        void* p = nullptr;
        const cudaError_t error = cudaMalloc(&p, grown * sizeof(T));
        if (error != cudaSuccess) {
            cudaGetLastError(); // clear the sticky-free allocation error
            return statusOf(error, what);
        }
        m_data = static_cast<T*>(p);
        m_capacity = grown;
        return CudaStatus::success();
    }
    void release() {
        if (m_data)
            cudaFree(m_data);
        m_data = nullptr;
        m_capacity = 0;
    }
    T* data() const { return m_data; }
    std::size_t capacity() const { return m_capacity; }
    std::size_t bytes() const { return m_capacity * sizeof(T); }
    friend void swap(DeviceBuffer& a, DeviceBuffer& b) noexcept {
        std::swap(a.m_data, b.m_data);
        std::swap(a.m_capacity, b.m_capacity);
    }

private:
    T* m_data = nullptr;
    std::size_t m_capacity = 0;
};

// Page-locked host memory (fast, asynchronous copies).
template <typename T> class PinnedBuffer {
public:
    PinnedBuffer() = default;
    ~PinnedBuffer() {
        if (m_data)
            cudaFreeHost(m_data);
    }
    PinnedBuffer(const PinnedBuffer&) = delete;
    PinnedBuffer& operator=(const PinnedBuffer&) = delete;
    CudaStatus reserve(std::size_t count, const char* what) {
        if (count <= m_capacity)
            return CudaStatus::success();
        if (m_data)
            cudaFreeHost(m_data);
        m_data = nullptr;
        m_capacity = 0;
        void* p = nullptr;
        LW_CUDA_TRY(cudaMallocHost(&p, count * sizeof(T)), what);
        m_data = static_cast<T*>(p);
        m_capacity = count;
        return CudaStatus::success();
    }
    T* data() const { return m_data; }

private:
    T* m_data = nullptr;
    std::size_t m_capacity = 0;
};

class Stream {
public:
    Stream() = default;
    ~Stream() {
        if (m_stream)
            cudaStreamDestroy(m_stream);
    }
    Stream(const Stream&) = delete;
    Stream& operator=(const Stream&) = delete;
    CudaStatus create() {
        if (!m_stream)
            LW_CUDA_TRY(cudaStreamCreateWithFlags(&m_stream, cudaStreamNonBlocking),
                        "cudaStreamCreate");
        return CudaStatus::success();
    }
    cudaStream_t get() const { return m_stream; }

private:
    cudaStream_t m_stream = nullptr;
};

// A pair of events around a stage; ms() after the stream was synchronised.
class StageTimer {
public:
    StageTimer() = default;
    ~StageTimer() {
        if (m_start)
            cudaEventDestroy(m_start);
        if (m_stop)
            cudaEventDestroy(m_stop);
    }
    StageTimer(const StageTimer&) = delete;
    StageTimer& operator=(const StageTimer&) = delete;
    CudaStatus start(cudaStream_t stream) {
        if (!m_start) {
            LW_CUDA_TRY(cudaEventCreate(&m_start), "cudaEventCreate");
            LW_CUDA_TRY(cudaEventCreate(&m_stop), "cudaEventCreate");
        }
        LW_CUDA_TRY(cudaEventRecord(m_start, stream), "cudaEventRecord");
        return CudaStatus::success();
    }
    CudaStatus stop(cudaStream_t stream) {
        LW_CUDA_TRY(cudaEventRecord(m_stop, stream), "cudaEventRecord");
        return CudaStatus::success();
    }
    // Blocks the host until the stage's end has passed on the device.
    CudaStatus waitForStop() const {
        if (m_stop)
            LW_CUDA_TRY(cudaEventSynchronize(m_stop), "cudaEventSynchronize(stage)");
        return CudaStatus::success();
    }
    double ms() const {
        float ms = 0.0f;
        if (m_start && m_stop && cudaEventElapsedTime(&ms, m_start, m_stop) == cudaSuccess)
            return double(ms);
        return 0.0;
    }

private:
    cudaEvent_t m_start = nullptr;
    cudaEvent_t m_stop = nullptr;
};

inline unsigned blocksFor(std::size_t items, int blockSize) {
    return unsigned((items + std::size_t(blockSize) - 1) / std::size_t(blockSize));
}

// How many blocks of `blockSize` threads of `kernel` the current device holds at once: the grid
// of a kernel whose threads take their work from a counter until it runs out.
template <typename Kernel>
CudaStatus residentBlocks(Kernel kernel, int blockSize, unsigned& blocks) {
    int device = 0, perMultiprocessor = 0, multiprocessors = 0;
    LW_CUDA_TRY(cudaGetDevice(&device), "cudaGetDevice");
    LW_CUDA_TRY(cudaDeviceGetAttribute(&multiprocessors, cudaDevAttrMultiProcessorCount, device),
                "cudaDeviceGetAttribute(multiprocessors)");
    LW_CUDA_TRY(
        cudaOccupancyMaxActiveBlocksPerMultiprocessor(&perMultiprocessor, kernel, blockSize, 0),
        "cudaOccupancyMaxActiveBlocksPerMultiprocessor");
    blocks = unsigned(std::max(1, perMultiprocessor * multiprocessors));
    return CudaStatus::success();
}

} // namespace lw::kernels::cuda::dispatch
