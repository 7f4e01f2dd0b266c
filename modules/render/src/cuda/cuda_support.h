#pragma once

// What the CUDA kernel sets share: failed statuses as errors, the closed surface downloaded and
// the host volume as the kernels see it.

#include "lw/core/error.h"
#include "lw/core/limits.h"
#include "lw/kernels/cpu/border_cap_cpu.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/kernels/cuda/contour_triangles_cuda.h"
#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/volume_view.h"
#include "lw/render/camera.h"
#include "lw/render/contour_triangles.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/volume/volume.h"

#include <memory>
#include <string>
#include <string_view>

namespace lw::render {

// A failed status as core::Error("<where>", "<kernel or call>: <CUDA error>").
inline void throwIfCudaFailed(std::string_view where, const kernels::cuda::CudaStatus& status) {
    if (!status.ok())
        throw core::Error(std::string(where), status.describe());
}

// The device mesh of the last extraction in host memory, with the border cap (host memory, or
// null when the surface is left open) appended after it: the closed surface every back-end draws.
// The host copy is counted first (the device knows its size) and refused over the host's
// ImportLimits, before anything is allocated for it.
inline void downloadSurface(std::string_view where, const kernels::cuda::MarchingCubesCuda& mc,
                            const Mesh* cap, Mesh& mesh) {
    const kernels::cuda::DeviceMeshView device = mc.mesh();
    const std::size_t capVertices = cap ? cap->vertexCount() : 0;
    const std::size_t capTriangles = cap ? cap->triangleCount() : 0;
    const std::size_t vertices = device.vertexCount + capVertices;
    const std::size_t triangles = device.triangleCount + capTriangles;
    core::ImportLimits().checkAllocation(std::size_t(kernels::meshBytes(vertices, triangles)),
                                         std::to_string(vertices) + " vertices, " +
                                             std::to_string(triangles) + " triangles",
                                         std::string(where), "the mesh's host copy");
    // Room for the cap first: download() resizes within it, and appending does not reallocate.
    mesh.positions.reserve(vertices);
    mesh.normals.reserve(vertices);
    mesh.indices.reserve(3 * triangles);
    throwIfCudaFailed(where, mc.download(mesh.positions, mesh.normals, mesh.indices));
    if (cap)
        kernels::cpu::appendMesh(mesh, *cap);
}

// Of that closed surface, only the triangles that may hold `camera`'s contour
// (contour_triangles.h): the device mesh's selected and downloaded by `contour`, the cap's
// selected on the host, in the order downloadSurface joins them.
inline kernels::cuda::CudaStatus
downloadContourTriangles(kernels::cuda::ContourTrianglesCuda& contour,
                         const kernels::cuda::MarchingCubesCuda& mc, const Mesh* cap,
                         const Camera& camera, Mesh& part) {
    const glm::vec4 viewer = camera.viewerHomogeneous();
    const kernels::cuda::CudaStatus status =
        contour.download(mc.mesh(), viewer, part.positions, part.normals);
    if (!status.ok())
        return status;
    if (cap)
        appendContourTriangles(*cap, viewer, part);
    numberCorners(part);
    return status;
}

inline kernels::VolumeView hostVolumeView(const volume::Volume& volume) {
    static_assert(int(kernels::VoxelKind::UInt8) == int(volume::VoxelType::UInt8) &&
                  int(kernels::VoxelKind::Int16) == int(volume::VoxelType::Int16) &&
                  int(kernels::VoxelKind::UInt16) == int(volume::VoxelType::UInt16) &&
                  int(kernels::VoxelKind::Float32) == int(volume::VoxelType::Float32));
    kernels::VolumeView view;
    view.voxels = volume.data();
    view.kind = kernels::VoxelKind(volume.voxelType());
    view.dims = volume.dims();
    return view;
}

// The volume onto the device for whole-volume marching cubes: device to device where `copy` holds
// its voxels there already (SilhouetteRenderer::setVolumeWithDeviceCopy), else from the host.
inline kernels::cuda::CudaStatus placeWholeVolume(kernels::cuda::MarchingCubesCuda& mc,
                                                  const volume::Volume& volume,
                                                  DeviceVoxelCopy copy) {
    kernels::VolumeView view = hostVolumeView(volume);
    const kernels::VoxelGridSetup setup = kernels::cpu::voxelGridSetup(volume);
    if (!copy.voxels)
        return mc.setVolume(view, setup);
    view.voxels = copy.voxels;
    return mc.setDeviceVolume(view, setup);
}

} // namespace lw::render
