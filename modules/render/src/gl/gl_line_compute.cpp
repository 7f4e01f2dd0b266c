#include "gl_line_compute.h"

#include "gl_api.h"
#include "gl_program.h"
#include "lw/core/error.h"
#include "lw_render_shaders.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <initializer_list>
#include <string>

namespace lw::render::gl {

namespace {

constexpr std::size_t kGroupSize = 256; // local_size_x of both compute shaders
constexpr std::size_t kMaxGroupsPerDimension = 65535;
// The command buffer: a DrawArraysIndirectCommand (vertex count, instances, first vertex, base
// instance), then the count of segments found (line_segments.comp.glsl).
constexpr std::size_t kCommandWords = 5;

// Enough groups of kGroupSize for `items`, laid out in two dimensions (the shaders number
// them row by row and skip what lies past the end).
void dispatchFor(std::size_t items) {
    const std::size_t groups = std::max<std::size_t>((items + kGroupSize - 1) / kGroupSize, 1);
    const std::size_t columns = std::min(groups, kMaxGroupsPerDimension);
    const std::size_t rows = (groups + columns - 1) / columns;
    if (rows > kMaxGroupsPerDimension)
        throw core::Error("GL compute",
                          std::to_string(items) + " items are more than one dispatch holds");
    glDispatchCompute(GLuint(columns), GLuint(rows), 1);
}

// Storage buffer bindings 0, 1, ... as the shaders number them (0: unbind).
void bindStorage(std::initializer_list<GLuint> buffers) {
    GLuint binding = 0;
    for (const GLuint buffer : buffers)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding++, buffer);
}

// Waits until the GPU has run every command issued so far (a fence; flushed, so it cannot wait
// on commands still in the driver's queue).
void waitForGpu(const char* what) {
    GLsync fence = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    if (!fence)
        throw core::Error(what, "no GL fence");
    constexpr GLuint64 kSecond = 1'000'000'000;
    constexpr int kPatienceSeconds = 60;
    GLenum result = GL_TIMEOUT_EXPIRED;
    for (int waited = 0; waited < kPatienceSeconds && result == GL_TIMEOUT_EXPIRED; ++waited)
        result = glClientWaitSync(fence, GL_SYNC_FLUSH_COMMANDS_BIT, kSecond);
    glDeleteSync(fence);
    if (result != GL_ALREADY_SIGNALED && result != GL_CONDITION_SATISFIED)
        throw core::Error(what, result == GL_TIMEOUT_EXPIRED
                                    ? "the GPU did not finish the frame within a minute"
                                    : "waiting for the GPU failed");
}

// Whether the current context's OpenGL version is at least major.minor.
bool versionAtLeast(GLint major, GLint minor) {
    GLint have[2] = {0, 0};
    glGetIntegerv(GL_MAJOR_VERSION, &have[0]);
    glGetIntegerv(GL_MINOR_VERSION, &have[1]);
    return have[0] > major || (have[0] == major && have[1] >= minor);
}

} // namespace

bool GlLineCompute::available() {
    if (!versionAtLeast(4, 3))
        return false;
    GLint vertexBuffers = 0;
    glGetIntegerv(GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS, &vertexBuffers);
    return vertexBuffers >= 1;
}

void GlLineCompute::initialize() {
    if (m_segmentProgram)
        return;
    m_persistentMapping = versionAtLeast(4, 4); // glBufferStorage
    GlProgram segments =
        linkProgram({{GL_COMPUTE_SHADER,
                      afterVersionLine(shaders::line_segments_comp, shaders::silhouette_segment),
                      "line_segments.comp.glsl"}},
                    "line segments");
    GlProgram mask = linkProgram(
        {{GL_COMPUTE_SHADER, shaders::line_mask_comp, "line_mask.comp.glsl"}}, "line mask");
    GlBuffer command = GlBuffer::create(), maskBuffer = GlBuffer::create(),
             segmentBuffer = GlBuffer::create();
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, command.get());
    glBufferData(GL_DRAW_INDIRECT_BUFFER, kCommandWords * sizeof(GLuint), nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    checkGlError("GlLineCompute::initialize");
    m_maskProgram = std::move(mask);
    m_command = std::move(command);
    m_mask = std::move(maskBuffer);
    m_segments = std::move(segmentBuffer);
    m_segmentProgram = std::move(segments); // last: initialised from here on
}

void GlLineCompute::reserveSegments(std::size_t segments) {
    initialize();
    segments = std::max<std::size_t>(segments, 1024);
    if (segments <= m_segmentCapacity)
        return;
    const std::size_t capacity = segments + segments / 8;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, m_segments.get());
    glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(capacity * 2 * sizeof(glm::vec4)), nullptr,
                 GL_DYNAMIC_COPY);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    checkGlError("GlLineCompute::reserveSegments");
    m_segmentCapacity = capacity;
}

