#include "gl_api.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/gl_context.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <cstring>
#include <string>
#include <vector>

namespace lw::render {

namespace {

const core::LogCategory kLog("lw.render");

bool hasExtension(const char* list, const char* name) {
    if (!list)
        return false;
    const std::size_t length = std::strlen(name);
    for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += length) {
        // Whole words only: EGL_EXT_device_base must not match EGL_EXT_device_base_foo.
        const bool startOk = p == list || p[-1] == ' ';
        const bool endOk = p[length] == ' ' || p[length] == '\0';
        if (startOk && endOk)
            return true;
    }
    return false;
}

std::string eglErrorText(EGLint error) {
    switch (error) {
    case EGL_SUCCESS:
        return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
        return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
        return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
        return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
        return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
        return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
        return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE:
        return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY:
        return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
        return "EGL_BAD_MATCH";
    case EGL_BAD_NATIVE_PIXMAP:
        return "EGL_BAD_NATIVE_PIXMAP";
    case EGL_BAD_NATIVE_WINDOW:
        return "EGL_BAD_NATIVE_WINDOW";
    case EGL_BAD_PARAMETER:
        return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
        return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST:
        return "EGL_CONTEXT_LOST";
    default:
        return "EGL error " + std::to_string(error);
    }
}

std::string eglFailure(const char* call) {
    return std::string(call) + " failed (" + eglErrorText(eglGetError()) + ")";
}

std::string glString(GLenum name) {
    const auto* text = reinterpret_cast<const char*>(glGetString(name));
    return text ? text : "";
}

void APIENTRY debugMessage(GLenum, GLenum type, GLuint, GLenum severity, GLsizei,
                           const GLchar* message, const void*) {
    // Driver chatter (performance hints, notifications) stays at debug level; real API errors are
    // also thrown by checkGlError, so a warning is enough here.
    const bool serious = type == GL_DEBUG_TYPE_ERROR || severity == GL_DEBUG_SEVERITY_HIGH;
    kLog.write(serious ? core::LogLevel::Warning : core::LogLevel::Debug,
               std::string("GL: ") + message);
}

struct Candidate {
    EglPlatform platform;
    EGLDisplay display;
    std::string name;
};

} // namespace

const char* eglPlatformName(EglPlatform platform) {
    switch (platform) {
    case EglPlatform::Device:
        return "EGL device";
    case EglPlatform::SurfacelessMesa:
        return "EGL surfaceless platform";
    case EglPlatform::SoftwareDevice:
        return "EGL software device";
    case EglPlatform::DefaultDisplay:
        return "EGL default display";
    }
    return "EGL";
}

struct EglHeadlessContext::Impl {
    EGLDisplay display = EGL_NO_DISPLAY;
    EGLContext context = EGL_NO_CONTEXT;
    EGLSurface surface = EGL_NO_SURFACE; // a 1x1 pbuffer only when surfaceless contexts are missing
    EglPlatform platform = EglPlatform::DefaultDisplay;
    std::string vendor, renderer, version;

    static EGLConfig pbufferConfig(EGLDisplay dpy) {
        const EGLint configAttribs[] = {EGL_SURFACE_TYPE,
                                        EGL_PBUFFER_BIT,
                                        EGL_RENDERABLE_TYPE,
                                        EGL_OPENGL_BIT,
                                        EGL_RED_SIZE,
                                        8,
                                        EGL_GREEN_SIZE,
                                        8,
                                        EGL_BLUE_SIZE,
                                        8,
                                        EGL_NONE};
        EGLConfig config = nullptr;
        EGLint configCount = 0;
        const bool found =
            eglChooseConfig(dpy, configAttribs, &config, 1, &configCount) && configCount >= 1;
        return found ? config : nullptr;
    }

