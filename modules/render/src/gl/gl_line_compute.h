#pragma once

// Method 1's per-frame GPU stages besides the two draws, in the GL context that draws the frame
// (compute shaders: OpenGL 4.3, and storage buffers in the geometry shader):
//  - pass 2's candidates (line_candidates.comp.glsl): the triangles whose facing can change for
//    the viewer, as triangle numbers, their count written into an indirect draw command on the
//    GPU; pass 2 then draws a point per candidate (silhouette_points.geom.glsl), and the host
//    never waits for the count;
//  - the frame's line mask for the host (line_mask.comp.glsl), thresholded and flipped where
//    the frame is: only a byte a pixel comes back.
// Why not CUDA, which extracts the mesh: on the H200 machine each switch between the CUDA and
// the GL context left the GPU idle for 0.2-0.3 ms, more than the work on either side (the
// candidates take 0.08 ms in CUDA, the mask 0.005 ms), and a frame that culled and read back
// through CUDA switched three times.

#include "lw/render/gl_object.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <vector>

namespace lw::render::gl {

class GlLineCompute {
public:
    // Whether the current context runs these stages: OpenGL 4.3 or later, with the four storage
    // buffers the points' geometry shader reads (the minimum GL requires there is none).
    static bool available();

    // The triangles (triangleCount of them: three uint32 indices each into the position and
    // normal buffers, three floats a vertex) that may hold a contour for `viewer`, as triangle
    // numbers into `candidates` (room for triangleCount), their count into the draw command.
    // The programs are built on first use (throws core::Error with the compiler's log).
    void cullCandidates(unsigned positions, unsigned normals, unsigned indices,
                        std::size_t triangleCount, glm::vec4 viewer, unsigned candidates);
    // Draws the last cull's candidates, a point each, with the bound program and a vertex array
    // without attributes; the points' geometry shader reads the same buffers the cull did.
    void drawCandidates(unsigned positions, unsigned normals, unsigned indices,
                        unsigned candidates) const;
    // `colourTexture` (width x height RGBA8, GL's rows bottom-up) as a mask, top row first: 1
    // where the red channel differs from `backgroundRed`.
    void readMask(unsigned colourTexture, int width, int height, std::uint8_t backgroundRed,
                  std::vector<std::uint8_t>& mask);

private:
    void initialize();
    void reserveMask(std::size_t bytes);

    GlProgram m_cullProgram;
    GlProgram m_maskProgram;
    GlBuffer m_command; // DrawArraysIndirectCommand
    GlBuffer m_mask;
    std::size_t m_maskBytes = 0;
    bool m_persistentMapping = false; // GL 4.4: m_mask lives in client memory, mapped for good
    void* m_maskMapped = nullptr;
};

} // namespace lw::render::gl
