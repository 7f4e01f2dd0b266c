#pragma once

// Probing for a CUDA device at run time. The back-end links the CUDA runtime statically, and the
// runtime loads the driver (libcuda) only when asked: a binary built with CUDA runs on machines
// without a GPU or without the driver, where the probe answers "none" with the reason.

#include <cstddef>
#include <string>

namespace lw::kernels::cuda {

struct CudaDeviceInfo {
    bool available = false;
    std::string name;   // e.g. "NVIDIA H100 80GB HBM3"
    std::string reason; // why none is available (empty when available)
    int computeMajor = 0, computeMinor = 0;
    std::size_t totalBytes = 0;
    std::size_t freeBytes = 0;
    int driverVersion = 0; // e.g. 13000
};

// Device 0. Cheap after the first call in a process (the CUDA context is then made).
CudaDeviceInfo probeCudaDevice();

// Free device memory now (bytes); 0 when there is no device.
std::size_t freeDeviceBytes();

} // namespace lw::kernels::cuda
