#include "lw/volume/volume.h"

#include "lw/core/parallel.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace lw::volume {

VoxelType parseVoxelType(std::string_view name) {
    if (name == "uint8" || name == "u8" || name == "uchar")
        return VoxelType::UInt8;
    if (name == "int16" || name == "i16" || name == "short")
        return VoxelType::Int16;
    if (name == "uint16" || name == "u16" || name == "ushort")
        return VoxelType::UInt16;
    if (name == "float32" || name == "f32" || name == "float")
        return VoxelType::Float32;
    throw core::Error("voxel type '" + std::string(name) + "'",
                      "unknown; expected uint8, int16, uint16 or float32");
}

std::size_t checkVolumeAllocation(glm::ivec3 dims, VoxelType type, const core::ImportLimits& limits,
                                  const std::string& subject, std::string_view what) {
    if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0)
        throw core::Error(subject, std::string(what) + ": dimensions must be positive, got " +
                                       std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                                       std::to_string(dims.z));
    return limits.checkedVolumeBytes(std::size_t(dims.x), std::size_t(dims.y), std::size_t(dims.z),
                                     voxelSize(type), voxelTypeName(type), subject, what);
}

Volume::Volume(glm::ivec3 dims, VoxelType type, VolumeGeometry geometry)
    : m_dims(dims), m_type(type), m_geometry(std::move(geometry)) {
    if (dims.x <= 0 || dims.y <= 0 || dims.z <= 0)
        throw core::Error("volume", "dimensions must be positive, got " + std::to_string(dims.x) +
                                        "x" + std::to_string(dims.y) + "x" +
                                        std::to_string(dims.z));
    m_voxelCount = std::size_t(dims.x) * std::size_t(dims.y) * std::size_t(dims.z);
    // Not zero-initialised: every reader overwrites all voxels, and zeroing 512 MB costs time.
    m_data = std::make_unique_for_overwrite<std::byte[]>(byteSize());
}

Volume Volume::clone() const {
    Volume copy;
    copy.m_dims = m_dims;
    copy.m_type = m_type;
    copy.m_voxelCount = m_voxelCount;
    if (m_data) {
        copy.m_data = std::make_unique_for_overwrite<std::byte[]>(byteSize());
        std::memcpy(copy.m_data.get(), m_data.get(), byteSize());
    }
    copy.m_geometry = m_geometry;
    copy.m_mapping = m_mapping;
    copy.m_description = m_description;
    return copy;
}

void Volume::checkType(VoxelType requested) const {
    if (requested != m_type)
        throw core::Error("volume", "voxels are " + std::string(voxelTypeName(m_type)) + ", not " +
                                        std::string(voxelTypeName(requested)));
}

double Volume::storedValue(int x, int y, int z) const {
    return dispatchVoxelType(m_type, [&](auto tag) {
        using T = decltype(tag);
        return double(reinterpret_cast<const T*>(m_data.get())[index(x, y, z)]);
    });
}

ValueRange Volume::storedRange() const {
    if (isEmpty())
        return {};
    return dispatchVoxelType(m_type, [&](auto tag) {
        using T = decltype(tag);
        const T* voxels = reinterpret_cast<const T*>(m_data.get());
        const std::size_t slices = std::size_t(m_dims.z);
        const std::size_t perSlice = std::size_t(m_dims.x) * std::size_t(m_dims.y);
        std::vector<ValueRange> partial(slices);
        core::parallelFor(slices, [&](std::size_t z) {
            const T* p = voxels + z * perSlice;
            T lo = p[0], hi = p[0];
            for (std::size_t i = 1; i < perSlice; ++i) {
                lo = std::min(lo, p[i]);
                hi = std::max(hi, p[i]);
            }
            partial[z] = {double(lo), double(hi)};
        });
        ValueRange range = partial[0];
        for (const auto& r : partial) {
            range.min = std::min(range.min, r.min);
            range.max = std::max(range.max, r.max);
        }
        return range;
    });
}

ValueRange Volume::realRange() const {
    const ValueRange stored = storedRange();
    const double a = m_mapping.toReal(stored.min), b = m_mapping.toReal(stored.max);
    return {std::min(a, b), std::max(a, b)};
}

Histogram Volume::histogram(int binCount) const {
    Histogram h;
    if (isEmpty() || binCount <= 0)
        return h;
    const ValueRange range = realRange();
    h.min = range.min;
    h.binWidth = range.max > range.min ? (range.max - range.min) / binCount : 1.0;
    h.counts.assign(std::size_t(binCount), 0);
    dispatchVoxelType(m_type, [&](auto tag) {
        using T = decltype(tag);
        const T* voxels = reinterpret_cast<const T*>(m_data.get());
        const double scale = m_mapping.slope / h.binWidth;
        const double shift = (m_mapping.intercept - h.min) / h.binWidth;
        for (std::size_t i = 0; i < m_voxelCount; ++i) {
            const double bin = double(voxels[i]) * scale + shift;
            if (!(bin == bin))
                continue; // NaN voxels (float volumes) belong to no bin
            const auto b = long(std::clamp(bin, 0.0, double(binCount - 1)));
            ++h.counts[std::size_t(b)];
        }
    });
    return h;
}

} // namespace lw::volume
