#include "lw/render/renderer_factory.h"

#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/raycast_silhouette_renderer.h"
#include "lw/render/zbuffer_silhouette_renderer.h"

#if LINEWORK_GL
#include "lw/render/geometry_shader_silhouette_renderer.h"
#endif

namespace lw::render {
namespace {

constexpr core::LogCategory kLog("lw.render");

} // namespace

SilhouetteMethod parseSilhouetteMethod(std::string_view text, std::string_view option) {
    if (text == "1")
        return SilhouetteMethod::GeometryShader;
    if (text == "2")
        return SilhouetteMethod::RayCastVisibility;
    if (text == "3")
        return SilhouetteMethod::ZBuffer;
    throw core::Error(std::string(option) + " " + std::string(text), "expected 1, 2 or 3");
}

Backend parseBackend(std::string_view text, std::string_view option) {
    if (text == "cpu")
        return Backend::Cpu;
    if (text == "cuda")
        return Backend::Cuda;
    if (text == "auto")
        return Backend::Auto;
    throw core::Error(std::string(option) + " " + std::string(text), "expected cpu, cuda or auto");
}

std::string_view backendName(Backend backend) {
    switch (backend) {
    case Backend::Cpu:
        return "cpu";
    case Backend::Cuda:
        return "cuda";
    case Backend::Auto:
        return "auto";
    }
    return "?";
}

Backend resolveBackend(Backend requested, std::string* backendNote) {
    if (requested == Backend::Cuda)
        throw core::Error("--backend cuda", "the CUDA backend is not built yet");
    if (backendNote) {
        if (requested == Backend::Auto)
            *backendNote = "auto: no CUDA backend in this build, using CPU";
        else
            backendNote->clear();
    }
    return Backend::Cpu;
}

std::unique_ptr<SilhouetteRenderer>
createSilhouetteRenderer(SilhouetteMethod method, Backend requested, std::string* backendNote) {
    std::string note;
    resolveBackend(requested, &note);
    if (!note.empty())
        kLog.info(note);
    if (backendNote)
        *backendNote = note;
    switch (method) {
    case SilhouetteMethod::GeometryShader:
#if LINEWORK_GL
        try {
            return std::make_unique<GeometryShaderSilhouetteRenderer>();
        } catch (const core::Error& error) {
            throw core::Error("method 1", std::string("no OpenGL context: ") + error.what());
        }
#else
        throw core::Error("method 1",
                          "no OpenGL context: this build has no OpenGL/EGL (LINEWORK_GL=0)");
#endif
    case SilhouetteMethod::RayCastVisibility:
        return std::make_unique<RayCastSilhouetteRenderer>();
    case SilhouetteMethod::ZBuffer:
        return std::make_unique<ZBufferSilhouetteRenderer>();
    }
    throw core::Error("silhouette method", std::to_string(int(method)) + " is not 1, 2 or 3");
}

} // namespace lw::render
