#pragma once

// Method 1's OpenGL pipeline (Morar et al. 2013). Three passes into its own framebuffer objects:
//   pass 1  the iso-surface: shaded into the colour texture for the iso panel, depth only for
//           the silhouette panel, into the surface depth texture
//   pass 2  the same triangles through a geometry shader that emits each triangle's silhouette
//           segment (Burns et al. 2005) as a one-pixel GL line into the line depth texture, the
//           nearest line kept per pixel (GL_LESS)
//   pass 3  (resolve) a full-screen pass colours the line pixels, widened by a square dilation
//           of radius round((lineWidth - 1) / 2), as the panels widen the other methods' masks;
//           one-pixel lines of a frame drawn in one call need no pass 3: pass 2 colours them
// A line pixel is visible when its depth is not behind the farthest surface depth of its 3x3
// neighbourhood by more than `depthTolerance` -- method 3's rule (lw/kernels/zbuffer_rules.h
// resolvePixel, lw/render/visibility_tolerance.h; in GLSL silhouette_visibility.glsl). A frame
// drawn in one call tests it in pass 2, per line fragment, so that only line fragments pay for
// it (a full-screen test costs a software rasterizer tens of ms); a frame drawn in pieces tests
// the nearest line of each pixel in pass 3, once the whole surface is there. For one pixel the
// two agree: some fragment passes iff the nearest does.
// The paper tests the lines with the GL depth test against a polygon-offset surface. That rule
// breaks the one-pixel lines wherever the contour grazes the surface (the offset surface wins
// there), and stroke pruning then drops the pieces: on real CT it lost 3-7 % of the outline and
// left method 1 agreeing with method 3 on 0.97 of the line pixels. The neighbourhood rule keeps
// what the depth test kept and gives methods 1 and 3 one definition of "visible".
// Both depth buffers keep per-pixel minima, so drawing a mesh in pieces (L) and resolving once
// gives exactly the image of the whole mesh, in any order.
// It needs only a current OpenGL 4.1+ core context (GlContext, or the GUI's QOpenGLWidget).
//
// Mode a (mesh uploaded once, only the view changes) and mode b (re-upload every frame) are the
// caller's choice: uploadMesh() and render() are separate, and buffers are reused when they fit.
//
// Every GL call needs the context that was current at initialize() to be current again. Each GL
// object is owned by a GlObject (lw/render/gl_object.h), so destroying the renderer frees them
// all: its owner destroys it while that context is still current.

#include "lw/core/image.h"
#include "lw/render/camera.h"
#include "lw/render/gl_object.h"
#include "lw/render/iso_surface.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace lw::render {

namespace gl {
class GlLineCompute;
}

enum class GlPanel {
    Iso,        // shaded iso-surface (silhouette lines optionally on top)
    Silhouette, // silhouette lines on the background; the surface only fills the depth buffer
};

