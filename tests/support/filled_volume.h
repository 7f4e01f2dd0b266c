#pragma once

// A volume of voxel type T sampled from value(x, y, z) at its voxel indices, with an optional
// geometry (tilt, uneven gaps): the analytic, noisy and trilinear fields of the volume and render
// tests. Header-only: the tests that use it link lw_volume themselves.

#include "lw/volume/volume.h"
#include "lw/volume/voxel_type.h"

#include <glm/glm.hpp>
#include <utility>

namespace lw::test {

template <typename T, typename F>
volume::Volume makeFilledVolume(glm::ivec3 dims, F&& value, volume::VolumeGeometry geometry = {}) {
    volume::Volume v(dims, volume::voxelTypeOf<T>(), std::move(geometry));
    T* data = v.dataAs<T>();
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                data[v.index(x, y, z)] = T(value(x, y, z));
    return v;
}

} // namespace lw::test
