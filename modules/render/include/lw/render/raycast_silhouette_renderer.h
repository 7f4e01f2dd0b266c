#pragma once

#include "lw/render/silhouette_renderer.h"

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace lw::render {

// Method 2 on the CPU: silhouette segments from the active cells (no mesh kept) and the paper's
// ray-cast visibility test (kernels/cpu/raycast_silhouette_cpu.h).
//
// Visibility rules:
//   endpoint-only (the paper): a segment is drawn when both of its endpoints are visible, so
//     segments that run behind an occluder drop out whole (the paper's broken lines);
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
    RayCastSilhouetteRenderer();
    ~RayCastSilhouetteRenderer() override;

    SilhouetteMethod method() const override { return SilhouetteMethod::RayCastVisibility; }
    std::string_view backendName() const override { return "cpu"; }
    void setVolume(const volume::Volume& volume) override;
    SilhouetteFrame renderFrame(const Camera& camera, const SilhouetteSettings& settings) override;

    // Segments (patient mm) of the last render, before the visibility test.
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
    struct Cache;
    const volume::Volume* m_volume = nullptr;
    std::unique_ptr<Cache> m_cache;
};

} // namespace lw::render
