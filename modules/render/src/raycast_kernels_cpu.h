#pragma once

// Method 2's CPU kernel set (raycast_kernel_set.h): the active cells and segments of
// kernels/cpu/raycast_silhouette_cpu.h on all cores, with the ray visibility test per endpoint or
// per line step, and the lines drawn serially.

#include "lw/kernels/cpu/raycast_silhouette_cpu.h"
#include "lw/render/iso_surface.h"
#include "point_visibility_memo.h"
#include "raycast_kernel_set.h"

#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace lw::render {

class CpuRayCastKernels final : public RayCastKernelSet {
public:
    std::string_view backendName() const override { return "cpu"; }
    void bind(const volume::Volume* volume) override;
    bool drawsPieces() const override { return true; }
    void prepare(double storedIso, const SilhouetteSettings& settings,
                 SilhouetteFrame& frame) override;
    void drawView(const Camera& camera, const SilhouetteSettings& settings,
                  SilhouetteFrame& frame) override;

    // Of the last frame (see RayCastSilhouetteRenderer).
    const kernels::cpu::RayCastSilhouetteCpu& kernel() const { return *m_kernel; }
    bool isPointVisible(const Camera& camera, glm::dvec3 point) const;
    // The border cap's segments of the last frame (empty when it was not closed at the border).
    const std::vector<kernels::SegmentEndpoints>& capSegments() const { return m_capSegments; }

private:
    void testVisibility(const Camera& camera, const SilhouetteSettings& settings);
    // The segments to test: the kernel's chunks, then the border cap's as one more chunk.
    std::size_t chunkCount() const { return m_kernel->segmentChunkCount() + 1; }
    const std::vector<kernels::SegmentEndpoints>& chunk(std::size_t c) const {
        return c < m_kernel->segmentChunkCount() ? m_kernel->segmentChunk(c) : m_capSegments;
    }

    const volume::Volume* m_volume = nullptr;
    std::unique_ptr<kernels::cpu::RayCastSilhouetteCpu> m_kernel =
        std::make_unique<kernels::cpu::RayCastSilhouetteCpu>();
    // Per segment chunk of the kernel, reused between frames: the projected lines to draw
    // (pairs of float pixel points) and, along segments, the single pixels of visible steps.
    // Projected points are rounded to float once, and every mode draws from the rounded
    // values, so a visible piece is pixel for pixel part of the line drawn with visibility off.
    std::vector<std::vector<glm::vec2>> m_chunkLines;
    std::vector<std::vector<glm::ivec2>> m_chunkDots;
    // Per chunk: each endpoint's visibility, one ray per point (endpoint tests only).
    std::vector<PointVisibilityMemo> m_chunkMemos;
    // The border cap at the prepared iso-value (settings.closeAtBorder) and its segments for the
    // frame's view: the kernel finds the segments of marching cubes' cells, the cap adds its own.
    double m_storedIso = 0.0;
    BorderCapCache m_cap;
    std::vector<kernels::SegmentEndpoints> m_capSegments;
};

} // namespace lw::render
