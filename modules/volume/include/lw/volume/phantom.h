#pragma once

#include "lw/core/progress.h"
#include "lw/volume/volume.h"

#include <cstdint>
#include <string_view>

namespace lw::volume {

// The deterministic CT-like benchmark phantom of ../shared/tools/phantom.py, reproduced voxel
// for voxel (within +-1 HU: float32 exp/sin/cos of numpy and libm may round differently).
enum class PhantomKind { Ct, Sphere };

PhantomKind parsePhantomKind(std::string_view name); // "ct" | "sphere", throws core::Error
std::string_view phantomKindName(PhantomKind kind);

// int16 HU volume of nx x ny x nz voxels. Each axis spans [-1, 1] in phantom units; the
// geometry gives it 1 mm voxels centred on the patient origin, identity value mapping.
// Generated slice-parallel on all cores (`threads` = 0) or the given number of threads.
// Throws core::Error before allocating when the volume is larger than `limits` allows.
// `progress` (optional) is stepped once per slice (z), and its cancel token is checked before
// each slice: a cancelled token stops the slices not yet started and throws core::Cancelled.
volume::Volume makePhantom(glm::ivec3 dims, PhantomKind kind, unsigned threads = 0,
                           const core::ImportLimits& limits = {},
                           core::Progress* progress = nullptr);

// phantom.py's checksums: the sum of all voxels and the number of voxels above 300.5 HU.
struct PhantomChecksum {
    std::int64_t sum = 0;
    std::int64_t above = 0;
};
PhantomChecksum phantomChecksum(const volume::Volume& volume, double iso = 300.5);

// The bone iso-value phantom.py names.
inline constexpr double kPhantomBoneIso = 300.5;

} // namespace lw::volume
