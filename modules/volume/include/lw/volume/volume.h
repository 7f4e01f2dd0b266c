#pragma once

#include "lw/core/limits.h"
#include "lw/volume/volume_geometry.h"
#include "lw/volume/voxel_type.h"

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <vector>

namespace lw::volume {

// Stored value -> real value (HU for CT): real = stored * slope + intercept.
struct ValueMapping {
    double slope = 1.0;
    double intercept = 0.0;

    double toReal(double stored) const { return stored * slope + intercept; }
    double toStored(double real) const { return (real - intercept) / slope; }
    bool isIdentity() const { return slope == 1.0 && intercept == 0.0; }
};

struct ValueRange {
    double min = 0.0;
    double max = 0.0;
};

struct Histogram {
    double min = 0.0;      // real value at the lower edge of bin 0
    double binWidth = 1.0; // in real units
    std::vector<std::uint64_t> counts;
};

// The bytes of a volume of `dims` voxels of `type`, asked by every path that makes one (readers,
// DICOM assembly, the phantom, finer and shape-based copies) BEFORE it allocates: throws
// core::Error(subject, "<what> (1024×1024×4096 int16) = 8.0 GiB is more than the limit of ...")
// over limits.maxBytes, and for dimensions below 1.
std::size_t checkVolumeAllocation(glm::ivec3 dims, VoxelType type, const core::ImportLimits& limits,
                                  const std::string& subject, std::string_view what = "the volume");

// A 3D scalar grid in its loaded voxel type, x fastest then y then z (index = x + nx*(y + ny*z)).
// Move-only: copying a CT volume by accident would be expensive, clone() says it on purpose.
class Volume {
public:
    Volume() = default;
    Volume(glm::ivec3 dims, VoxelType type, VolumeGeometry geometry = {});

    Volume(Volume&&) noexcept = default;
    Volume& operator=(Volume&&) noexcept = default;
    Volume(const Volume&) = delete;
    Volume& operator=(const Volume&) = delete;
    Volume clone() const;

    bool isEmpty() const { return m_voxelCount == 0; }
    glm::ivec3 dims() const { return m_dims; }
    VoxelType voxelType() const { return m_type; }
    std::size_t voxelCount() const { return m_voxelCount; }
    std::size_t byteSize() const { return m_voxelCount * voxelSize(m_type); }
    std::size_t index(int x, int y, int z) const {
        return std::size_t(x) +
               std::size_t(m_dims.x) * (std::size_t(y) + std::size_t(m_dims.y) * std::size_t(z));
    }

    std::byte* data() { return m_data.get(); }
    const std::byte* data() const { return m_data.get(); }
    // Typed access; throws when T is not the volume's voxel type.
    template <typename T> T* dataAs() {
        checkType(voxelTypeOf<T>());
        return reinterpret_cast<T*>(m_data.get());
    }
    template <typename T> const T* dataAs() const {
        checkType(voxelTypeOf<T>());
        return reinterpret_cast<const T*>(m_data.get());
    }
    std::byte* sliceData(int z) { return m_data.get() + index(0, 0, z) * voxelSize(m_type); }
    const std::byte* sliceData(int z) const {
        return m_data.get() + index(0, 0, z) * voxelSize(m_type);
    }

    // Stored value at a voxel as double (slow path: tests and tools, not kernels).
    double storedValue(int x, int y, int z) const;

    const VolumeGeometry& geometry() const { return m_geometry; }
    void setGeometry(VolumeGeometry geometry) { m_geometry = std::move(geometry); }
    const ValueMapping& valueMapping() const { return m_mapping; }
    void setValueMapping(ValueMapping mapping) { m_mapping = mapping; }

    const std::string& description() const { return m_description; }
    void setDescription(std::string text) { m_description = std::move(text); }

    // Min/max of the stored values (multi-threaded scan of the voxels).
    ValueRange storedRange() const;
    // Min/max in real units (after the value mapping).
    ValueRange realRange() const;
    Histogram histogram(int binCount = 256) const;

private:
    void checkType(VoxelType requested) const;

    glm::ivec3 m_dims{0};
    VoxelType m_type = VoxelType::UInt8;
    std::size_t m_voxelCount = 0;
    std::unique_ptr<std::byte[]> m_data;
    VolumeGeometry m_geometry;
    ValueMapping m_mapping;
    std::string m_description;
};

} // namespace lw::volume
