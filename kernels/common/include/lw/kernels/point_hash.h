#pragma once

// A 64-bit hash of a point's three float bit patterns (passed as integers: each back-end reads
// the bits its own way), for the tables that give each silhouette endpoint one visibility ray
// (method 2: PointVisibilityMemo on the CPU, the endpoint table on CUDA).

#include "lw/kernels/host_device.h"

#include <cstdint>

namespace lw::kernels {

LW_HOST_DEVICE inline std::uint64_t pointBitsHash(std::uint32_t x, std::uint32_t y,
                                                  std::uint32_t z) {
    std::uint64_t h = 0x9E3779B97F4A7C15ull * (1ull + x);
    h = (h ^ (h >> 31)) + 0xBF58476D1CE4E5B9ull * (1ull + y);
    h = (h ^ (h >> 29)) + 0x94D049BB133111EBull * (1ull + z);
    return h ^ (h >> 32);
}

} // namespace lw::kernels
