#pragma once

// Functions in kernels/common compile for the host and, under nvcc, for the device too, so
// the CPU reference and the CUDA backend share one definition of the math they must agree on.
#if defined(__CUDACC__)
#define LW_HOST_DEVICE __host__ __device__
#else
#define LW_HOST_DEVICE
#endif
