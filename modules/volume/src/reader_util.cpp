#include "reader_util.h"

#include <algorithm>
#include <bit>
#include <cctype>
#include <charconv>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace lw::volume::detail {

void fail(const std::filesystem::path& path, const std::string& reason) {
    throw core::Error(path.string(), reason);
}

std::string describeShape(glm::ivec3 dims, VoxelType type) {
    return std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z) +
           " " + std::string(voxelTypeName(type));
}

std::size_t checkVolumeSize(const std::filesystem::path& path, glm::ivec3 dims,
                            std::size_t sourceElementSize, VoxelType target,
                            const core::ImportLimits& limits) {
    static constexpr const char* kAxes[3] = {"size along x", "size along y", "size along z"};
    for (int axis = 0; axis < 3; ++axis)
        limits.checkDimension(dims[axis], path.string(), kAxes[axis]);
    const std::size_t x = std::size_t(dims.x), y = std::size_t(dims.y), z = std::size_t(dims.z);
    checkVolumeAllocation(dims, target, limits, path.string());
    return limits.checkedBytes({x, y, z, sourceElementSize}, path.string(), "the image data");
}

bool hostIsLittleEndian() {
    return std::endian::native == std::endian::little;
}

void swapBytesInPlace(std::byte* data, std::size_t count, std::size_t elementSize) {
    switch (elementSize) {
    case 2:
        for (std::size_t i = 0; i < count; ++i) {
            std::uint16_t v;
            std::memcpy(&v, data + 2 * i, 2);
            v = std::uint16_t((v >> 8) | (v << 8));
            std::memcpy(data + 2 * i, &v, 2);
        }
        break;
    case 4:
        for (std::size_t i = 0; i < count; ++i) {
            std::uint32_t v;
            std::memcpy(&v, data + 4 * i, 4);
            v = __builtin_bswap32(v);
            std::memcpy(data + 4 * i, &v, 4);
        }
        break;
    case 8:
        for (std::size_t i = 0; i < count; ++i) {
            std::uint64_t v;
            std::memcpy(&v, data + 8 * i, 8);
            v = __builtin_bswap64(v);
            std::memcpy(data + 8 * i, &v, 8);
        }
        break;
    default:
        break;
    }
}

void fillVolume(Volume& volume, const std::byte* source, bool sourceBigEndian) {
    std::memcpy(volume.data(), source, volume.byteSize());
    const std::size_t size = voxelSize(volume.voxelType());
    if (size > 1 && sourceBigEndian == hostIsLittleEndian())
        swapBytesInPlace(volume.data(), volume.voxelCount(), size);
}

std::size_t sourceTypeSize(SourceType type) {
    switch (type) {
    case SourceType::UInt8:
    case SourceType::Int8:
        return 1;
    case SourceType::Int16:
    case SourceType::UInt16:
        return 2;
    case SourceType::Int32:
    case SourceType::UInt32:
    case SourceType::Float32:
        return 4;
    case SourceType::Float64:
        return 8;
    }
    return 1;
}

VoxelType targetVoxelType(SourceType type) {
    switch (type) {
    case SourceType::UInt8:
        return VoxelType::UInt8;
    case SourceType::Int8:
    case SourceType::Int16:
        return VoxelType::Int16;
    case SourceType::UInt16:
        return VoxelType::UInt16;
    case SourceType::Int32:
    case SourceType::UInt32:
    case SourceType::Float32:
    case SourceType::Float64:
        return VoxelType::Float32;
    }
    return VoxelType::UInt8;
}

namespace {

template <typename From, typename To>
void convertElements(const std::byte* source, To* target, std::size_t count, bool swap) {
    for (std::size_t i = 0; i < count; ++i) {
        std::byte raw[sizeof(From)];
        std::memcpy(raw, source + i * sizeof(From), sizeof(From));
        if (swap)
            std::reverse(raw, raw + sizeof(From));
        From value;
        std::memcpy(&value, raw, sizeof(From));
        target[i] = static_cast<To>(value);
    }
}

} // namespace

Volume makeVolume(glm::ivec3 dims, SourceType type, const std::byte* source, bool sourceBigEndian,
                  VolumeGeometry geometry) {
    Volume volume(dims, targetVoxelType(type), std::move(geometry));
    const bool swap = sourceBigEndian == hostIsLittleEndian();
    const std::size_t n = volume.voxelCount();
    switch (type) {
    case SourceType::UInt8:
    case SourceType::Int16:
    case SourceType::UInt16:
    case SourceType::Float32:
        fillVolume(volume, source, sourceBigEndian);
        break;
    case SourceType::Int8:
        convertElements<std::int8_t>(source, volume.dataAs<std::int16_t>(), n, false);
        break;
    case SourceType::Int32:
        convertElements<std::int32_t>(source, volume.dataAs<float>(), n, swap);
        break;
    case SourceType::UInt32:
        convertElements<std::uint32_t>(source, volume.dataAs<float>(), n, swap);
        break;
    case SourceType::Float64:
        convertElements<double>(source, volume.dataAs<float>(), n, swap);
        break;
    }
    return volume;
}

std::string_view trim(std::string_view text) {
    const auto isSpace = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
    while (!text.empty() && isSpace(text.front()))
        text.remove_prefix(1);
    while (!text.empty() && isSpace(text.back()))
        text.remove_suffix(1);
    return text;
}

std::string toLower(std::string_view text) {
    std::string out(text);
    std::transform(out.begin(), out.end(), out.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    return out;
}

std::vector<std::string> splitWhitespace(std::string_view text) {
    std::vector<std::string> parts;
    std::size_t i = 0;
    while (i < text.size()) {
        while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i])))
            ++i;
        const std::size_t start = i;
        while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i])))
            ++i;
        if (i > start)
            parts.emplace_back(text.substr(start, i - start));
    }
    return parts;
}

std::optional<long long> parseInteger(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+')
        text.remove_prefix(1);
    long long value = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty())
        return std::nullopt;
    return value;
}

std::optional<double> parseDouble(std::string_view text) {
    text = trim(text);
    if (!text.empty() && text.front() == '+')
        text.remove_prefix(1);
    const std::string lower = toLower(text);
    if (lower == "nan")
        return std::numeric_limits<double>::quiet_NaN();
    double value = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || end != text.data() + text.size() || text.empty())
        return std::nullopt;
    return value;
}

} // namespace lw::volume::detail
