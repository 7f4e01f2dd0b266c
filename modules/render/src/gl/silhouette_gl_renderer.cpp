#include "lw/render/silhouette_gl_renderer.h"

#include "gl_api.h"
#include "gl_line_compute.h"
#include "gl_program.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/pixel_mask.h"
#include "lw_render_shaders.h"

#include <algorithm>
#include <cstdio>
#include <glm/gtc/type_ptr.hpp>
#include <string>
#include <vector>

namespace lw::render {

namespace {

const core::LogCategory kLog("lw.render");

using gl::afterVersionLine;
using gl::linkProgram;

// A fragment shader of passes 2 and 3: `defines` and the shared visibility rule
// (silhouette_visibility.glsl).
std::string withVisibilityRule(const char* source, const std::string& defines) {
    return afterVersionLine(source, defines + gl::shaders::silhouette_visibility);
}

// Method 1's pass-2 program: the silhouette segments, their fragments tested for visibility or
// not. Over triangles (the geometry shader computes each one's segment), or over the segments
// the GPU computed this frame (GlLineCompute), drawn as plain lines.
enum class LineInput { Triangles, ComputedSegments };

GlProgram linkLineProgram(LineInput input, bool testVisibility, bool stamp = false) {
    const gl::ShaderSource fragment{GL_FRAGMENT_SHADER,
                                    withVisibilityRule(gl::shaders::silhouette_frag,
                                                       std::string("#define LW_TEST_VISIBILITY ") +
                                                           (testVisibility ? "1\n" : "0\n") +
                                                           "#define LW_STAMP " +
                                                           (stamp ? "1\n" : "0\n")),
                                    "silhouette.frag.glsl"};
    if (input == LineInput::ComputedSegments)
        return linkProgram({{GL_VERTEX_SHADER, gl::shaders::silhouette_segments_vert,
                             "silhouette_segments.vert.glsl"},
                            fragment},
                           "silhouette lines from computed segments");
    return linkProgram(
        {{GL_VERTEX_SHADER, gl::shaders::silhouette_vert, "silhouette.vert.glsl"},
         {GL_GEOMETRY_SHADER,
          afterVersionLine(gl::shaders::silhouette_geom, gl::shaders::silhouette_segment),
          "silhouette.geom.glsl"},
         fragment},
        "silhouette lines");
}

GLint uniform(GLuint program, const char* name) {
    // -1 (optimised away) is legal for glUniform*, so it is not an error here.
    return glGetUniformLocation(program, name);
}

// Grows a buffer only when the data does not fit (mode b re-uploads every frame: reallocating
// then would cost a driver allocation per frame); otherwise overwrites the front part in place.
void uploadBuffer(GLenum target, GLuint buffer, const void* data, std::size_t bytes,
                  std::size_t& capacityBytes) {
    glBindBuffer(target, buffer);
    if (bytes > capacityBytes) {
        glBufferData(target, GLsizeiptr(bytes), data, GL_DYNAMIC_DRAW);
        capacityBytes = bytes;
    } else if (bytes > 0) {
        glBufferSubData(target, 0, GLsizeiptr(bytes), data);
    }
}

// Restores the caller's framebuffer bindings and viewport: under QOpenGLWidget the widget's own
// framebuffer (not 0) is bound while painting, and the GUI must find it bound again afterwards.
class FramebufferBindingGuard {
public:
    FramebufferBindingGuard() {
        glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &m_draw);
        glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &m_read);
        glGetIntegerv(GL_VIEWPORT, m_viewport);
    }
    ~FramebufferBindingGuard() {
        glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(m_draw));
        glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(m_read));
        glViewport(m_viewport[0], m_viewport[1], m_viewport[2], m_viewport[3]);
    }
    FramebufferBindingGuard(const FramebufferBindingGuard&) = delete;
    FramebufferBindingGuard& operator=(const FramebufferBindingGuard&) = delete;

private:
    GLint m_draw = 0;
    GLint m_read = 0;
    GLint m_viewport[4] = {0, 0, 0, 0};
};

// The strokes' footprint (PixelMask::strokeReach / strokeRadius) for pass 3, its radius bounded:
// a 33-pixel line is far wider than any drawing needs.
int resolveRadius(float lineWidth) {
    return std::min(PixelMask::strokeRadius(lineWidth), 16);
}

// A query's result (waits for it); timestamps in nanoseconds.
GLuint64 queryResult(GLuint query) {
    GLuint64 value = 0;
    glGetQueryObjectui64v(query, GL_QUERY_RESULT, &value);
    return value;
}

double nanosecondsToMs(GLuint64 from, GLuint64 to) {
    return to > from ? double(to - from) * 1e-6 : 0.0;
}

} // namespace

// Out of line: GlLineCompute is complete only here. The GlObject members delete every GL object.
SilhouetteGlRenderer::SilhouetteGlRenderer() = default;

SilhouetteGlRenderer::~SilhouetteGlRenderer() = default;