void GlLineCompute::computeSegments(unsigned positions, unsigned normals, unsigned indices,
                                    std::size_t triangleCount, const glm::mat4& viewProjection,
                                    glm::vec4 viewer, glm::vec2 viewportSize,
                                    HiddenLineTest hidden) {
    initialize();
    if (m_segmentCapacity == 0)
        reserveSegments(triangleCount / 4);
    const std::array<GLuint, kCommandWords> command{0, 1, 0, 0, 0};
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_command.get());
    glBufferSubData(GL_DRAW_INDIRECT_BUFFER, 0, sizeof command, command.data());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    const GLuint program = m_segmentProgram.get();
    glUseProgram(program);
    glUniformMatrix4fv(glGetUniformLocation(program, "uViewProjection"), 1, GL_FALSE,
                       &viewProjection[0][0]);
    glUniform4f(glGetUniformLocation(program, "uViewer"), viewer.x, viewer.y, viewer.z, viewer.w);
    glUniform2f(glGetUniformLocation(program, "uViewportSize"), viewportSize.x, viewportSize.y);
    glUniform1ui(glGetUniformLocation(program, "uTriangleCount"), GLuint(triangleCount));
    glUniform1ui(glGetUniformLocation(program, "uSegmentCapacity"), GLuint(m_segmentCapacity));
    glUniform1i(glGetUniformLocation(program, "uCullHidden"), hidden.surfaceDepthTexture != 0);
    glUniform1f(glGetUniformLocation(program, "uTolerance"), hidden.tolerance);
    glUniform1i(glGetUniformLocation(program, "uSurfaceDepth"), 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, hidden.surfaceDepthTexture);
    bindStorage({positions, normals, indices, m_segments.get(), m_command.get()});
    dispatchFor(triangleCount);
    bindStorage({0, 0, 0, 0, 0});
    glBindTexture(GL_TEXTURE_2D, 0);
    // Pass 2 reads the segments in its vertex shader and the count as a draw command;
    // segmentCounts() reads the command with glGetBufferSubData, which sees a shader's storage
    // writes only after a buffer-update barrier (they are incoherent).
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT |
                    GL_BUFFER_UPDATE_BARRIER_BIT);
    glUseProgram(0);
    checkGlError("GlLineCompute::computeSegments");
}

GlLineCompute::SegmentCounts GlLineCompute::segmentCounts() const {
    std::array<GLuint, kCommandWords> command{};
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_command.get());
    glGetBufferSubData(GL_DRAW_INDIRECT_BUFFER, 0, sizeof command, command.data());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    checkGlError("GlLineCompute::segmentCounts");
    return {command[4], command[0] / 2};
}

void GlLineCompute::drawSegments(unsigned program) const {
    glUniform1ui(glGetUniformLocation(program, "uVertexCapacity"), GLuint(2 * m_segmentCapacity));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, m_segments.get());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_command.get());
    glDrawArraysIndirect(GL_LINES, nullptr);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, 0);
}

void GlLineCompute::reserveMask(std::size_t bytes) {
    if (bytes <= m_maskBytes)
        return;
    GlBuffer buffer = GlBuffer::create();
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer.get());
    m_maskMapped = nullptr;
    if (m_persistentMapping) {
        // In client memory, mapped for good: the shader's bytes cross the bus as it writes them,
        // and the host copies them out without a driver read-back.
        constexpr GLbitfield kAccess =
            GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
        glBufferStorage(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr,
                        kAccess | GL_CLIENT_STORAGE_BIT);
        m_maskMapped = glMapBufferRange(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(bytes), kAccess);
        if (!m_maskMapped)
            throw core::Error("GL line mask", "the read-back buffer could not be mapped");
    } else {
        glBufferData(GL_SHADER_STORAGE_BUFFER, GLsizeiptr(bytes), nullptr, GL_STREAM_READ);
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    checkGlError("GlLineCompute::reserveMask");
    m_mask = std::move(buffer); // the old buffer (unmapped as it goes) is deleted
    m_maskBytes = bytes;
}

void GlLineCompute::readMask(unsigned texture, std::uint32_t stamp, int width, int height,
                             std::uint8_t backgroundRed, std::vector<std::uint8_t>& mask) {
    initialize();
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    const std::size_t words = (pixels + 3) / 4;
    reserveMask(words * 4);
    const GLuint program = m_maskProgram.get();
    glUseProgram(program);
    glUniform2i(glGetUniformLocation(program, "uSize"), width, height);
    glUniform1ui(glGetUniformLocation(program, "uBackgroundRed"), backgroundRed);
    glUniform1ui(glGetUniformLocation(program, "uStamp"), stamp);
    const GLenum unit = stamp != 0 ? GL_TEXTURE1 : GL_TEXTURE0; // the shaders' bindings
    glActiveTexture(unit);
    glBindTexture(GL_TEXTURE_2D, texture);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m_mask.get());
    dispatchFor(words);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
    glActiveTexture(GL_TEXTURE0);
    glUseProgram(0);
    mask.resize(pixels);
    if (m_maskMapped) {
        glMemoryBarrier(GL_CLIENT_MAPPED_BUFFER_BARRIER_BIT);
        waitForGpu("GL line mask");
        std::memcpy(mask.data(), m_maskMapped, pixels);
    } else {
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, m_mask.get());
        glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, GLsizeiptr(pixels), mask.data());
        glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
    }
    checkGlError("GlLineCompute::readMask");
}

} // namespace lw::render::gl
