#pragma once

// Method 1's OpenGL pipeline (Morar et al. 2013): pass 1 draws the iso-surface (shaded for the
// iso panel, depth only for the silhouette panel), pass 2 sends the same triangles through a
// geometry shader that emits each triangle's silhouette segment (Burns et al. 2005), depth-tested
// against pass 1. It needs only a current OpenGL 4.1+ core context (GlContext, or the GUI's
// QOpenGLWidget) and draws into its own framebuffer object.
//
// Mode a (mesh uploaded once, only the view changes) and mode b (re-upload every frame) are the
// caller's choice: uploadMesh() and render() are separate, and buffers are reused when they fit.
//
// Every GL call needs the context that was current at initialize() to be current again. GL
// objects are freed by release() (call it while the context is still current); the destructor
// makes no GL calls because the context may already be gone.

#include "lw/core/image.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

namespace lw::render {

enum class GlPanel {
    Iso,        // shaded iso-surface (silhouette lines optionally on top)
    Silhouette, // silhouette lines on the background; the surface only fills the depth buffer
};

struct SilhouetteGlOptions {
    GlPanel panel = GlPanel::Silhouette;
    // Depth-test the lines against pass 1 (hidden contours disappear); off draws every segment
    // and skips pass 1 on the silhouette panel (the paper's "visibility off" rows).
    bool visibility = true;
    bool linesOnIso = false; // also draw the silhouette on the iso panel
    float lineWidth = 1.0f;  // pixels; above 1 the segments are drawn as screen-space quads
    glm::vec4 lineColour{0.0f, 0.0f, 0.0f, 1.0f};
    glm::vec4 background{1.0f, 1.0f, 1.0f, 1.0f};
    glm::vec3 frontColour{0.93f, 0.89f, 0.80f};     // bone
    glm::vec3 backColour{0.55f, 0.35f, 0.35f};      // inside of a surface cut by the volume border
    glm::vec4 material{0.15f, 0.80f, 0.25f, 32.0f}; // ambient, diffuse, specular, shininess
    // Pass 1 is pushed back by glPolygonOffset(factor, units) so the lines, which lie exactly on
    // the surface, win the depth test where they are visible; depthBias (NDC) pulls the lines
    // forward as well (glPolygonOffset does not apply to lines).
    float polygonOffsetFactor = 2.0f;
    float polygonOffsetUnits = 4.0f;
    float depthBias = 0.0f;
    // The surface is closed and the camera outside it: on the silhouette panel pass 1 draws only
    // front faces (counter-clockwise, as marching cubes winds them seen from outside), which
    // always hold the nearest depth there; back faces would only cost fixed-function time.
    bool cullBackFacesInDepthPass = false;
    bool countSegments = false; // query how many segments the geometry shader emitted
    bool timePasses = false;    // GPU time of pass 1 and pass 2 (GL_TIME_ELAPSED queries)
    // Pass 2 over a subset of the triangles: the candidate buffer (reserveLineCandidates) holding
    // `lineCandidateIndices` indices, three a triangle, filled by whoever knows which triangles
    // can hold a silhouette (the CUDA back-end's facing test). Off: pass 2 sends every triangle.
    bool useLineCandidates = false;
    std::size_t lineCandidateIndices = 0;
    // Drawing a mesh in pieces (method 1's L variant: one brick uploaded at a time). With
    // clear = false render() draws over the last frame instead of clearing it (the caller starts
    // the frame with clear(); the size must stay the same). On the silhouette panel,
    // surfaceInBackground makes pass 1 write the background colour as well as depth, and
    // linesWriteDepth makes pass 2 write its depth: a later piece's nearer surface then paints
    // over an earlier piece's hidden line, an earlier nearer surface or line rejects a later
    // piece's fragments, and the pieces give exactly the image of the whole mesh in one draw
    // (a pixel ends black iff its nearest line fragment is <= its nearest offset surface
    // fragment, whatever the order). Only for a uniform line colour (a nearer line hides a
    // farther one at the same pixel).
    bool clear = true;
    bool surfaceInBackground = false;
    bool linesWriteDepth = false;
};

struct SilhouetteGlStats {
    std::size_t triangles = 0;
    std::size_t segments = 0;   // only with countSegments (GL_PRIMITIVES_GENERATED)
    double surfacePassMs = 0.0; // only with timePasses: pass 1 (surface), GPU time
    double linePassMs = 0.0;    // pass 2 (geometry-shader silhouette)
};

class SilhouetteGlRenderer {
public:
    SilhouetteGlRenderer() = default;
    ~SilhouetteGlRenderer();
    SilhouetteGlRenderer(const SilhouetteGlRenderer&) = delete;
    SilhouetteGlRenderer& operator=(const SilhouetteGlRenderer&) = delete;