void SilhouetteGlRenderer::initialize() {
    if (isInitialized())
        return;
    gl::checkGlError("before SilhouetteGlRenderer::initialize"); // someone else's error is not ours
    // Everything is made into locals first: when a step throws, what was made so far deletes
    // itself and the renderer stays uninitialised.
    GlProgram surfaceProgram =
        linkProgram({{GL_VERTEX_SHADER, gl::shaders::surface_vert, "surface.vert.glsl"},
                     {GL_FRAGMENT_SHADER, gl::shaders::surface_frag, "surface.frag.glsl"}},
                    "surface");
    GlProgram linePrograms[2] = {linkLineProgram(LineInput::Triangles, false),
                                 linkLineProgram(LineInput::Triangles, true)};
    // The compute stages and the computed segments' programs are built on first use: the iso
    // panel, which shares this class, never needs them, and every link adds to the first frame.
    std::unique_ptr<gl::GlLineCompute> compute;
    if (gl::GlLineCompute::available())
        compute = std::make_unique<gl::GlLineCompute>();
    resolveProgram(0, true); // a resolve variant, so that a compile error shows here
    GlVertexArray vertexArray = GlVertexArray::create();
    GlBuffer positionBuffer = GlBuffer::create(), normalBuffer = GlBuffer::create();
    glBindVertexArray(vertexArray.get());
    // Separate position and normal buffers: Mesh keeps them apart, so each uploads without an
    // interleaving copy.
    glBindBuffer(GL_ARRAY_BUFFER, positionBuffer.get());
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, normalBuffer.get());
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    glEnableVertexAttribArray(1);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    GlVertexArray emptyVertexArray = GlVertexArray::create();
    GlBuffer indexBuffer = GlBuffer::create(), candidateBuffer = GlBuffer::create();
    GlQuery segmentQuery = GlQuery::create();
    GlQuery timerQueries[3] = {GlQuery::create(), GlQuery::create(), GlQuery::create()};
    gl::checkGlError("SilhouetteGlRenderer::initialize");

    m_linePrograms[0] = std::move(linePrograms[0]);
    m_linePrograms[1] = std::move(linePrograms[1]);
    m_vertexArray = std::move(vertexArray);
    m_emptyVertexArray = std::move(emptyVertexArray);
    m_positionBuffer = std::move(positionBuffer);
    m_normalBuffer = std::move(normalBuffer);
    m_indexBuffer = std::move(indexBuffer);
    m_candidateBuffer = std::move(candidateBuffer);
    m_segmentQuery = std::move(segmentQuery);
    m_timerQueries[0] = std::move(timerQueries[0]);
    m_timerQueries[1] = std::move(timerQueries[1]);
    m_timerQueries[2] = std::move(timerQueries[2]);
    m_compute = std::move(compute);
    m_surfaceProgram = std::move(surfaceProgram); // last: isInitialized() from here on
}

void SilhouetteGlRenderer::uploadMesh(const Mesh& mesh) {
    uploadMesh(mesh.positions, mesh.normals, mesh.indices);
}

void SilhouetteGlRenderer::uploadMesh(std::span<const glm::vec3> positions,
                                      std::span<const glm::vec3> normals,
                                      std::span<const std::uint32_t> indices) {
    if (positions.size() != normals.size())
        throw core::Error("GL mesh upload", std::to_string(positions.size()) + " positions but " +
                                                std::to_string(normals.size()) + " normals");
    if (indices.size() % 3 != 0)
        throw core::Error("GL mesh upload",
                          std::to_string(indices.size()) + " indices is not a multiple of 3");
    // An index past the end would make the GPU read outside the buffer (undefined, not an error).
    std::uint32_t maxIndex = 0;
    for (std::uint32_t index : indices)
        maxIndex = std::max(maxIndex, index);
    if (!indices.empty() && maxIndex >= positions.size())
        throw core::Error("GL mesh upload", "index " + std::to_string(maxIndex) +
                                                " out of range for " +
                                                std::to_string(positions.size()) + " vertices");
    initialize();
    std::size_t vertexBytes = m_vertexCapacity * sizeof(glm::vec3);
    std::size_t normalBytes = vertexBytes;
    uploadBuffer(GL_ARRAY_BUFFER, m_positionBuffer.get(), positions.data(), positions.size_bytes(),
                 vertexBytes);
    uploadBuffer(GL_ARRAY_BUFFER, m_normalBuffer.get(), normals.data(), normals.size_bytes(),
                 normalBytes);
    const std::size_t oldVertexCapacity = m_vertexCapacity, oldIndexCapacity = m_indexCapacity;
    m_vertexCapacity = std::min(vertexBytes, normalBytes) / sizeof(glm::vec3);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    // The element buffer binding is vertex array state.
    glBindVertexArray(m_vertexArray.get());
    std::size_t indexBytes = m_indexCapacity * sizeof(std::uint32_t);
    uploadBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer.get(), indices.data(), indices.size_bytes(),
                 indexBytes);
    m_indexCapacity = indexBytes / sizeof(std::uint32_t);
    glBindVertexArray(0);
    m_indexCount = indices.size();
    if (m_vertexCapacity != oldVertexCapacity || m_indexCapacity != oldIndexCapacity)
        ++m_storageGeneration;
    gl::checkGlError("SilhouetteGlRenderer::uploadMesh");
}

