#pragma once

// Method 1's per-frame GPU stages besides the two draws, in the GL context that draws the frame
// (compute shaders: OpenGL 4.3, and a storage buffer in the vertex shader):
//  - pass 2's segments (line_segments.comp.glsl): each triangle's silhouette segment, computed
//    by the geometry shader's rule and arithmetic, as two clip-space line ends, their count
//    written into an indirect draw command on the GPU; pass 2 then draws them as plain lines
//    (silhouette_segments.vert.glsl), and the host never waits for the count;
//  - the frame's line mask for the host (line_mask.comp.glsl), thresholded and flipped where
//    the frame is: only a byte a pixel comes back.
// Why not CUDA, which extracts the mesh: on the H200 machine each switch between the CUDA and
// the GL context left the GPU idle for 0.2-0.3 ms, more than the work on either side (the
// contour's candidates took 0.08 ms in CUDA, the mask 0.005 ms), and a frame that culled and
// read back through CUDA switched three times.

#include "lw/render/gl_object.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace lw::render::gl {

class GlLineCompute {
public:
    // Whether the current context runs these stages: OpenGL 4.3 or later, with a storage buffer
    // in the vertex shader (the minimum GL requires there is none).
    static bool available();

    // Pass 1's depth, where pass 2 will discard hidden fragments: segments hidden wherever they
    // could draw are then dropped before they are drawn (silhouette_visibility.glsl's rule).
    struct HiddenLineTest {
        unsigned surfaceDepthTexture = 0; // 0: keep every segment
        float tolerance = 0.0f;           // window depth
    };
    // The silhouette segments of the triangles (triangleCount of them: three uint32 indices each
    // into the position and normal buffers, three floats a vertex) for the camera, into the
    // segment buffer, their vertex count into the draw command. Segments past the buffer's
    // capacity are counted but not kept (see segmentCounts). The programs are built on first
    // use (throws core::Error with the compiler's log).
    void computeSegments(unsigned positions, unsigned normals, unsigned indices,
                         std::size_t triangleCount, const glm::mat4& viewProjection,
                         glm::vec4 viewer, glm::vec2 viewportSize, HiddenLineTest hidden);
    // Draws the last computeSegments' segments as lines with the bound program (a vertex array
    // without attributes; silhouette_segments.vert.glsl, whose uVertexCapacity it sets).
    void drawSegments(unsigned program) const;
    // The last computeSegments' counts, once the GPU has run it (reading them earlier waits):
    // segments found, and segments to draw (hidden ones dropped). More to draw than
    // segmentCapacity() means the caller should reserveSegments and draw again.
    struct SegmentCounts {
        std::size_t found = 0;
        std::size_t toDraw = 0;
    };
    SegmentCounts segmentCounts() const;
    std::size_t segmentCapacity() const { return m_segmentCapacity; }
    // Room for at least `segments` segments (32 bytes each). The first computeSegments reserves
    // a quarter of its triangles' count, far more than a contour holds.
    void reserveSegments(std::size_t segments);
    // A frame's lines as a mask, top row first: 1 where the red channel of `texture` (RGBA8,
    // width x height, GL's rows bottom-up) differs from `backgroundRed`, or, with a nonzero
    // `stamp`, where `texture` (R32UI) holds that stamp (silhouette.frag.glsl, LW_STAMP).
    void readMask(unsigned texture, std::uint32_t stamp, int width, int height,
                  std::uint8_t backgroundRed, std::vector<std::uint8_t>& mask);

private:
    void initialize();
    void reserveMask(std::size_t bytes);

    GlProgram m_segmentProgram;
    GlProgram m_maskProgram;
    GlBuffer m_command;  // DrawArraysIndirectCommand, then the count of segments found
    GlBuffer m_segments; // two clip-space vec4 a segment
    std::size_t m_segmentCapacity = 0;
    GlBuffer m_mask;
    std::size_t m_maskBytes = 0;
    bool m_persistentMapping = false; // GL 4.4: m_mask lives in client memory, mapped for good
    void* m_maskMapped = nullptr;
};

} // namespace lw::render::gl
