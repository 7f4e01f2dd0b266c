#pragma once

// A float volume sampled from value(x, y, z) at its voxel indices (the render tests' analytic
// and noisy fields), with an optional geometry (tilt, uneven gaps).

#include "filled_volume.h"

#include <utility>

namespace lw::render::test {

template <typename F>
volume::Volume makeFloatVolume(glm::ivec3 dims, F&& value, volume::VolumeGeometry geometry = {}) {
    return lw::test::makeFilledVolume<float>(dims, std::forward<F>(value), std::move(geometry));
}

} // namespace lw::render::test
