// Kept device meshes (device_mesh_store.h): one exact allocation per mesh, laid out as
//   [ positions: vertexCount vec3 | normals: vertexCount vec3 | indices: 3 * triangleCount u32 ]
// (every part 4-byte aligned, which is all the kernels' loads need).

#include "dispatch.h"
#include "lw/kernels/cuda/device_mesh_store.h"

#include <vector>

namespace lw::kernels::cuda {

namespace {

// One mesh's allocation, freed with it.
class KeptMesh {
public:
    KeptMesh() = default;
    ~KeptMesh() {
        if (m_bytes)
            cudaFree(m_bytes);
    }
    KeptMesh(const KeptMesh&) = delete;
    KeptMesh& operator=(const KeptMesh&) = delete;
    KeptMesh(KeptMesh&& other) noexcept
        : m_bytes(std::exchange(other.m_bytes, nullptr)), m_size(other.m_size),
          m_view(other.m_view) {}

    CudaStatus copy(const DeviceMeshView& mesh, cudaStream_t stream) {
        const std::size_t vertexBytes = mesh.vertexCount * sizeof(glm::vec3);
        const std::size_t indexBytes = mesh.triangleCount * 3 * sizeof(std::uint32_t);
        m_size = 2 * vertexBytes + indexBytes;
        void* p = nullptr;
        const cudaError_t error = cudaMalloc(&p, m_size);
        if (error != cudaSuccess) {
            cudaGetLastError(); // an allocation failure is not sticky
            return dispatch::statusOf(error, "cudaMalloc(kept mesh)");
        }
        m_bytes = static_cast<unsigned char*>(p);
        LW_CUDA_TRY(
            cudaMemcpyAsync(m_bytes, mesh.positions, vertexBytes, cudaMemcpyDeviceToDevice, stream),
            "cudaMemcpy(kept positions)");
        LW_CUDA_TRY(cudaMemcpyAsync(m_bytes + vertexBytes, mesh.normals, vertexBytes,
                                    cudaMemcpyDeviceToDevice, stream),
                    "cudaMemcpy(kept normals)");
        LW_CUDA_TRY(cudaMemcpyAsync(m_bytes + 2 * vertexBytes, mesh.indices, indexBytes,
                                    cudaMemcpyDeviceToDevice, stream),
                    "cudaMemcpy(kept indices)");
        LW_CUDA_TRY(cudaStreamSynchronize(stream), "cudaMemcpy(kept mesh)");
        m_view = mesh;
        m_view.positions = reinterpret_cast<const glm::vec3*>(m_bytes);
        m_view.normals = reinterpret_cast<const glm::vec3*>(m_bytes + vertexBytes);
        m_view.indices = reinterpret_cast<const std::uint32_t*>(m_bytes + 2 * vertexBytes);
        return CudaStatus::success();
    }
    const DeviceMeshView& view() const { return m_view; }
    std::size_t bytes() const { return m_size; }

private:
    unsigned char* m_bytes = nullptr;
    std::size_t m_size = 0;
    DeviceMeshView m_view;
};

} // namespace

struct DeviceMeshStore::Impl {
    dispatch::Stream stream;
    std::vector<KeptMesh> meshes;
    std::size_t bytes = 0;
};

DeviceMeshStore::DeviceMeshStore() : m_impl(std::make_unique<Impl>()) {}
DeviceMeshStore::~DeviceMeshStore() = default;

std::size_t DeviceMeshStore::bytesOf(const DeviceMeshView& mesh) {
    return 2 * mesh.vertexCount * sizeof(glm::vec3) +
           mesh.triangleCount * 3 * sizeof(std::uint32_t);
}

CudaStatus DeviceMeshStore::keep(const DeviceMeshView& mesh) {
    Impl& s = *m_impl;
    LW_RETURN_IF_FAILED(s.stream.create());
    KeptMesh kept;
    LW_RETURN_IF_FAILED(kept.copy(mesh, s.stream.get()));
    s.bytes += kept.bytes();
    s.meshes.push_back(std::move(kept));
    return CudaStatus::success();
}

std::size_t DeviceMeshStore::count() const {
    return m_impl->meshes.size();
}

const DeviceMeshView& DeviceMeshStore::mesh(std::size_t index) const {
    return m_impl->meshes.at(index).view();
}

std::size_t DeviceMeshStore::deviceBytes() const {
    return m_impl->bytes;
}

void DeviceMeshStore::clear() {
    m_impl->meshes.clear();
    m_impl->bytes = 0;
}

} // namespace lw::kernels::cuda