    // An OpenGL core context, or EGL_NO_CONTEXT with each version's error in `errors`.
    static EGLContext createCoreContext(EGLDisplay dpy, EGLConfig config,
                                        const EglContextOptions& options, std::string& errors) {
        // 4.5 first (what the renderers are written against); 4.1 still has geometry shaders and
        // everything the silhouette pipeline uses, so older drivers get a chance too.
        std::vector<std::pair<int, int>> versions{{options.majorVersion, options.minorVersion}};
        if (options.majorVersion > 4 || (options.majorVersion == 4 && options.minorVersion > 1))
            versions.emplace_back(4, 1);
        for (auto [want, wantMinor] : versions) {
            const EGLint contextAttribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                             want,
                                             EGL_CONTEXT_MINOR_VERSION,
                                             wantMinor,
                                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                             EGL_CONTEXT_OPENGL_DEBUG,
                                             options.debug ? EGL_TRUE : EGL_FALSE,
                                             EGL_NONE};
            const EGLContext created =
                eglCreateContext(dpy, config, EGL_NO_CONTEXT, contextAttribs);
            if (created != EGL_NO_CONTEXT)
                return created;
            // append(), not operator+ on a literal: GCC 12 reports a false -Wrestrict for that.
            errors.append(" ")
                .append(std::to_string(want))
                .append(".")
                .append(std::to_string(wantMinor));
            errors.append(": ").append(eglErrorText(eglGetError()));
        }
        return EGL_NO_CONTEXT;
    }

    // Reads the context's strings; empty when usable, else why not.
    std::string checkUsable() {
        // A context that cannot answer glGetString is not usable (e.g. a vendor library that
        // loaded but has no device behind it).
        renderer = glString(GL_RENDERER);
        vendor = glString(GL_VENDOR);
        version = glString(GL_VERSION);
        if (renderer.empty() || version.empty())
            return "the context reports no GL_RENDERER/GL_VERSION";
        GLint glMajor = 0;
        glGetIntegerv(GL_MAJOR_VERSION, &glMajor);
        if (glMajor < 4)
            return "OpenGL " + version + " is older than 4.x";
        return {};
    }

    // Tries one display; on failure cleans up and returns the reason.
    bool tryDisplay(const Candidate& candidate, const EglContextOptions& options,
                    std::string& reason) {
        EGLDisplay dpy = candidate.display;
        if (dpy == EGL_NO_DISPLAY) {
            reason = "no display";
            return false;
        }
        EGLint major = 0, minor = 0;
        if (!eglInitialize(dpy, &major, &minor)) {
            reason = eglFailure("eglInitialize");
            return false;
        }
        auto fail = [&](std::string why) {
            if (surface != EGL_NO_SURFACE)
                eglDestroySurface(dpy, surface);
            if (context != EGL_NO_CONTEXT) {
                eglMakeCurrent(dpy, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
                eglDestroyContext(dpy, context);
            }
            surface = EGL_NO_SURFACE;
            context = EGL_NO_CONTEXT;
            // No eglTerminate: EGL displays are per-process singletons, so terminating one could
            // pull it out from under another context that lives on the same display.
            reason = std::move(why);
            return false;
        };
        const char* extensions = eglQueryString(dpy, EGL_EXTENSIONS);
        const bool surfaceless = hasExtension(extensions, "EGL_KHR_surfaceless_context");
        if (!eglBindAPI(EGL_OPENGL_API))
            return fail(eglFailure("eglBindAPI(EGL_OPENGL_API)"));

        EGLConfig config = pbufferConfig(dpy);
        if (!config)
            return fail("no EGL config with OpenGL and pbuffer support");

        std::string contextErrors;
        context = createCoreContext(dpy, config, options, contextErrors);
        if (context == EGL_NO_CONTEXT)
            return fail("eglCreateContext (OpenGL core) failed:" + contextErrors);
        if (!surfaceless) {
            const EGLint pbufferAttribs[] = {EGL_WIDTH, 1, EGL_HEIGHT, 1, EGL_NONE};
            surface = eglCreatePbufferSurface(dpy, config, pbufferAttribs);
            if (surface == EGL_NO_SURFACE)
                return fail(eglFailure("eglCreatePbufferSurface"));
        }
        if (!eglMakeCurrent(dpy, surface, surface, context))
            return fail(eglFailure("eglMakeCurrent"));
        if (std::string unusable = checkUsable(); !unusable.empty())
            return fail(unusable);
        display = dpy;
        platform = candidate.platform;
        return true;
    }
};