struct SilhouetteGlOptions {
    GlPanel panel = GlPanel::Silhouette;
    // Test the lines' visibility against pass 1 (hidden contours disappear); off draws every
    // segment and skips pass 1 on the silhouette panel (the paper's "visibility off" rows).
    bool visibility = true;
    bool linesOnIso = false; // also draw the silhouette on the iso panel
    // Pixels; the visible one-pixel lines are drawn as antialiased strokes of this width through
    // their pixels, as the panels draw methods 2 and 3 (PixelMask::strokeCoverage).
    float lineWidth = 1.0f;
    glm::vec4 lineColour{0.0f, 0.0f, 0.0f, 1.0f};
    glm::vec4 background{1.0f, 1.0f, 1.0f, 1.0f};
    glm::vec3 frontColour{0.93f, 0.89f, 0.80f};     // bone
    glm::vec3 backColour{0.55f, 0.35f, 0.35f};      // inside of a surface cut by the volume border
    glm::vec4 material{0.15f, 0.80f, 0.25f, 32.0f}; // ambient, diffuse, specular, shininess
    // The resolve pass's tolerance in window depth ([0, 1]): windowDepthTolerance() of the
    // camera and the volume's box (lw/render/visibility_tolerance.h); 0 = exact comparison.
    float depthTolerance = 0.0f;
    // The surface is closed and the camera outside it: on the silhouette panel pass 1 draws only
    // front faces (counter-clockwise, as marching cubes winds them seen from outside), which
    // always hold the nearest depth there; back faces would only cost fixed-function time.
    bool cullBackFacesInDepthPass = false;
    // Count the segments pass 2 draws (a primitive query); the GPU's own segments
    // (cullLineCandidatesOnGpu) are always counted, by the stage that finds them.
    bool countSegments = false;
    bool timePasses = false; // GPU time of pass 1 and of passes 2 + 3 (GL_TIMESTAMP queries)
    // Pass 2 over a subset of the triangles: the candidate buffer (reserveLineCandidates) holding
    // `lineCandidateIndices` indices, three a triangle, filled by whoever knows which triangles
    // can hold a silhouette (method 1's host test on a software rasterizer). Off: pass 2 sends
    // every triangle.
    bool useLineCandidates = false;
    std::size_t lineCandidateIndices = 0;
    // Pass 2 over the segments a compute shader finds this frame after pass 1, with the geometry
    // shader's rule and arithmetic, drawn as plain lines (SilhouetteGlRenderer::cullsOnGpu());
    // ignored where the context cannot. Overrides useLineCandidates.
    bool cullLineCandidatesOnGpu = false;
    // The frame is read only as a line mask (readRedMask), never as an image: with the GPU's
    // segments (above) and one-pixel lines drawn in one call, pass 2 writes only the frame's
    // stamp where a visible line falls (no colour, no line depth, neither cleared), and
    // readRedMask reads the stamps. Ignored otherwise.
    bool maskOnly = false;
    // Drawing a mesh in pieces (method 1's L variant: one brick uploaded at a time): the caller
    // starts the frame with clear(), draws each piece with clear = false and resolve = false
    // (passes 1 and 2 only), and ends it with resolve() (pass 3). The size must stay the same.
    // With resolve = true the frame is complete after this call: pass 2 tests visibility against
    // the surface depth drawn so far.
    bool clear = true;
    bool resolve = true;
};

struct SilhouetteGlStats {
    std::size_t triangles = 0;
    std::size_t segments = 0;   // with countSegments, or the GPU's own segments
    double surfacePassMs = 0.0; // only with timePasses: pass 1 (surface), GPU time
    double linePassMs = 0.0;    // the segment stage, passes 2 and 3
    // The GPU found more segments than its buffer held, and the frame lacks those beyond: draw it
    // again (render() does; the buffer has grown).
    bool incomplete = false;
};

class SilhouetteGlRenderer {
public:
    SilhouetteGlRenderer();
    // Deletes the GL objects: the context they were made in must be current.
    ~SilhouetteGlRenderer();
    SilhouetteGlRenderer(const SilhouetteGlRenderer&) = delete;
    SilhouetteGlRenderer& operator=(const SilhouetteGlRenderer&) = delete;

    // Compiles the shaders and creates the vertex arrays. Needs a current context; throws
    // core::Error with the compile/link log or the GL error, having made nothing. Called by the
    // first upload/render.
    void initialize();
    bool isInitialized() const { return bool(m_surfaceProgram); }

