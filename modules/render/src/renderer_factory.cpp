#include "lw/render/renderer_factory.h"

#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/raycast_silhouette_renderer.h"
#include "lw/render/silhouette_methods.h"
#include "lw/render/zbuffer_silhouette_renderer.h"

#if LINEWORK_GL
#include "lw/render/geometry_shader_silhouette_renderer.h"
#endif
#if LINEWORK_CUDA
#include "lw/kernels/cuda/cuda_device.h"
#endif

namespace lw::render {
namespace {

constexpr core::LogCategory kLog("lw.render");
#if LINEWORK_CUDA_GL_INTEROP && LINEWORK_GL
constexpr bool kCudaGlInterop = true;
#else
constexpr bool kCudaGlInterop = false;
#endif

} // namespace

SilhouetteMethod parseSilhouetteMethod(std::string_view text, std::string_view option) {
    if (const SilhouetteMethodInfo* info = findSilhouetteMethod(text))
        return info->method;
    throw core::Error(std::string(option) + " " + std::string(text),
                      "expected " + silhouetteMethodKeys());
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

CudaAvailability cudaAvailability() {
    CudaAvailability availability;
#if LINEWORK_CUDA
    // Probed once per process: the answer does not change while it runs, and the first probe
    // pays for the CUDA context (0.2-0.35 s on an H100).
    static const kernels::cuda::CudaDeviceInfo device = kernels::cuda::probeCudaDevice();
    availability.built = true;
    availability.available = device.available;
    availability.deviceName = device.name;
    availability.reason = device.available ? std::string() : device.reason;
#else
    availability.reason = "this build has no CUDA backend (no nvcc, or LINEWORK_CUDA=OFF)";
#endif
    return availability;
}

Backend resolveBackend(Backend requested, std::string* backendNote) {
    return resolveBackend(requested, SilhouetteMethod::ZBuffer, backendNote);
}

Backend resolveBackend(Backend requested, SilhouetteMethod method, std::string* backendNote) {
    std::string note;
    Backend chosen = Backend::Cpu;
    if (requested != Backend::Cpu) {
        const CudaAvailability cuda = cudaAvailability();
        // A method drawn with OpenGL has CUDA only where this build has CUDA-GL interop.
        const SilhouetteMethodInfo& info = silhouetteMethodInfo(method);
        const bool hasKernels = info.hasCuda && (!info.needsOpenGl || kCudaGlInterop);
        if (requested == Backend::Cuda) {
            if (!cuda.available)
                throw core::Error("--backend cuda", cuda.reason);
            if (!hasKernels)
                throw core::Error("--backend cuda",
                                  "method " + std::string(info.key) +
                                      " has no CUDA implementation in this build");
            chosen = Backend::Cuda;
        } else if (!cuda.available) {
            note = "auto: " + cuda.reason + ", using CPU";
        } else if (!hasKernels) {
            note = "auto: method " + std::string(info.key) +
                   " has no CUDA implementation yet, using CPU";
        } else {
            chosen = Backend::Cuda;
            note = "auto: CUDA on " + cuda.deviceName;
        }
    }
    if (backendNote)
        *backendNote = note;
    return chosen;
}

std::unique_ptr<SilhouetteRenderer>
createSilhouetteRenderer(SilhouetteMethod method, Backend requested, std::string* backendNote) {
    std::string note;
    const Backend backend = resolveBackend(requested, method, &note);
    if (!note.empty())
        kLog.info(note);
    if (backendNote)
        *backendNote = note;
    switch (method) {
    case SilhouetteMethod::GeometryShader:
#if LINEWORK_GL
        try {
            auto renderer = std::make_unique<GeometryShaderSilhouetteRenderer>();
            if (backend == Backend::Cuda)
                renderer->useCudaExtraction();
            return renderer;
        } catch (const core::Error& error) {
            throw core::Error("method 1", std::string("no OpenGL context: ") + error.what());
        }
#else
        throw core::Error("method 1",
                          "no OpenGL context: this build has no OpenGL/EGL (LINEWORK_GL=0)");
#endif
    case SilhouetteMethod::RayCastVisibility:
        return std::make_unique<RayCastSilhouetteRenderer>(backend == Backend::Cuda ? Backend::Cuda
                                                                                    : Backend::Cpu);
    case SilhouetteMethod::ZBuffer:
        return std::make_unique<ZBufferSilhouetteRenderer>(backend == Backend::Cuda ? Backend::Cuda
                                                                                    : Backend::Cpu);
    }
    throw core::Error("silhouette method",
                      std::to_string(int(method)) + " is not " + silhouetteMethodKeys());
}

} // namespace lw::render