bool SilhouetteGlRenderer::reserveLineCandidates(std::size_t triangleCount) {
    initialize();
    const std::size_t indices = std::max<std::size_t>(triangleCount * 3, 3);
    if (indices <= m_candidateCapacity)
        return false;
    const std::size_t capacity = indices + indices / 8;
    // Bound outside any vertex array: GL_ELEMENT_ARRAY_BUFFER is vertex-array state.
    glBindVertexArray(0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, m_candidateBuffer.get());
    glBufferData(GL_COPY_WRITE_BUFFER, GLsizeiptr(capacity * sizeof(std::uint32_t)), nullptr,
                 GL_DYNAMIC_DRAW);
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    m_candidateCapacity = capacity;
    gl::checkGlError("SilhouetteGlRenderer::reserveLineCandidates");
    return true;
}

void SilhouetteGlRenderer::writeMeshTail(std::size_t firstVertex, std::size_t firstTriangle,
                                         const Mesh& piece) {
    if (piece.isEmpty())
        return;
    if (firstVertex + piece.vertexCount() > m_vertexCapacity ||
        (firstTriangle + piece.triangleCount()) * 3 > m_indexCount)
        throw core::Error("SilhouetteGlRenderer::writeMeshTail",
                          "the piece does not fit the reserved mesh buffers");
    const auto vertexBytes = GLsizeiptr(piece.vertexCount() * sizeof(glm::vec3));
    const auto vertexOffset = GLintptr(firstVertex * sizeof(glm::vec3));
    glBindBuffer(GL_ARRAY_BUFFER, m_positionBuffer.get());
    glBufferSubData(GL_ARRAY_BUFFER, vertexOffset, vertexBytes, piece.positions.data());
    glBindBuffer(GL_ARRAY_BUFFER, m_normalBuffer.get());
    glBufferSubData(GL_ARRAY_BUFFER, vertexOffset, vertexBytes, piece.normals.data());
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    std::vector<std::uint32_t> shifted(piece.indices.size());
    for (std::size_t i = 0; i < shifted.size(); ++i)
        shifted[i] = std::uint32_t(firstVertex) + piece.indices[i];
    // Bound outside any vertex array: GL_ELEMENT_ARRAY_BUFFER is vertex-array state.
    glBindVertexArray(0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, m_indexBuffer.get());
    glBufferSubData(GL_COPY_WRITE_BUFFER, GLintptr(firstTriangle * 3 * sizeof(std::uint32_t)),
                    GLsizeiptr(shifted.size() * sizeof(std::uint32_t)), shifted.data());
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    gl::checkGlError("SilhouetteGlRenderer::writeMeshTail");
}

void SilhouetteGlRenderer::writeLineCandidatesTail(std::size_t firstIndex,
                                                   std::span<const std::uint32_t> indices) {
    if (indices.empty())
        return;
    if (firstIndex + indices.size() > m_candidateCapacity)
        throw core::Error("SilhouetteGlRenderer::writeLineCandidatesTail",
                          "the indices do not fit the reserved candidate buffer");
    glBindVertexArray(0);
    glBindBuffer(GL_COPY_WRITE_BUFFER, m_candidateBuffer.get());
    glBufferSubData(GL_COPY_WRITE_BUFFER, GLintptr(firstIndex * sizeof(std::uint32_t)),
                    GLsizeiptr(indices.size() * sizeof(std::uint32_t)), indices.data());
    glBindBuffer(GL_COPY_WRITE_BUFFER, 0);
    gl::checkGlError("SilhouetteGlRenderer::writeLineCandidatesTail");
}

bool SilhouetteGlRenderer::reserveMesh(std::size_t vertexCount, std::size_t triangleCount) {
    initialize();
    bool reallocated = false;
    // Room to grow by an eighth, so a slightly larger surface at the next iso-value reuses the
    // storage (and its CUDA registration).
    const auto grow = [](std::size_t n) { return n + n / 8; };
    if (vertexCount > m_vertexCapacity || m_vertexCapacity == 0) {
        const std::size_t capacity = std::max<std::size_t>(grow(vertexCount), 1);
        for (GLuint buffer : {m_positionBuffer.get(), m_normalBuffer.get()}) {
            glBindBuffer(GL_ARRAY_BUFFER, buffer);
            glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(capacity * sizeof(glm::vec3)), nullptr,
                         GL_DYNAMIC_DRAW);
        }
        glBindBuffer(GL_ARRAY_BUFFER, 0);
        m_vertexCapacity = capacity;
        reallocated = true;
    }
    if (triangleCount * 3 > m_indexCapacity || m_indexCapacity == 0) {
        const std::size_t capacity = std::max<std::size_t>(grow(triangleCount * 3), 3);
        glBindVertexArray(m_vertexArray.get());
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer.get());
        glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(capacity * sizeof(std::uint32_t)), nullptr,
                     GL_DYNAMIC_DRAW);
        glBindVertexArray(0);
        m_indexCapacity = capacity;
        reallocated = true;
    }
    m_indexCount = triangleCount * 3;
    if (reallocated)
        ++m_storageGeneration;
    gl::checkGlError("SilhouetteGlRenderer::reserveMesh");
    return reallocated;
}

