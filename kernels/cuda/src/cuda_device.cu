#include "lw/kernels/cuda/cuda_device.h"

#include <cuda_runtime.h>

namespace lw::kernels::cuda {

CudaDeviceInfo probeCudaDevice() {
    CudaDeviceInfo info;
    int count = 0;
    const cudaError_t error = cudaGetDeviceCount(&count);
    if (error != cudaSuccess) {
        cudaGetLastError();
        const std::string detail = std::string(" (") + cudaGetErrorName(error) + ")";
        if (error == cudaErrorNoDevice)
            info.reason = "no CUDA device" + detail;
        else if (error == cudaErrorInsufficientDriver)
            info.reason = "no NVIDIA driver, or one older than this build's CUDA runtime" + detail;
        else
            info.reason =
                std::string("CUDA is not usable here: ") + cudaGetErrorString(error) + detail;
        return info;
    }
    if (count == 0) {
        info.reason = "no CUDA device";
        return info;
    }
    cudaDeviceProp props{};
    if (cudaGetDeviceProperties(&props, 0) != cudaSuccess) {
        cudaGetLastError();
        info.reason = "cudaGetDeviceProperties failed";
        return info;
    }
    info.name = props.name;
    info.computeMajor = props.major;
    info.computeMinor = props.minor;
    cudaDriverGetVersion(&info.driverVersion);
    if (cudaMemGetInfo(&info.freeBytes, &info.totalBytes) != cudaSuccess) {
        cudaGetLastError();
        info.reason = "cannot create a CUDA context on " + info.name;
        return info;
    }
    info.available = true;
    return info;
}

std::size_t freeDeviceBytes() {
    std::size_t free = 0, total = 0;
    if (cudaMemGetInfo(&free, &total) != cudaSuccess) {
        cudaGetLastError();
        return 0;
    }
    return free;
}

} // namespace lw::kernels::cuda
