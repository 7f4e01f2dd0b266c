#pragma once

// Private helpers shared by the volume readers: byte order, bounded parsing and checked
// arithmetic. Every reader funnels failures through fail() so messages name the file.

#include "lw/core/error.h"
#include "lw/core/limits.h"
#include "lw/core/module_boundary.h"
#include "lw/volume/volume.h"

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lw::volume::detail {

[[noreturn]] void fail(const std::filesystem::path& path, const std::string& reason);

// "64x64x93 int16" for messages.
std::string describeShape(glm::ivec3 dims, VoxelType type);

// The one size check of every volume reader, made from the header before anything is read or
// allocated: each axis within limits.maxDimension, and both the data as stored (dims x
// sourceElementSize) and the volume made from it (dims x the target type's size) within
// limits.maxBytes, the products checked for overflow. Returns the stored data's byte count.
std::size_t checkVolumeSize(const std::filesystem::path& path, glm::ivec3 dims,
                            std::size_t sourceElementSize, VoxelType target,
                            const core::ImportLimits& limits);

bool hostIsLittleEndian();
// Reverses the bytes of every element of `elementSize` (2, 4 or 8) in place.
void swapBytesInPlace(std::byte* data, std::size_t count, std::size_t elementSize);

// Copies `volume.byteSize()` bytes from `source` into the volume and fixes the byte order.
void fillVolume(Volume& volume, const std::byte* source, bool sourceBigEndian);

// Element types as files store them. Types the Volume cannot hold are widened or converted:
// int8 -> int16 (exact), int32/uint32/float64 -> float32 (CT and most scalar data survive).
enum class SourceType { UInt8, Int8, Int16, UInt16, Int32, UInt32, Float32, Float64 };
std::size_t sourceTypeSize(SourceType type);
VoxelType targetVoxelType(SourceType type);
// Creates the volume and fills it from `source` (at least dims * sourceTypeSize bytes).
Volume makeVolume(glm::ivec3 dims, SourceType type, const std::byte* source, bool sourceBigEndian,
                  VolumeGeometry geometry);

std::string_view trim(std::string_view text);
std::string toLower(std::string_view text);
std::vector<std::string> splitWhitespace(std::string_view text);

// Whole-string numeric parsing; nullopt for garbage or trailing characters.
std::optional<long long> parseInteger(std::string_view text);
std::optional<double> parseDouble(std::string_view text);

} // namespace lw::volume::detail