void SilhouetteGlRenderer::clearMesh() {
    if (!isInitialized())
        return;
    glBindBuffer(GL_ARRAY_BUFFER, m_positionBuffer.get());
    glBufferData(GL_ARRAY_BUFFER, 0, nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, m_normalBuffer.get());
    glBufferData(GL_ARRAY_BUFFER, 0, nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    glBindVertexArray(m_vertexArray.get());
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer.get());
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, 0, nullptr, GL_DYNAMIC_DRAW);
    glBindVertexArray(0);
    m_vertexCapacity = m_indexCapacity = m_indexCount = 0;
    ++m_storageGeneration;
    gl::checkGlError("SilhouetteGlRenderer::clearMesh");
}

void SilhouetteGlRenderer::clear(int width, int height, glm::vec4 background) {
    initialize();
    m_lastFrameMaskOnly = false;
    const FramebufferBindingGuard bindingGuard;
    ensureFramebuffer(width, height);
    clearBuffers(background);
    gl::checkGlError("SilhouetteGlRenderer::clear");
}

void SilhouetteGlRenderer::clearBuffers(glm::vec4 background, bool colour, bool lineDepth) {
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDepthMask(GL_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.get());
    glClearColor(background.r, background.g, background.b, background.a);
    glClearDepth(1.0);
    glClear(colour ? GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT : GL_DEPTH_BUFFER_BIT);
    if (!lineDepth)
        return;
    glBindFramebuffer(GL_FRAMEBUFFER, m_lineFramebuffer.get());
    glClear(GL_DEPTH_BUFFER_BIT);
}

namespace {

// A 2D texture of `width` x `height` sampled texel for texel (no filtering, no mipmaps).
void allocateTexture(GLuint texture, GLint internalFormat, GLenum format, GLenum type, int width,
                     int height) {
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexImage2D(GL_TEXTURE_2D, 0, internalFormat, width, height, 0, format, type, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
}

void checkFramebufferComplete(const char* which) {
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status == GL_FRAMEBUFFER_COMPLETE)
        return;
    char hex[16];
    std::snprintf(hex, sizeof hex, "%04X", status);
    throw core::Error("GL render target",
                      std::string(which) + " framebuffer incomplete (status 0x" + hex + ")");
}

} // namespace

void SilhouetteGlRenderer::ensureFramebufferObjects() {
    for (GlFramebuffer* framebuffer : {&m_framebuffer, &m_lineFramebuffer, &m_resolveFramebuffer})
        if (!*framebuffer)
            *framebuffer = GlFramebuffer::create();
    for (GlTexture* texture : {&m_colourTexture, &m_surfaceDepthTexture, &m_lineDepthTexture})
        if (!*texture)
            *texture = GlTexture::create();
}

void SilhouetteGlRenderer::ensureFramebuffer(int width, int height) {
    if (width <= 0 || height <= 0)
        throw core::Error("GL render target",
                          "invalid size " + std::to_string(width) + "x" + std::to_string(height));
    if (m_framebuffer.get() && width == m_width && height == m_height)
        return;
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &maxSize);
    if (width > maxSize || height > maxSize)
        throw core::Error("GL render target", std::to_string(width) + "x" + std::to_string(height) +
                                                  " exceeds the driver's limit of " +
                                                  std::to_string(maxSize));
    ensureFramebufferObjects();
    allocateTexture(m_colourTexture.get(), GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE, width, height);
    // 32-bit float depth: CT surfaces span hundreds of mm, the tolerance is 0.1 % of that.
    for (GLuint texture : {m_surfaceDepthTexture.get(), m_lineDepthTexture.get()})
        allocateTexture(texture, GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT, width,
                        height);
    glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                           m_colourTexture.get(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D,
                           m_surfaceDepthTexture.get(), 0);
    checkFramebufferComplete("surface");
    // Pass 2 writes line depth and, when it draws the final lines itself, the colour.
    glBindFramebuffer(GL_FRAMEBUFFER, m_lineFramebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                           m_colourTexture.get(), 0);
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D,
                           m_lineDepthTexture.get(), 0);
    checkFramebufferComplete("line depth");
    // Pass 3 reads both depth textures, so none of them may be attached where it draws.
    glBindFramebuffer(GL_FRAMEBUFFER, m_resolveFramebuffer.get());
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                           m_colourTexture.get(), 0);
    checkFramebufferComplete("resolve");
    gl::checkGlError("SilhouetteGlRenderer: framebuffers");
    m_width = width;
    m_height = height;
}

