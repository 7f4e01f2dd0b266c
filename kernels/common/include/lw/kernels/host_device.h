#pragma once

// Functions in kernels/common compile for the host and, under nvcc, for the device too, so
// the CPU reference and the CUDA backend share one definition of the math they must agree on.
#if defined(__CUDACC__)
#define LW_HOST_DEVICE __host__ __device__
#else
#define LW_HOST_DEVICE
#endif

// For the few functions on a hot path that the host compiler stops inlining once they grow (a
// call per marching-cubes vertex costs measurably); nvcc's __forceinline__ on the device.
#if defined(__CUDACC__)
#define LW_FORCE_INLINE __forceinline__
#else
#define LW_FORCE_INLINE [[gnu::always_inline]] inline
#endif
