#pragma once

// The GL renderers need nothing but a current OpenGL 4.x core context -- plain GL behind a thin
// context, so the same renderer code runs headless and in a widget: headless EGL here and in the
// CLI, QOpenGLWidget's context in the GUI. Only this interface crosses module boundaries; EGL
// types stay in the .cpp.

#include <algorithm>
#include <cctype>
#include <memory>
#include <string>
#include <string_view>

namespace lw::render {

class GlContext {
public:
    virtual ~GlContext() = default;
    // Makes the context current on the calling thread. Throws core::Error on failure.
    virtual void makeCurrent() = 0;
    virtual void doneCurrent() = 0;
    // "vendor | renderer | version" of the context, for logs and reports.
    virtual std::string description() const = 0;
};

// Whether a GL_RENDERER string (or a description() holding it) names a software rasterizer
// (Mesa's llvmpipe, softpipe, swrast): one that runs the vertex and geometry work on the CPU,
// inside the draw call.
inline bool isSoftwareRenderer(std::string_view renderer) {
    std::string lower(renderer);
    std::transform(lower.begin(), lower.end(), lower.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    for (const char* name : {"llvmpipe", "softpipe", "swrast", "software rasterizer"})
        if (lower.find(name) != std::string::npos)
            return true;
    return false;
}

// Which EGL display a headless context came from.
enum class EglPlatform {
    Device,          // EGL_EXT_platform_device: a GPU without a window system (NVIDIA)
    SurfacelessMesa, // EGL_MESA_platform_surfaceless (Mesa: llvmpipe or a GPU; NVIDIA offers it
                     // too)
    SoftwareDevice,  // a device that Mesa enumerates as software (EGL_MESA_device_software)
    DefaultDisplay,  // EGL_DEFAULT_DISPLAY, the last resort
};

const char* eglPlatformName(EglPlatform platform);

struct EglContextOptions {
    int majorVersion = 4;
    int minorVersion = 5;
    bool debug = false; // a debug context (KHR_debug messages are then logged under lw.render)
};

// A headless OpenGL core context made current without a surface (a 1x1 pbuffer where the display
// lacks EGL_KHR_surfaceless_context); the renderers draw into their own framebuffer objects.
// Tries, in order: the device platform's hardware devices, surfaceless Mesa, software devices,
// EGL_DEFAULT_DISPLAY; throws core::Error listing why each failed when none gives a context.
// The context is current on the constructing thread afterwards.
class EglHeadlessContext final : public GlContext {
public:
    explicit EglHeadlessContext(const EglContextOptions& options = {});
    ~EglHeadlessContext() override;
    EglHeadlessContext(const EglHeadlessContext&) = delete;
    EglHeadlessContext& operator=(const EglHeadlessContext&) = delete;

    void makeCurrent() override;
    void doneCurrent() override;
    std::string description() const override;

    EglPlatform platform() const;
    std::string vendor() const;
    std::string renderer() const;
    std::string version() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::render