// The next frame's stamp (silhouette.frag.glsl, LW_STAMP) in a stamp texture of the frame's size;
// the texture is cleared only when it is made and when the 32-bit stamp wraps.
void SilhouetteGlRenderer::nextStamp(int width, int height) {
    if (!m_stampFramebuffer)
        m_stampFramebuffer = GlFramebuffer::create();
    if (!m_stampTexture || m_stampSize != glm::ivec2(width, height)) {
        m_stampTexture = GlTexture::create();
        allocateTexture(m_stampTexture.get(), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, width,
                        height);
        glBindFramebuffer(GL_FRAMEBUFFER, m_stampFramebuffer.get());
        glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D,
                               m_stampTexture.get(), 0);
        checkFramebufferComplete("line stamps");
        m_stampSize = {width, height};
        m_stamp = 0;
    }
    if (++m_stamp == 1) { // new, or wrapped: no pixel may hold an old frame's stamp 1
        const GLuint zero[4] = {0, 0, 0, 0};
        glBindFramebuffer(GL_FRAMEBUFFER, m_stampFramebuffer.get());
        glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        glClearBufferuiv(GL_COLOR, 0, zero);
    }
}

SilhouetteGlStats SilhouetteGlRenderer::render(const Camera& camera,
                                               const SilhouetteGlOptions& options) {
    const glm::vec3 light(camera.panelLightDirection());
    return render(camera.viewProjectionMatrixF(), camera.viewerHomogeneous(), light, camera.width(),
                  camera.height(), options);
}

SilhouetteGlStats SilhouetteGlRenderer::render(const glm::mat4& viewProjection, glm::vec4 viewer,
                                               glm::vec3 lightDirection, int width, int height,
                                               const SilhouetteGlOptions& options) {
    queueRender(viewProjection, viewer, lightDirection, width, height, options);
    const SilhouetteGlStats stats = queuedStats();
    if (stats.incomplete) // queuedStats made room for every segment
        return render(viewProjection, viewer, lightDirection, width, height, options);
    return stats;
}

void SilhouetteGlRenderer::queueRender(const Camera& camera, const SilhouetteGlOptions& options) {
    const glm::vec3 light(camera.panelLightDirection());
    queueRender(camera.viewProjectionMatrixF(), camera.viewerHomogeneous(), light, camera.width(),
                camera.height(), options);
}

void SilhouetteGlRenderer::queueRender(const glm::mat4& viewProjection, glm::vec4 viewer,
                                       glm::vec3 lightDirection, int width, int height,
                                       const SilhouetteGlOptions& options) {
    if (options.lineWidth <= 0.0f)
        throw core::Error("silhouette line width",
                          std::to_string(options.lineWidth) + " is not positive");
    initialize();
    const FramebufferBindingGuard bindingGuard;
    ensureFramebuffer(width, height);
    glViewport(0, 0, width, height);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    QueuedFrame frame;
    frame.triangles = triangleCount();
    const bool iso = options.panel == GlPanel::Iso;
    frame.drawLines = !iso || options.linesOnIso;
    frame.drawSurface = m_indexCount > 0 && (iso || options.visibility);
    frame.segmentsOnGpu = frame.drawLines && options.cullLineCandidatesOnGpu && m_compute;
    // One-pixel lines of a complete frame need no pass 3: pass 2 colours them itself.
    const bool direct = options.resolve && resolveRadius(options.lineWidth) == 0;
    const bool maskOnly = options.maskOnly && !iso && frame.segmentsOnGpu && direct;
    if (options.clear)
        clearBuffers(options.background, !maskOnly, !maskOnly);
    if (maskOnly)
        nextStamp(width, height);
    m_lastFrameMaskOnly = maskOnly;
    frame.countSegments = options.countSegments;
    frame.timePasses = options.timePasses;
    // GPU timestamps before pass 1, between the passes and after the last (a GL_TIME_ELAPSED
    // pair around each pass cost the H200 up to 0.1 ms a frame more).
    const auto mark = [&](int i) {
        if (options.timePasses)
            glQueryCounter(m_timerQueries[i].get(), GL_TIMESTAMP);
    };
    mark(0);
    if (frame.drawSurface) {
        drawSurfacePass(viewProjection, viewer, lightDirection, options);
        // Sent now, so that the GPU draws while the rest is queued (the driver would hold the
        // commands until the host first waits).
        glFlush();
    }
    mark(1);
    if (frame.drawLines) {
        frame.segmentsComputed = frame.segmentsOnGpu && m_indexCount > 0;
        if (frame.segmentsComputed)
            computeSegments(viewProjection, viewer, width, height, options, frame.drawSurface);
        const bool query = frame.countSegments && !frame.segmentsOnGpu;
        if (query)
            glBeginQuery(GL_PRIMITIVES_GENERATED, m_segmentQuery.get());
        if (m_indexCount > 0)
            drawLinePass(viewProjection, viewer, options, direct && !maskOnly, maskOnly);
        if (query)
            glEndQuery(GL_PRIMITIVES_GENERATED);
        if (options.resolve && !direct)
            drawResolvePass(options, false); // pass 2 has tested visibility
    }
    mark(2);
    glBindVertexArray(0);
    glUseProgram(0);
    gl::checkGlError("SilhouetteGlRenderer::queueRender");
    m_queued = frame;
}