    // Uploads an indexed mesh (positions and normals per vertex, three indices per triangle).
    // Buffers are reused when the new data fits; throws core::Error for inconsistent sizes or
    // indices out of range.
    void uploadMesh(const Mesh& mesh);
    void uploadMesh(std::span<const glm::vec3> positions, std::span<const glm::vec3> normals,
                    std::span<const std::uint32_t> indices);
    std::size_t triangleCount() const { return m_indexCount / 3; }
    // Sizes the mesh buffers for `vertexCount` vertices and `triangleCount` triangles without
    // filling them (another API writes them: the CUDA back-end through CUDA-GL interop); their
    // contents are undefined until written. Returns true when the buffers' storage was
    // reallocated (a registration with CUDA must then be renewed).
    bool reserveMesh(std::size_t vertexCount, std::size_t triangleCount);
    // Writes `piece` into the reserved mesh buffers from vertex `firstVertex` and triangle
    // `firstTriangle` on, its indices shifted by firstVertex (the border cap after the part
    // another API wrote). Throws core::Error when it does not fit the reserved sizes.
    void writeMeshTail(std::size_t firstVertex, std::size_t firstTriangle, const Mesh& piece);
    // Writes `indices` into the line-candidate buffer from index `firstIndex` on.
    void writeLineCandidatesTail(std::size_t firstIndex, std::span<const std::uint32_t> indices);
    // The buffer names (GL_ARRAY_BUFFER positions and normals as 3 floats a vertex,
    // GL_ELEMENT_ARRAY_BUFFER indices as uint32), for interop.
    unsigned positionBuffer() const { return m_positionBuffer.get(); }
    unsigned normalBuffer() const { return m_normalBuffer.get(); }
    unsigned indexBuffer() const { return m_indexBuffer.get(); }
    // A GL_ELEMENT_ARRAY_BUFFER for up to `triangleCount` triangles of pass-2 candidates (see
    // SilhouetteGlOptions::useLineCandidates); its name, and true when its storage was
    // reallocated (a CUDA registration must be renewed).
    unsigned lineCandidateBuffer() const { return m_candidateBuffer.get(); }
    bool reserveLineCandidates(std::size_t triangleCount);
    // The last frame's red channel as a mask, top row first: 1 where it differs from
    // `backgroundRed` (lines drawn in another red than the background). A quarter of readImage's
    // bytes, and no image in between; with compute shaders the threshold and the flip run on
    // the GPU and only the mask's bytes come back.
    void readRedMask(std::uint8_t backgroundRed, std::vector<std::uint8_t>& mask);
    // Whether the context runs method 1's compute stages (gl/gl_line_compute.h):
    // cullLineCandidatesOnGpu works, and readRedMask thresholds on the GPU. Known after
    // initialize().
    bool cullsOnGpu() const { return m_compute != nullptr; }
    // Changes whenever the mesh buffers' storage is reallocated (by any upload, reserve or clear):
    // a CUDA registration made at another generation is stale.
    std::size_t storageGeneration() const { return m_storageGeneration; }
    // Frees the mesh buffers' storage (the buffers stay; the next upload allocates what it needs),
    // e.g. before drawing piece by piece after a whole mesh was uploaded.
    void clearMesh();
    // Starts a frame of `width` x `height` (the framebuffer objects recreated only when the size
    // changes): colour = background, both depths = 1. For render() with options.clear = false.
    void clear(int width, int height, glm::vec4 background);
    // Pass 3 alone, over what the passes 1 and 2 of the frame so far left (see
    // SilhouetteGlOptions::resolve). Uses visibility, lineWidth, lineColour and depthTolerance.
    void resolve(const SilhouetteGlOptions& options);

    // Renders the uploaded mesh with the camera's matrices into the framebuffer object, sized to
    // the camera's viewport (recreated only when the size changes).
    SilhouetteGlStats render(const Camera& camera, const SilhouetteGlOptions& options = {});
    // Same with explicit matrices: `viewer` is the eye (w = 1) or, for an orthographic camera, the
    // unit direction toward the viewer (w = 0); `lightDirection` points toward the light.
    SilhouetteGlStats render(const glm::mat4& viewProjection, glm::vec4 viewer,
                             glm::vec3 lightDirection, int width, int height,
                             const SilhouetteGlOptions& options = {});
    // render() in two halves, for a caller that queues more GPU work on the frame before it
    // waits (method 1's mask read-back): queueRender sends the passes and returns at once;
    // queuedStats waits for their queries. Where it says `incomplete`, queue the frame again.
    void queueRender(const Camera& camera, const SilhouetteGlOptions& options = {});
    void queueRender(const glm::mat4& viewProjection, glm::vec4 viewer, glm::vec3 lightDirection,
                     int width, int height, const SilhouetteGlOptions& options = {});
    SilhouetteGlStats queuedStats();

    // The last frame as RGBA8, top row first.
    core::ImageRgba8 readImage() const;
    // The last frame's surface depth buffer in [0, 1] (1 = nothing drawn), top row first: picking a
    // pixel's surface point with Camera::unproject (depth * 2 - 1 is its NDC depth).
    std::vector<float> readDepth() const;
    // One pixel of it (x right, y down from the top row); 1 outside the frame. Picking under the
    // mouse reads this rather than the whole buffer.
    float readDepthAt(int x, int y) const;
    // render() + readImage().
    core::ImageRgba8 renderImage(const Camera& camera, const SilhouetteGlOptions& options = {});

