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
    GLint geometryBuffers = 0;
    glGetIntegerv(GL_MAX_GEOMETRY_SHADER_STORAGE_BLOCKS, &geometryBuffers);
    return geometryBuffers >= 4;
}

void GlLineCompute::initialize() {
    if (m_cullProgram)
        return;
    m_persistentMapping = versionAtLeast(4, 4); // glBufferStorage
    GlProgram cull = linkProgram(
        {{GL_COMPUTE_SHADER, shaders::line_candidates_comp, "line_candidates.comp.glsl"}},
        "line candidates");
    GlProgram mask = linkProgram(
        {{GL_COMPUTE_SHADER, shaders::line_mask_comp, "line_mask.comp.glsl"}}, "line mask");
    GlBuffer command = GlBuffer::create(), maskBuffer = GlBuffer::create();
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, command.get());
    glBufferData(GL_DRAW_INDIRECT_BUFFER, 4 * sizeof(GLuint), nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    checkGlError("GlLineCompute::initialize");
    m_maskProgram = std::move(mask);
    m_command = std::move(command);
    m_mask = std::move(maskBuffer);
    m_cullProgram = std::move(cull); // last: initialised from here on
}

void GlLineCompute::cullCandidates(unsigned positions, unsigned normals, unsigned indices,
                                   std::size_t triangleCount, glm::vec4 viewer,
                                   unsigned candidates) {
    initialize();
    const std::array<GLuint, 4> command{0, 1, 0, 0}; // count, instanceCount, first, baseInstance
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_command.get());
    glBufferSubData(GL_DRAW_INDIRECT_BUFFER, 0, sizeof command, command.data());
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    const GLuint program = m_cullProgram.get();
    glUseProgram(program);
    glUniform4f(glGetUniformLocation(program, "uViewer"), viewer.x, viewer.y, viewer.z, viewer.w);
    glUniform1ui(glGetUniformLocation(program, "uTriangleCount"), GLuint(triangleCount));
    bindStorage({positions, normals, indices, candidates, m_command.get()});
    dispatchFor(triangleCount);
    bindStorage({0, 0, 0, 0, 0});
    // Pass 2 reads the candidates in its geometry shader and the count as a draw command.
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT);
    glUseProgram(0);
    checkGlError("GlLineCompute::cullCandidates");
}

void GlLineCompute::drawCandidates(unsigned positions, unsigned normals, unsigned indices,
                                   unsigned candidates) const {
    bindStorage({positions, normals, indices, candidates});
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, m_command.get());
    glDrawArraysIndirect(GL_POINTS, nullptr);
    glBindBuffer(GL_DRAW_INDIRECT_BUFFER, 0);
    bindStorage({0, 0, 0, 0});
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

void GlLineCompute::readMask(unsigned colourTexture, int width, int height,
                             std::uint8_t backgroundRed, std::vector<std::uint8_t>& mask) {
    initialize();
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    const std::size_t words = (pixels + 3) / 4;
    reserveMask(words * 4);
    const GLuint program = m_maskProgram.get();
    glUseProgram(program);
    glUniform2i(glGetUniformLocation(program, "uSize"), width, height);
    glUniform1ui(glGetUniformLocation(program, "uBackgroundRed"), backgroundRed);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, colourTexture);
    glUniform1i(glGetUniformLocation(program, "uColour"), 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, m_mask.get());
    dispatchFor(words);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
    glBindTexture(GL_TEXTURE_2D, 0);
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
