#pragma once

// A float volume sampled from value(x, y, z) at its voxel indices (the render tests' analytic
// and noisy fields), with an optional geometry (tilt, uneven gaps).

#include "lw/volume/volume.h"

#include <glm/glm.hpp>
#include <utility>

namespace lw::render::test {

template <typename F>
volume::Volume makeFloatVolume(glm::ivec3 dims, F&& value, volume::VolumeGeometry geometry = {}) {
    volume::Volume v(dims, volume::VoxelType::Float32, std::move(geometry));
    float* data = v.dataAs<float>();
    for (int z = 0; z < dims.z; ++z)
        for (int y = 0; y < dims.y; ++y)
            for (int x = 0; x < dims.x; ++x)
                data[v.index(x, y, z)] = float(value(x, y, z));
    return v;
}

} // namespace lw::render::test