    // Compiles the shaders and creates the vertex arrays. Needs a current context; throws
    // core::Error with the compile/link log or the GL error. Called by the first upload/render.
    void initialize();
    bool isInitialized() const { return m_surfaceProgram != 0; }
    // Frees every GL object; the context they were created in must be current. Safe to call twice.
    void release();

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
    unsigned positionBuffer() const { return m_positionBuffer; }
    unsigned normalBuffer() const { return m_normalBuffer; }
    unsigned indexBuffer() const { return m_indexBuffer; }
    // A GL_ELEMENT_ARRAY_BUFFER for up to `triangleCount` triangles of pass-2 candidates (see
    // SilhouetteGlOptions::useLineCandidates); its name, and true when its storage was
    // reallocated (a CUDA registration must be renewed).
    unsigned lineCandidateBuffer() const { return m_candidateBuffer; }
    bool reserveLineCandidates(std::size_t triangleCount);
    // The last frame's red channel as a mask, top row first: 1 where it differs from
    // `backgroundRed` (lines drawn in another red than the background). A quarter of readImage's
    // bytes, and no image in between.
    void readRedMask(std::uint8_t backgroundRed, std::vector<std::uint8_t>& mask) const;
    // Changes whenever the mesh buffers' storage is reallocated (by any upload, reserve or clear):
    // a CUDA registration made at another generation is stale.
    std::size_t storageGeneration() const { return m_storageGeneration; }
    // Frees the mesh buffers' storage (the buffers stay; the next upload allocates what it needs),
    // e.g. before drawing piece by piece after a whole mesh was uploaded.
    void clearMesh();
    // Starts a frame of `width` x `height` (the framebuffer object recreated only when the size
    // changes): colour = background, depth = 1. For render() with options.clear = false.
    void clear(int width, int height, glm::vec4 background);

    // Renders the uploaded mesh with the camera's matrices into the framebuffer object, sized to
    // the camera's viewport (recreated only when the size changes).
    SilhouetteGlStats render(const Camera& camera, const SilhouetteGlOptions& options = {});
    // Same with explicit matrices: `viewer` is the eye (w = 1) or, for an orthographic camera, the
    // unit direction toward the viewer (w = 0); `lightDirection` points toward the light.
    SilhouetteGlStats render(const glm::mat4& viewProjection, glm::vec4 viewer,
                             glm::vec3 lightDirection, int width, int height,
                             const SilhouetteGlOptions& options = {});

    // The last frame as RGBA8, top row first.
    core::ImageRgba8 readImage() const;
    // The last frame's depth buffer in [0, 1] (1 = nothing drawn), top row first: picking a
    // pixel's surface point with Camera::unproject (depth * 2 - 1 is its NDC depth).
    std::vector<float> readDepth() const;
    // One pixel of it (x right, y down from the top row); 1 outside the frame. Picking under the
    // mouse reads this rather than the whole buffer.
    float readDepthAt(int x, int y) const;
    // render() + readImage().
    core::ImageRgba8 renderImage(const Camera& camera, const SilhouetteGlOptions& options = {});

    // The framebuffer object and its colour texture (GL_RGBA8), for a GUI that blits or samples
    // them into its own framebuffer.
    unsigned framebuffer() const { return m_framebuffer; }
    unsigned colourTexture() const { return m_colourTexture; }
    int width() const { return m_width; }
    int height() const { return m_height; }

private:
    void ensureFramebuffer(int width, int height);

    unsigned m_surfaceProgram = 0;
    unsigned m_lineProgram = 0;     // geometry shader emitting GL lines
    unsigned m_wideLineProgram = 0; // geometry shader emitting quads
    unsigned m_vertexArray = 0;
    unsigned m_positionBuffer = 0;
    unsigned m_normalBuffer = 0;
    unsigned m_indexBuffer = 0;
    unsigned m_segmentQuery = 0;
    unsigned m_timerQueries[2] = {0, 0};
    std::size_t m_vertexCapacity = 0; // vertices the position/normal buffers can hold
    std::size_t m_indexCapacity = 0;
    std::size_t m_indexCount = 0;
    std::size_t m_storageGeneration = 0;
    unsigned m_candidateBuffer = 0;
    std::size_t m_candidateCapacity = 0; // indices

    unsigned m_framebuffer = 0;
    unsigned m_colourTexture = 0;
    unsigned m_depthBuffer = 0;
    int m_width = 0;
    int m_height = 0;
};

} // namespace lw::render