SilhouetteGlStats SilhouetteGlRenderer::queuedStats() {
    if (!m_queued)
        throw core::Error("SilhouetteGlRenderer::queuedStats", "no frame is queued");
    const QueuedFrame frame = *m_queued;
    m_queued.reset();
    SilhouetteGlStats stats;
    stats.triangles = frame.triangles;
    // The queries are read once every pass is queued: reading one right after its pass would
    // stall the CPU until the GPU had drained, with the next pass not yet sent.
    if (frame.timePasses) {
        const GLuint64 between = queryResult(m_timerQueries[1].get());
        if (frame.drawSurface)
            stats.surfacePassMs = nanosecondsToMs(queryResult(m_timerQueries[0].get()), between);
        if (frame.drawLines)
            stats.linePassMs = nanosecondsToMs(between, queryResult(m_timerQueries[2].get()));
    }
    if (frame.segmentsOnGpu) {
        // Where the compute pass did not run, its command holds no count of this frame (before
        // the first pass, no count at all: the buffer's contents are undefined).
        const gl::GlLineCompute::SegmentCounts counts = frame.segmentsComputed
                                                            ? m_compute->segmentCounts()
                                                            : gl::GlLineCompute::SegmentCounts{};
        stats.segments = counts.found;
        if (counts.toDraw > m_compute->segmentCapacity()) {
            // Rare: the buffer holds a quarter of the triangles' count from the start, and keeps
            // what it grew to.
            kLog.info("method 1: " + std::to_string(counts.toDraw) +
                      " silhouette segments, more than the buffer held; the frame is drawn again");
            m_compute->reserveSegments(counts.toDraw);
            stats.incomplete = true;
        }
    } else if (frame.drawLines && frame.countSegments) {
        GLuint primitives = 0;
        glGetQueryObjectuiv(m_segmentQuery.get(), GL_QUERY_RESULT, &primitives);
        stats.segments = primitives;
    }
    gl::checkGlError("SilhouetteGlRenderer::queuedStats");
    return stats;
}

// Pass 2's segments by a compute shader (GlLineCompute), after pass 1: where pass 2 will discard
// hidden fragments against a complete surface depth, hidden segments are dropped before drawing.
void SilhouetteGlRenderer::computeSegments(const glm::mat4& viewProjection, glm::vec4 viewer,
                                           int width, int height,
                                           const SilhouetteGlOptions& options, bool surfaceDrawn) {
    gl::GlLineCompute::HiddenLineTest hidden;
    if (surfaceDrawn && options.visibility && options.resolve)
        hidden = {m_surfaceDepthTexture.get(), options.depthTolerance};
    m_compute->computeSegments(m_positionBuffer.get(), m_normalBuffer.get(), m_indexBuffer.get(),
                               triangleCount(), viewProjection, viewer,
                               glm::vec2(float(width), float(height)), hidden);
}

// Pass 1: the surface. The silhouette panel needs it only as the depth to test against.
void SilhouetteGlRenderer::drawSurfacePass(const glm::mat4& viewProjection, glm::vec4 viewer,
                                           glm::vec3 lightDirection,
                                           const SilhouetteGlOptions& options) {
    const bool iso = options.panel == GlPanel::Iso;
    glBindFramebuffer(GL_FRAMEBUFFER, m_framebuffer.get());
    glUseProgram(m_surfaceProgram.get());
    glUniformMatrix4fv(uniform(m_surfaceProgram.get(), "uViewProjection"), 1, GL_FALSE,
                       glm::value_ptr(viewProjection));
    glUniform4fv(uniform(m_surfaceProgram.get(), "uViewer"), 1, glm::value_ptr(viewer));
    glUniform3fv(uniform(m_surfaceProgram.get(), "uLightDirection"), 1,
                 glm::value_ptr(lightDirection));
    glUniform3fv(uniform(m_surfaceProgram.get(), "uFrontColour"), 1,
                 glm::value_ptr(options.frontColour));
    glUniform3fv(uniform(m_surfaceProgram.get(), "uBackColour"), 1,
                 glm::value_ptr(options.backColour));
    glUniform4fv(uniform(m_surfaceProgram.get(), "uMaterial"), 1, glm::value_ptr(options.material));
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glColorMask(iso, iso, iso, iso);
    if (!iso && options.cullBackFacesInDepthPass) {
        glEnable(GL_CULL_FACE);
        glFrontFace(GL_CCW);
        glCullFace(GL_BACK);
    }
    glBindVertexArray(m_vertexArray.get());
    glDrawElements(GL_TRIANGLES, GLsizei(m_indexCount), GL_UNSIGNED_INT, nullptr);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
}

