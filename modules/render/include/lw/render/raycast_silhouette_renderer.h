#pragma once

#include "lw/render/renderer_factory.h"
#include "lw/render/silhouette_renderer.h"

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace lw::render {

// Method 2: silhouette segments from the active cells (no mesh kept) and the paper's ray-cast
// visibility test, on the CPU (kernels/cpu/raycast_silhouette_cpu.h) or the CUDA back-end
// (kernels/cuda/raycast_silhouette_cuda.h) behind one frame logic (this class; per back-end
// src/raycast_kernel_set.h). The CUDA back-end has no streamed variant, so its L frames, and every
// frame of a volume for which the device ran out of memory, run on the CPU (backendName() says
// which ran the last frame).
//
// Visibility rules:
//   endpoint-only (the default): a segment is drawn whole when both of its endpoints are
//     visible (the paper's rule), not at all when neither is, and in the half next to the
//     visible endpoint when one is (kernels::drawnSpanOfSegment): the paper's rule broke a
//     contour at every endpoint whose ray grazes noise or a sheet's face;
//   settings.testAlongSegment: the point under every step of the line rasterizer (at most one
//     pixel apart, endpoints included) is tested and only the pixels of visible steps are drawn,
//     so the visible pieces are exactly part of the line drawn with visibility off.
// Mode a caches the active cell list (view independent) with a cone around each cell's vertex
// normals while the volume, iso-value and brick size stay the same; segments depend on the eye
// and are found anew for every view, skipping the cells whose cone rules a silhouette out.
// The L variant (brickCells > 0) finds the cells and segments brick by brick and tests them
// against the whole volume, so its image equals the S variant's.
class RayCastSilhouetteRenderer final : public SilhouetteRenderer {
public:
    // Backend::Cuda throws core::Error where this build has no CUDA back-end.
    explicit RayCastSilhouetteRenderer(Backend backend = Backend::Cpu);
    ~RayCastSilhouetteRenderer() override;
    RayCastSilhouetteRenderer(const RayCastSilhouetteRenderer&) = delete;
    RayCastSilhouetteRenderer& operator=(const RayCastSilhouetteRenderer&) = delete;

    SilhouetteMethod method() const override { return SilhouetteMethod::RayCastVisibility; }
    std::string_view backendName() const override;
    void setVolume(const volume::Volume& volume) override;
    void setVolumeWithDeviceCopy(const volume::Volume& volume, DeviceVoxelCopy copy) override;
    void releaseVolume() override;
    SilhouetteFrame renderFrame(const Camera& camera, const SilhouetteSettings& settings) override;

    // Of the last frame drawn on the CPU (core::Error after a CUDA frame):
    // segments (patient mm), before the visibility test.
    struct Segment {
        glm::vec3 a;
        glm::vec3 b;
    };
    std::vector<Segment> lastSegments() const;
    // Active cells in the current cache (0 before the first render).
    std::size_t activeCellCount() const;
    // The visibility test for one patient-space point, as render() applies it.
    bool isPointVisible(const Camera& camera, glm::dvec3 point) const;

private:
    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
