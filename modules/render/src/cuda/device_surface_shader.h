#pragma once

// The iso panel shaded on the CUDA device from a surface that is already there (method 3's kept
// mesh, method 1's CUDA extraction) and its border cap: kernels::cuda::SurfaceShadingCuda with
// the render module's shading and image types. Internal to the CUDA back-end's sources.

#include "lw/core/image.h"
#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/cuda/surface_shading_cuda.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/shaded_surface_cpu.h"

#include <cstddef>
#include <vector>

namespace lw::render {

class DeviceSurfaceShader {
public:
    struct Shaded {
        std::size_t triangles = 0;
        double rasterMs = 0.0, shadeMs = 0.0; // CUDA events
    };

    // `mesh` then `cap` (host memory, small; null: none) lit at `camera` into `image` (sized to
    // the camera) and `depth` (optional; shadeSurfaceCpu's). The cap is copied to the device when
    // it is not the one copied last: forgetCap() after the caller's cap changed in place.
    kernels::cuda::CudaStatus shade(const Camera& camera, const SurfaceShading& shading,
                                    const kernels::cuda::DeviceMeshView& mesh, const Mesh* cap,
                                    core::ImageRgba8& image, std::vector<float>* depth,
                                    Shaded& shaded);
    void forgetCap() { m_capOnDevice = nullptr; }
    std::size_t deviceBytes() const { return m_shading.deviceBytes(); }
    void release() {
        m_shading.release();
        m_capOnDevice = nullptr;
    }

private:
    kernels::cuda::SurfaceShadingCuda m_shading;
    const Mesh* m_capOnDevice = nullptr;
};

} // namespace lw::render
