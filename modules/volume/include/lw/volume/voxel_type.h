#pragma once

#include "lw/core/error.h"

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <type_traits>

namespace lw::volume {

// Voxels stay in the type they were loaded in: CT is int16 or uint16 and converting a
// 512x512x1024 series to float would double its memory for nothing.
enum class VoxelType : std::uint8_t { UInt8, Int16, UInt16, Float32 };

constexpr std::size_t voxelSize(VoxelType type) {
    switch (type) {
    case VoxelType::UInt8: return 1;
    case VoxelType::Int16:
    case VoxelType::UInt16: return 2;
    case VoxelType::Float32: return 4;
    }
    return 0;
}

constexpr std::string_view voxelTypeName(VoxelType type) {
    switch (type) {
    case VoxelType::UInt8: return "uint8";
    case VoxelType::Int16: return "int16";
    case VoxelType::UInt16: return "uint16";
    case VoxelType::Float32: return "float32";
    }
    return "?";
}

// Parses "uint8", "int16", "uint16", "float32" (and the short forms u8, i16, u16, f32).
VoxelType parseVoxelType(std::string_view name);

template <typename T> constexpr VoxelType voxelTypeOf() {
    if constexpr (std::is_same_v<T, std::uint8_t>)
        return VoxelType::UInt8;
    else if constexpr (std::is_same_v<T, std::int16_t>)
        return VoxelType::Int16;
    else if constexpr (std::is_same_v<T, std::uint16_t>)
        return VoxelType::UInt16;
    else if constexpr (std::is_same_v<T, float>)
        return VoxelType::Float32;
    else
        static_assert(sizeof(T) == 0, "unsupported voxel type");
}

// Calls f(T{}) with the C++ type of `type`, so one template serves every voxel type.
template <typename F> decltype(auto) dispatchVoxelType(VoxelType type, F&& f) {
    switch (type) {
    case VoxelType::UInt8: return f(std::uint8_t{});
    case VoxelType::Int16: return f(std::int16_t{});
    case VoxelType::UInt16: return f(std::uint16_t{});
    case VoxelType::Float32: return f(float{});
    }
    throw core::Error("voxel type", "unknown voxel type");
}

} // namespace lw::volume
