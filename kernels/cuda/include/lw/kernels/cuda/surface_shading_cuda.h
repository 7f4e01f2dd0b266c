#pragma once

// The shaded iso panel on the GPU: the surface that method 3 keeps on the device, rasterized at
// the panel's camera and lit per pixel, so that only the finished image (and its depth, for
// picking) leaves the device. The rules are the CPU reference's (render/shaded_surface_cpu.h):
//   project   per vertex: fixed-point screen position, depth key and 1/w (zbuffer_rules.h)
//   nearest   per triangle: covered pixel centres, (key bits << 32 | triangle + 1) kept by a
//             64-bit atomicMax, so equal depths go to the larger triangle whatever the order
//   shade     per pixel: perspective-correct barycentrics from the snapped vertices, the
//             interpolated normal lit Blinn-Phong (or a headlight), two-sided, and the depth as
//             a GL depth buffer holds it
// Up to kMaxMeshes meshes a frame (the surface and its border cap); their triangles are numbered
// one after the other, as in the host mesh that joins them. Public header: no CUDA types.

#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/triangle_mesh.h"
#include "lw/kernels/zbuffer_rules.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>

namespace lw::kernels::cuda {

// Colours in 0..255 per channel, the material as the GL panel's surface shader takes it.
struct SurfaceLighting {
    glm::dvec3 background{255.0};
    glm::dvec3 front{200.0};
    glm::dvec3 back{200.0}; // inner faces seen through a surface cut open by the border
    double ambient = 0.15, diffuse = 0.75, specular = 0.25, shininess = 32.0;
    glm::dvec3 lightDirection{0.0}; // unit, toward the light; zero: a headlight
};

struct SurfaceShadingTimes {
    double rasterMs = 0.0; // projection and nearest triangles, CUDA events
    double shadeMs = 0.0;  // lighting and the copy to the host
};

class SurfaceShadingCuda {
public:
    static constexpr int kMaxMeshes = 2;

    SurfaceShadingCuda();
    ~SurfaceShadingCuda();
    SurfaceShadingCuda(const SurfaceShadingCuda&) = delete;
    SurfaceShadingCuda& operator=(const SurfaceShadingCuda&) = delete;

    // Starts a frame at the view's size: no meshes, every pixel empty.
    CudaStatus begin(const ViewTransform& view);
    // Rasterizes `mesh` (device memory; it must stay valid until shade() returns) after the ones
    // drawn before in this frame. Fails with TooLarge beyond kMaxMeshes meshes or 2^32 triangles.
    CudaStatus draw(const DeviceMeshView& mesh);
    // A small host mesh (the border cap): copied to the device once and kept until the next
    // keepHostMesh; drawKeptHostMesh draws the copy like draw().
    CudaStatus keepHostMesh(const TriangleMesh& mesh);
    CudaStatus drawKeptHostMesh();
    // Lights every pixel into `hostRgba` (width * height * 4 bytes, top row first) and, when not
    // null, its depth into `hostDepth` ((NDC depth + 1) / 2, 1 where no surface is). Blocks until
    // both are in host memory.
    CudaStatus shade(const SurfaceLighting& lighting, std::uint8_t* hostRgba, float* hostDepth,
                     SurfaceShadingTimes& times);

    std::size_t deviceBytes() const;
    void release(); // frees every buffer

    struct Impl;

private:
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::kernels::cuda