// Pass 2: the silhouette segments from the geometry shader, the nearest kept per pixel (its depth
// test is against the other lines only). A frame drawn in one call has its whole surface depth
// by now, so the fragments test visibility here; pieces leave it to the resolve.
void SilhouetteGlRenderer::drawLinePass(const glm::mat4& viewProjection, glm::vec4 viewer,
                                        const SilhouetteGlOptions& options, bool writeColour,
                                        bool stamp) {
    glBindFramebuffer(GL_FRAMEBUFFER, stamp ? m_stampFramebuffer.get() : m_lineFramebuffer.get());
    const bool testVisibility = options.visibility && options.resolve;
    const bool computed = options.cullLineCandidatesOnGpu && m_compute;
    GlProgram& segmentProgram = m_segmentLinePrograms[int(testVisibility) + 2 * int(stamp)];
    if (computed && !segmentProgram)
        segmentProgram = linkLineProgram(LineInput::ComputedSegments, testVisibility, stamp);
    const GLuint program = computed ? segmentProgram.get() : m_linePrograms[testVisibility].get();
    glUseProgram(program);
    glUniformMatrix4fv(uniform(program, "uViewProjection"), 1, GL_FALSE,
                       glm::value_ptr(viewProjection));
    glUniform4fv(uniform(program, "uViewer"), 1, glm::value_ptr(viewer));
    glUniform2f(uniform(program, "uViewportSize"), float(m_width), float(m_height));
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, testVisibility ? m_surfaceDepthTexture.get() : 0);
    glUniform1i(uniform(program, "uSurfaceDepth"), 0);
    glUniform1f(uniform(program, "uTolerance"), options.depthTolerance);
    glUniform1ui(uniform(program, "uStamp"), m_stamp);
    glUniform4fv(uniform(program, "uLineColour"), 1, glm::value_ptr(options.lineColour));
    // A stamp marks the pixel whichever line is nearest: no depth there.
    const bool colour = writeColour || stamp;
    glColorMask(colour, colour, colour, colour);
    if (stamp) {
        glDisable(GL_DEPTH_TEST);
    } else {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
    }
    // The computed segments have no attributes; the triangles read the mesh's.
    glBindVertexArray(computed ? m_emptyVertexArray.get() : m_vertexArray.get());
    if (computed) {
        m_compute->drawSegments(program);
    } else if (options.useLineCandidates) {
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_candidateBuffer.get());
        glDrawElements(GL_TRIANGLES,
                       GLsizei(std::min(options.lineCandidateIndices, m_candidateCapacity)),
                       GL_UNSIGNED_INT, nullptr);
        glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m_indexBuffer.get());
    } else {
        glDrawElements(GL_TRIANGLES, GLsizei(m_indexCount), GL_UNSIGNED_INT, nullptr);
    }
    glDisable(GL_DEPTH_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBindTexture(GL_TEXTURE_2D, 0);
}

unsigned SilhouetteGlRenderer::resolveProgram(int radius, bool visibility) {
    const int key = radius * 2 + (visibility ? 1 : 0);
    for (const auto& [programKey, program] : m_resolvePrograms)
        if (programKey == key)
            return program.get();
    const std::string defines = "#define LW_RADIUS " + std::to_string(radius) +
                                "\n#define LW_VISIBILITY " + (visibility ? "1" : "0") + "\n";
    GlProgram program = linkProgram(
        {{GL_VERTEX_SHADER, gl::shaders::silhouette_resolve_vert, "silhouette_resolve.vert.glsl"},
         {GL_FRAGMENT_SHADER, withVisibilityRule(gl::shaders::silhouette_resolve_frag, defines),
          "silhouette_resolve.frag.glsl"}},
        "silhouette resolve");
    return m_resolvePrograms.emplace_back(key, std::move(program)).second.get();
}

void SilhouetteGlRenderer::resolve(const SilhouetteGlOptions& options) {
    if (!m_framebuffer.get())
        throw core::Error("silhouette resolve", "nothing has been drawn yet");
    const FramebufferBindingGuard bindingGuard;
    glViewport(0, 0, m_width, m_height);
    drawResolvePass(options, options.visibility);
    glBindVertexArray(0);
    glUseProgram(0);
    gl::checkGlError("SilhouetteGlRenderer::resolve");
}

// Pass 3: the visible line pixels as antialiased strokes of the line width, in the line colour
// over what pass 1 left; with `testVisibility` the nearest line of each pixel is tested here (a
// frame drawn in pieces).
void SilhouetteGlRenderer::drawResolvePass(const SilhouetteGlOptions& options,
                                           bool testVisibility) {
    glBindFramebuffer(GL_FRAMEBUFFER, m_resolveFramebuffer.get());
    glDisable(GL_DEPTH_TEST);
    // The strokes' coverage blends the line colour over what pass 1 left (the background, or the
    // iso panel's surface); the alpha stays the background's.
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    const GLuint program = resolveProgram(resolveRadius(options.lineWidth), testVisibility);
    glUseProgram(program);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, m_surfaceDepthTexture.get());
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, m_lineDepthTexture.get());
    glUniform1i(uniform(program, "uSurfaceDepth"), 0);
    glUniform1i(uniform(program, "uLineDepth"), 1);
    glUniform1f(uniform(program, "uTolerance"), options.depthTolerance);
    glUniform4fv(uniform(program, "uLineColour"), 1, glm::value_ptr(options.lineColour));
    glUniform1f(uniform(program, "uReach"), float(PixelMask::strokeReach(options.lineWidth)));
    glBindVertexArray(m_emptyVertexArray.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glDisable(GL_BLEND);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, 0);
}