    // The framebuffer object and its colour texture (GL_RGBA8), for a GUI that blits or samples
    // them into its own framebuffer.
    unsigned framebuffer() const { return m_framebuffer.get(); }
    unsigned colourTexture() const { return m_colourTexture.get(); }
    int width() const { return m_width; }
    int height() const { return m_height; }

private:
    void ensureFramebuffer(int width, int height);
    void ensureFramebufferObjects();
    void clearBuffers(glm::vec4 background, bool colour = true, bool lineDepth = true);
    void nextStamp(int width, int height);
    void drawSurfacePass(const glm::mat4& viewProjection, glm::vec4 viewer,
                         glm::vec3 lightDirection, const SilhouetteGlOptions& options);
    void drawLinePass(const glm::mat4& viewProjection, glm::vec4 viewer,
                      const SilhouetteGlOptions& options, bool writeColour, bool stamp = false);
    void computeSegments(const glm::mat4& viewProjection, glm::vec4 viewer, int width, int height,
                         const SilhouetteGlOptions& options, bool surfaceDrawn);
    void drawResolvePass(const SilhouetteGlOptions& options, bool testVisibility);
    // The resolve program for a stroke radius and visibility on or off, compiled on first use
    // (constant loop bounds: see silhouette_resolve.frag.glsl).
    unsigned resolveProgram(int radius, bool visibility);

    GlProgram m_surfaceProgram;
    GlProgram m_linePrograms[2]; // geometry shader emitting GL lines; [test visibility]
    // What queuedStats needs of the frame queueRender sent.
    struct QueuedFrame {
        std::size_t triangles = 0;
        bool drawSurface = false, drawLines = false, segmentsOnGpu = false;
        bool segmentsComputed = false; // the compute pass ran (not where there are no triangles)
        bool countSegments = false, timePasses = false;
    };
    std::optional<QueuedFrame> m_queued;
    // The same over the GPU's segments, on first use: [test visibility + 2 * stamp].
    GlProgram m_segmentLinePrograms[4];
    GlVertexArray m_vertexArray;
    std::vector<std::pair<int, GlProgram>> m_resolvePrograms; // (radius * 2 + visibility, program)
    GlVertexArray m_emptyVertexArray; // the resolve's full-screen triangle has no attributes
    GlBuffer m_positionBuffer;
    GlBuffer m_normalBuffer;
    GlBuffer m_indexBuffer;
    GlQuery m_segmentQuery;
    GlQuery m_timerQueries[3];        // GL_TIMESTAMP: before pass 1, between the passes, after them
    std::size_t m_vertexCapacity = 0; // vertices the position/normal buffers can hold
    std::size_t m_indexCapacity = 0;
    std::size_t m_indexCount = 0;
    std::size_t m_storageGeneration = 0;
    GlBuffer m_candidateBuffer;
    std::size_t m_candidateCapacity = 0;          // indices
    std::unique_ptr<gl::GlLineCompute> m_compute; // null: the context has no compute shaders

    GlFramebuffer m_framebuffer;        // colour + surface depth (passes 1 and the read-backs)
    GlFramebuffer m_lineFramebuffer;    // line depth (pass 2)
    GlFramebuffer m_resolveFramebuffer; // colour only (pass 3 samples both depth textures)
    GlTexture m_colourTexture;
    GlTexture m_surfaceDepthTexture;
    GlTexture m_lineDepthTexture;
    // Mask-only frames (SilhouetteGlOptions::maskOnly): pass 2 writes the frame's stamp into an
    // R32UI texture that is never cleared between frames (nextStamp).
    GlFramebuffer m_stampFramebuffer;
    GlTexture m_stampTexture;
    glm::ivec2 m_stampSize{0, 0};
    std::uint32_t m_stamp = 0;
    bool m_lastFrameMaskOnly = false; // readImage has nothing to read
    int m_width = 0;
    int m_height = 0;
};

} // namespace lw::render
