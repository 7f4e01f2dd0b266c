#pragma once

// A volume as a kernel sees it: a pointer to the voxels (host or device memory), their type and
// dims, x fastest. No lw::volume types, so the CUDA back-end's translation units stay plain C++17;
// the geometry travels separately as a VoxelGridSetup (voxel_grid.h).

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>

namespace lw::kernels {

// The same four types as lw::volume::VoxelType, in the same order.
enum class VoxelKind : std::uint8_t { UInt8, Int16, UInt16, Float32 };

inline constexpr std::size_t voxelKindSize(VoxelKind kind) {
    return kind == VoxelKind::UInt8 ? 1 : (kind == VoxelKind::Float32 ? 4 : 2);
}

struct VolumeView {
    const void* voxels = nullptr;
    VoxelKind kind = VoxelKind::Int16;
    glm::ivec3 dims{0};

    std::size_t voxelCount() const {
        return std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
    }
    std::size_t byteCount() const { return voxelCount() * voxelKindSize(kind); }
};

// Calls f(T{}) with the C++ type of `kind` (host code; CUDA dispatch uses it too).
template <typename F> decltype(auto) dispatchVoxelKind(VoxelKind kind, F&& f) {
    switch (kind) {
    case VoxelKind::UInt8: return f(std::uint8_t{});
    case VoxelKind::Int16: return f(std::int16_t{});
    case VoxelKind::UInt16: return f(std::uint16_t{});
    case VoxelKind::Float32: break;
    }
    return f(float{});
}

} // namespace lw::kernels