namespace {

// glReadPixels of the whole framebuffer object into tightly packed client memory, whatever pack
// state the caller left set (restored afterwards).
// The rectangle (x, y, width, height) in GL's bottom-up rows.
void readFramebuffer(unsigned framebuffer, int x, int y, int width, int height, GLenum format,
                     GLenum type, void* pixels, const char* what) {
    const FramebufferBindingGuard bindingGuard;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
    if (format != GL_DEPTH_COMPONENT)
        glReadBuffer(GL_COLOR_ATTACHMENT0);
    GLint alignment = 4, packBuffer = 0;
    glGetIntegerv(GL_PACK_ALIGNMENT, &alignment);
    glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &packBuffer);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glReadPixels(x, y, width, height, format, type, pixels);
    glPixelStorei(GL_PACK_ALIGNMENT, alignment);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(packBuffer));
    gl::checkGlError(what);
}

} // namespace

core::ImageRgba8 SilhouetteGlRenderer::readImage() const {
    if (!m_framebuffer.get())
        throw core::Error("GL read-back", "nothing has been rendered yet");
    if (m_lastFrameMaskOnly)
        throw core::Error("GL read-back", "the last frame was drawn as a line mask only");
    core::ImageRgba8 image(m_width, m_height);
    readFramebuffer(m_framebuffer.get(), 0, 0, m_width, m_height, GL_RGBA, GL_UNSIGNED_BYTE,
                    image.bytes(), "SilhouetteGlRenderer::readImage");
    image.flipRows(); // GL's first row is the bottom one
    return image;
}

void SilhouetteGlRenderer::readRedMask(std::uint8_t backgroundRed,
                                       std::vector<std::uint8_t>& mask) {
    if (!m_framebuffer.get())
        throw core::Error("GL read-back", "nothing has been rendered yet");
    if (m_compute) {
        if (m_lastFrameMaskOnly)
            m_compute->readMask(m_stampTexture.get(), m_stamp, m_width, m_height, backgroundRed,
                                mask);
        else
            m_compute->readMask(m_colourTexture.get(), 0, m_width, m_height, backgroundRed, mask);
        return;
    }
    // Read straight into the mask (no second buffer per frame), then turn GL's bottom-up rows
    // around and threshold in place.
    const std::size_t width = std::size_t(m_width);
    mask.resize(width * std::size_t(m_height));
    readFramebuffer(m_framebuffer.get(), 0, 0, m_width, m_height, GL_RED, GL_UNSIGNED_BYTE,
                    mask.data(), "SilhouetteGlRenderer::readRedMask");
    for (int y = 0; y < m_height / 2; ++y)
        std::swap_ranges(mask.begin() + std::ptrdiff_t(std::size_t(y) * width),
                         mask.begin() + std::ptrdiff_t(std::size_t(y + 1) * width),
                         mask.begin() + std::ptrdiff_t(std::size_t(m_height - 1 - y) * width));
    for (std::uint8_t& red : mask)
        red = red != backgroundRed ? 1 : 0;
}

std::vector<float> SilhouetteGlRenderer::readDepth() const {
    if (!m_framebuffer.get())
        throw core::Error("GL depth read-back", "nothing has been rendered yet");
    std::vector<float> depth(std::size_t(m_width) * std::size_t(m_height));
    readFramebuffer(m_framebuffer.get(), 0, 0, m_width, m_height, GL_DEPTH_COMPONENT, GL_FLOAT,
                    depth.data(), "SilhouetteGlRenderer::readDepth");
    // GL's first row is the bottom one; callers index top row first like the images.
    for (int y = 0; y < m_height / 2; ++y)
        std::swap_ranges(depth.begin() + std::ptrdiff_t(y) * m_width,
                         depth.begin() + std::ptrdiff_t(y + 1) * m_width,
                         depth.begin() + std::ptrdiff_t(m_height - 1 - y) * m_width);
    return depth;
}

float SilhouetteGlRenderer::readDepthAt(int x, int y) const {
    if (!m_framebuffer.get())
        throw core::Error("GL depth read-back", "nothing has been rendered yet");
    if (x < 0 || y < 0 || x >= m_width || y >= m_height)
        return 1.0f;
    float depth = 1.0f;
    readFramebuffer(m_framebuffer.get(), x, m_height - 1 - y, 1, 1, GL_DEPTH_COMPONENT, GL_FLOAT,
                    &depth, "SilhouetteGlRenderer::readDepthAt");
    return depth;
}

core::ImageRgba8 SilhouetteGlRenderer::renderImage(const Camera& camera,
                                                   const SilhouetteGlOptions& options) {
    render(camera, options);
    return readImage();
}

} // namespace lw::render
