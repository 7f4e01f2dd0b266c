// Host dispatch of the contour triangles (kernels in contour_triangles_kernels.cuh).

#include "contour_triangles_kernels.cuh"
#include "dispatch.h"
#include "lw/kernels/cuda/contour_triangles_cuda.h"
#include "tuning.h"

#include <cub/device/device_select.cuh>
#include <limits>
#include <thrust/iterator/counting_iterator.h>

namespace lw::kernels::cuda {

using dispatch::blocksFor;
using dispatch::DeviceBuffer;

struct ContourTrianglesCuda::Impl {
    dispatch::Stream stream;
    DeviceBuffer<std::uint8_t> flags;
    DeviceBuffer<std::uint32_t> selected;
    DeviceBuffer<std::uint32_t> selectedCount;
    DeviceBuffer<std::uint8_t> selectTemp;
    DeviceBuffer<glm::vec3> positions;
    DeviceBuffer<glm::vec3> normals;
};

ContourTrianglesCuda::ContourTrianglesCuda() : m_impl(std::make_unique<Impl>()) {}
ContourTrianglesCuda::~ContourTrianglesCuda() = default;

void ContourTrianglesCuda::release() {
    m_impl = std::make_unique<Impl>();
}

CudaStatus ContourTrianglesCuda::download(const DeviceMeshView& mesh, glm::vec4 viewer,
                                          std::vector<glm::vec3>& positions,
                                          std::vector<glm::vec3>& normals) {
    if (mesh.triangleCount == 0)
        return CudaStatus::success();
    if (3 * mesh.triangleCount > std::numeric_limits<std::uint32_t>::max())
        return CudaStatus::failure(CudaStatus::Code::TooLarge, "contour::download",
                                   "more than 2^32 corners");
    Impl& s = *m_impl;
    LW_RETURN_IF_FAILED(s.stream.create());
    const cudaStream_t st = s.stream.get();
    const auto triangles = std::uint32_t(mesh.triangleCount);
    LW_RETURN_IF_FAILED(s.flags.reserve(triangles, "cudaMalloc(contour flags)"));
    LW_RETURN_IF_FAILED(s.selected.reserve(triangles, "cudaMalloc(contour selected)"));
    LW_RETURN_IF_FAILED(s.selectedCount.reserve(1, "cudaMalloc(contour count)"));
    contour::flagTriangles<<<blocksFor(triangles, tuning::kTriangleBlock), tuning::kTriangleBlock,
                             0, st>>>(mesh.positions, mesh.normals, mesh.indices, triangles, viewer,
                                      s.flags.data());
    LW_CUDA_LAUNCHED("contour::flagTriangles");
    const thrust::counting_iterator<std::uint32_t> numbers(0);
    std::size_t bytes = 0;
    LW_CUDA_TRY(cub::DeviceSelect::Flagged(nullptr, bytes, numbers, s.flags.data(),
                                           s.selected.data(), s.selectedCount.data(), triangles,
                                           st),
                "cub::DeviceSelect(contour triangles)");
    LW_RETURN_IF_FAILED(s.selectTemp.reserve(bytes, "cudaMalloc(contour select)"));
    LW_CUDA_TRY(cub::DeviceSelect::Flagged(s.selectTemp.data(), bytes, numbers, s.flags.data(),
                                           s.selected.data(), s.selectedCount.data(), triangles,
                                           st),
                "cub::DeviceSelect(contour triangles)");
    std::uint32_t count = 0;
    LW_CUDA_TRY(
        cudaMemcpyAsync(&count, s.selectedCount.data(), sizeof count, cudaMemcpyDeviceToHost, st),
        "cudaMemcpy(contour count)");
    LW_CUDA_TRY(cudaStreamSynchronize(st), "contour::select");
    if (count == 0)
        return CudaStatus::success();
    const std::size_t corners = 3 * std::size_t(count);
    LW_RETURN_IF_FAILED(s.positions.reserve(corners, "cudaMalloc(contour positions)"));
    LW_RETURN_IF_FAILED(s.normals.reserve(corners, "cudaMalloc(contour normals)"));
    contour::
        gatherCorners<<<blocksFor(corners, tuning::kVertexBlock), tuning::kVertexBlock, 0, st>>>(
            mesh.positions, mesh.normals, mesh.indices, s.selected.data(), s.selectedCount.data(),
            s.positions.data(), s.normals.data());
    LW_CUDA_LAUNCHED("contour::gatherCorners");
    const std::size_t first = positions.size();
    positions.resize(first + corners);
    normals.resize(first + corners);
    LW_CUDA_TRY(cudaMemcpyAsync(positions.data() + first, s.positions.data(),
                                corners * sizeof(glm::vec3), cudaMemcpyDeviceToHost, st),
                "cudaMemcpy(contour positions)");
    LW_CUDA_TRY(cudaMemcpyAsync(normals.data() + first, s.normals.data(),
                                corners * sizeof(glm::vec3), cudaMemcpyDeviceToHost, st),
                "cudaMemcpy(contour normals)");
    LW_CUDA_TRY(cudaStreamSynchronize(st), "contour::gatherCorners");
    return CudaStatus::success();
}

} // namespace lw::kernels::cuda
