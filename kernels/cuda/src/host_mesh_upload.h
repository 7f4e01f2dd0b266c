#pragma once

// A small host mesh kept on the device (the border cap that method 3 and the shaded iso panel
// draw after the surface): three device buffers, grown on demand, and the view of them.
// Internal: CUDA types allowed.

#include "dispatch.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "lw/kernels/triangle_mesh.h"

#include <cstddef>
#include <cstdint>

namespace lw::kernels::cuda {

class HostMeshUpload {
public:
    // Queues the copies of `mesh` on `stream`; view() shows it from then on (empty for an empty
    // mesh). From pageable host memory each copy has left `mesh` when its call returns (CUDA
    // stages it), so the caller may change the mesh afterwards; work queued later on `stream`
    // sees the copy.
    CudaStatus upload(const TriangleMesh& mesh, cudaStream_t stream) {
        m_view = DeviceMeshView();
        if (mesh.isEmpty())
            return CudaStatus::success();
        const std::size_t vertices = mesh.vertexCount();
        LW_RETURN_IF_FAILED(m_positions.reserve(vertices, "cudaMalloc(hostPositions)"));
        LW_RETURN_IF_FAILED(m_normals.reserve(vertices, "cudaMalloc(hostNormals)"));
        LW_RETURN_IF_FAILED(m_indices.reserve(mesh.indices.size(), "cudaMalloc(hostIndices)"));
        LW_CUDA_TRY(cudaMemcpyAsync(m_positions.data(), mesh.positions.data(),
                                    vertices * sizeof(glm::vec3), cudaMemcpyHostToDevice, stream),
                    "cudaMemcpy(hostPositions)");
        LW_CUDA_TRY(cudaMemcpyAsync(m_normals.data(), mesh.normals.data(),
                                    vertices * sizeof(glm::vec3), cudaMemcpyHostToDevice, stream),
                    "cudaMemcpy(hostNormals)");
        LW_CUDA_TRY(cudaMemcpyAsync(m_indices.data(), mesh.indices.data(),
                                    mesh.indices.size() * sizeof(std::uint32_t),
                                    cudaMemcpyHostToDevice, stream),
                    "cudaMemcpy(hostIndices)");
        m_view.positions = m_positions.data();
        m_view.normals = m_normals.data();
        m_view.indices = m_indices.data();
        m_view.vertexCount = vertices;
        m_view.triangleCount = mesh.triangleCount();
        return CudaStatus::success();
    }
    const DeviceMeshView& view() const { return m_view; }
    std::size_t bytes() const {
        return m_positions.bytes() + m_normals.bytes() + m_indices.bytes();
    }

private:
    dispatch::DeviceBuffer<glm::vec3> m_positions, m_normals;
    dispatch::DeviceBuffer<std::uint32_t> m_indices;
    DeviceMeshView m_view; // in the buffers above (empty: none kept)
};

} // namespace lw::kernels::cuda
