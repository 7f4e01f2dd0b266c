#pragma once

// What a CUDA call of the back-end reports instead of throwing: kernels and their host dispatch
// never throw (render turns a failed status into core::Error, or falls back). Free of CUDA types.

#include <string>

namespace lw::kernels::cuda {

struct CudaStatus {
    enum class Code {
        Ok,
        NoDevice,    // no CUDA device or driver on this machine
        OutOfMemory, // a device allocation failed: the caller may retry chunked or on the CPU
        Failed,      // a kernel launch or CUDA call failed (see where and message)
        TooLarge,    // the input exceeds what the kernels index (32-bit voxel or vertex ids)
    };
    Code code = Code::Ok;
    std::string where;   // the kernel or CUDA call, e.g. "mc::classifyTiles"
    std::string message; // the CUDA error text or the reason

    bool ok() const { return code == Code::Ok; }
    // "<where>: <message>", or "ok".
    std::string describe() const { return ok() ? "ok" : where + ": " + message; }

    static CudaStatus success() { return {}; }
    static CudaStatus failure(Code code, std::string where, std::string message) {
        CudaStatus s;
        s.code = code;
        s.where = std::move(where);
        s.message = std::move(message);
        return s;
    }
};

} // namespace lw::kernels::cuda

// Returns a failed status from the enclosing function (which returns CudaStatus).
#define LW_RETURN_IF_FAILED(statusExpr)                                                            \
    do {                                                                                           \
        ::lw::kernels::cuda::CudaStatus lwStatus_ = (statusExpr);                                  \
        if (!lwStatus_.ok())                                                                       \
            return lwStatus_;                                                                      \
    } while (0)
