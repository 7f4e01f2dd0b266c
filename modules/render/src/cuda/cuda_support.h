#pragma once

// What the CUDA renderers share: failed statuses as errors, the host volume as the kernels see it,
// and the CPU fallback for
// the chunked (L) variant, which runs on the CPU renderer of the same method until bricks stream
// through a device memory budget (issue 8, item 7).

#include "lw/core/error.h"
#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/volume_view.h"
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

template <typename CpuRenderer> class ChunkedOnCpu {
public:
    void setVolume(const volume::Volume& volume) {
        m_volume = &volume;
        if (m_renderer)
            m_renderer->setVolume(volume);
    }
    // An L frame (settings.brickCells > 0) on the CPU renderer: true and `frame` set. Otherwise
    // false, and the caller renders on the GPU.
    bool render(const Camera& camera, const SilhouetteSettings& settings, SilhouetteFrame& frame) {
        m_lastFrame = settings.brickCells > 0;
        if (m_lastFrame)
            renderAlways(camera, settings, frame);
        return m_lastFrame;
    }
    // Every frame on the CPU (after the device ran out of memory).
    void renderAlways(const Camera& camera, const SilhouetteSettings& settings,
                      SilhouetteFrame& frame) {
        if (!m_renderer) {
            m_renderer = std::make_unique<CpuRenderer>();
            m_renderer->setVolume(*m_volume);
        }
        frame = m_renderer->render(camera, settings);
    }
    bool lastFrameWasChunked() const { return m_lastFrame; }
    const CpuRenderer* renderer() const { return m_renderer.get(); }

private:
    const volume::Volume* m_volume = nullptr;
    std::unique_ptr<CpuRenderer> m_renderer;
    bool m_lastFrame = false;
};

} // namespace lw::render
