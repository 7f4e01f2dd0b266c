#pragma once

// MarchingCubesCuda's state, shared with the other kernels of the back-end that start from its
// classification (method 2 walks its active cells). Private to kernels/cuda.

#include "dispatch.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"
#include "marching_cubes_kernels.cuh"

#include <cub/device/device_scan.cuh>

namespace lw::kernels::cuda {

using dispatch::blocksFor;
using dispatch::DeviceBuffer;

struct MarchingCubesCuda::Impl {
    dispatch::Stream stream;
    VolumeView volume;          // device voxels after setVolume (voxels points to `voxels`)
    DeviceBuffer<unsigned char> voxels;
    DeviceBuffer<double> sliceOffset;
    DeviceBuffer<float> spanK, invSpanK;
    GridSpans spans;
    McGridFrame frame{};
    std::uint32_t bricksX = 0, bricksY = 0, bricksZ = 0;
    DeviceBuffer<float2> brickMinMax;
    DeviceBuffer<std::uint8_t> brickActive;
    DeviceBuffer<int> flag;

    DeviceBuffer<std::uint32_t> tileCounts, tileOffsets;
    DeviceBuffer<std::uint32_t> activeVoxels, vertexCounts, vertexOffsets, triangleCounts,
        triangleOffsets;
    DeviceBuffer<std::uint16_t> activeCodes;
    DeviceBuffer<std::uint32_t> rowStart;
    DeviceBuffer<unsigned char> scanTemp;
    DeviceBuffer<glm::vec3> positions, normals;
    DeviceBuffer<std::uint32_t> indices;

    std::uint32_t activeCount = 0;
    DeviceMeshView mesh;
    McCudaTimes times;
    double uploadMs = 0.0;
    dispatch::StageTimer timers[4];

    std::size_t deviceBytes() const {
        return voxels.bytes() + sliceOffset.bytes() + spanK.bytes() + invSpanK.bytes() +
               brickMinMax.bytes() + brickActive.bytes() + tileCounts.bytes() +
               tileOffsets.bytes() + activeVoxels.bytes() + vertexCounts.bytes() +
               vertexOffsets.bytes() + triangleCounts.bytes() + triangleOffsets.bytes() +
               activeCodes.bytes() + rowStart.bytes() + scanTemp.bytes() + positions.bytes() + normals.bytes() +
               indices.bytes();
    }

    // CUB's exclusive sum over `count` values (temporary storage grown on demand).
    CudaStatus exclusiveSum(const std::uint32_t* in, std::uint32_t* out, std::uint32_t count,
                            const char* what) {
        std::size_t bytes = 0;
        LW_CUDA_TRY(cub::DeviceScan::ExclusiveSum(nullptr, bytes, in, out, count, stream.get()),
                    what);
        LW_RETURN_IF_FAILED(scanTemp.reserve(bytes, what));
        LW_CUDA_TRY(cub::DeviceScan::ExclusiveSum(scanTemp.data(), bytes, in, out, count,
                                                  stream.get()),
                    what);
        return CudaStatus::success();
    }

    template <typename T> mc::Grid<T> grid(double iso) const {
        mc::Grid<T> g;
        g.voxels = reinterpret_cast<const T*>(voxels.data());
        g.spans = spans;
        g.frame = frame;
        g.nx = std::uint32_t(volume.dims.x);
        g.ny = std::uint32_t(volume.dims.y);
        g.nz = std::uint32_t(volume.dims.z);
        g.voxelCount = std::uint32_t(volume.voxelCount());
        g.threshold = voxelInsideThreshold<T>(iso);
        g.iso = iso;
        g.isoF = insideThreshold(iso);
        g.brickActive = brickActive.data();
        g.bricksX = bricksX;
        g.bricksY = bricksY;
        return g;
    }

    template <typename T> CudaStatus computeBrickMinMax();
    // Active bricks, border test and the ordered active voxel list (activeVoxels/activeCodes).
    template <typename T> CudaStatus classifyTyped(double iso);
    template <typename T> CudaStatus extractTyped(double iso);
    CudaStatus readBack(const std::uint32_t* device, std::uint32_t& host, const char* what) {
        LW_CUDA_TRY(cudaMemcpyAsync(&host, device, sizeof host, cudaMemcpyDeviceToHost,
                                    stream.get()),
                    what);
        LW_CUDA_TRY(cudaStreamSynchronize(stream.get()), what);
        return CudaStatus::success();
    }
};


} // namespace lw::kernels::cuda