EglHeadlessContext::EglHeadlessContext(const EglContextOptions& options)
    : m_impl(std::make_unique<Impl>()) {
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    const bool platformBase =
        getPlatformDisplay && hasExtension(clientExtensions, "EGL_EXT_platform_base");

    // Candidates in order of preference. Hardware devices first (the NVIDIA machine has no window
    // system at all); Mesa lists its software rasterizer as a device too, which we only want
    // after surfaceless Mesa (EGL_MESA_platform_surfaceless: llvmpipe without a window system,
    // the path CI and the development machines take).
    std::vector<Candidate> hardware, software;
    std::string attempts;
    // EGL_EXT_device_base is the older name that bundles enumeration and query.
    const bool enumeration = hasExtension(clientExtensions, "EGL_EXT_device_enumeration") ||
                             hasExtension(clientExtensions, "EGL_EXT_device_base");
    if (platformBase && enumeration && hasExtension(clientExtensions, "EGL_EXT_platform_device")) {
        auto queryDevices =
            reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
        auto queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(
            eglGetProcAddress("eglQueryDeviceStringEXT"));
        EGLint count = 0;
        if (queryDevices && queryDevices(0, nullptr, &count) && count > 0) {
            std::vector<EGLDeviceEXT> devices(static_cast<std::size_t>(count));
            queryDevices(count, devices.data(), &count);
            for (EGLint i = 0; i < count; ++i) {
                const char* deviceExtensions =
                    queryDeviceString ? queryDeviceString(devices[i], EGL_EXTENSIONS) : nullptr;
                const bool isSoftware = hasExtension(deviceExtensions, "EGL_MESA_device_software");
                Candidate candidate{
                    isSoftware ? EglPlatform::SoftwareDevice : EglPlatform::Device,
                    getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr),
                    "EGL device " + std::to_string(i)};
                (isSoftware ? software : hardware).push_back(candidate);
            }
            if (hardware.empty())
                attempts += "\n  EGL devices: " + std::to_string(count) +
                            " enumerated, none of them hardware";
        } else {
            attempts += "\n  EGL devices: none enumerated";
        }
    } else {
        attempts += "\n  EGL devices: EGL_EXT_device_enumeration/platform_device not offered";
    }
    std::vector<Candidate> candidates = hardware;
    if (platformBase && hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless"))
        candidates.push_back(
            {EglPlatform::SurfacelessMesa,
             getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr),
             "EGL surfaceless platform"});
    else
        attempts += "\n  EGL surfaceless platform: EGL_MESA_platform_surfaceless not offered";
    candidates.insert(candidates.end(), software.begin(), software.end());
    candidates.push_back(
        {EglPlatform::DefaultDisplay, eglGetDisplay(EGL_DEFAULT_DISPLAY), "EGL_DEFAULT_DISPLAY"});

    for (const Candidate& candidate : candidates) {
        std::string reason;
        if (m_impl->tryDisplay(candidate, options, reason)) {
            if (options.debug && hasExtension(glString(GL_EXTENSIONS).c_str(), "GL_KHR_debug")) {
                glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
                glDebugMessageCallback(debugMessage, nullptr);
            }
            // Say why preferred displays were passed over: on a GPU machine, landing on a software
            // rasterizer is worth knowing.
            if (!attempts.empty())
                kLog.info("EGL displays passed over:" + attempts);
            kLog.info("OpenGL context on " + candidate.name + ": " + description());
            return;
        }
        attempts += "\n  " + candidate.name + ": " + reason;
    }
    throw core::Error("headless OpenGL (EGL)",
                      "no OpenGL 4.x core context could be created:" + attempts);
}

EglHeadlessContext::~EglHeadlessContext() {
    if (m_impl->display == EGL_NO_DISPLAY)
        return;
    eglMakeCurrent(m_impl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (m_impl->surface != EGL_NO_SURFACE)
        eglDestroySurface(m_impl->display, m_impl->surface);
    eglDestroyContext(m_impl->display, m_impl->context);
    // No eglTerminate: the display is a per-process singleton that another context (a second
    // EglHeadlessContext, a library) may still be using; the process exit releases it.
    eglReleaseThread();
}

void EglHeadlessContext::makeCurrent() {
    if (!eglMakeCurrent(m_impl->display, m_impl->surface, m_impl->surface, m_impl->context))
        throw core::Error("headless OpenGL (EGL)", eglFailure("eglMakeCurrent"));
}

void EglHeadlessContext::doneCurrent() {
    eglMakeCurrent(m_impl->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
}

std::string EglHeadlessContext::description() const {
    return m_impl->vendor + " | " + m_impl->renderer + " | " + m_impl->version + " (" +
           eglPlatformName(m_impl->platform) + ")";
}

EglPlatform EglHeadlessContext::platform() const {
    return m_impl->platform;
}
std::string EglHeadlessContext::vendor() const {
    return m_impl->vendor;
}
std::string EglHeadlessContext::renderer() const {
    return m_impl->renderer;
}
std::string EglHeadlessContext::version() const {
    return m_impl->version;
}

} // namespace lw::render
