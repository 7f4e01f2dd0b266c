#include "lw/render/zbuffer_silhouette_renderer.h"

#include "lw/core/error.h"
#include "lw/core/log.h"
#include "zbuffer_kernel_set.h"

#include <cmath>
#include <limits>
#include <string>

namespace lw::render {
namespace {

constexpr core::LogCategory kLog("lw.render");
constexpr double kNoIso = std::numeric_limits<double>::quiet_NaN();

} // namespace

struct ZBufferSilhouetteRenderer::State {
    const volume::Volume* volume = nullptr;
    std::unique_ptr<ZBufferKernelSet> kernels;
    // The CPU's kernel set once the back-end's ways down are exhausted (until the next volume).
    std::unique_ptr<ZBufferKernelSet> cpuFallback;
    bool onFallback = false;

    // Mode a: the kept surface is for keptIso (NaN: none kept), closed at the border or not,
    // with normals from keptStencil.
    double keptIso = kNoIso;
    bool keptClosing = false;
    GradientStencil keptStencil = GradientStencil::Central;
    // Whether the open surface at touchIso touches the border (pieces: computed on the host once).
    double touchIso = kNoIso;
    bool touches = false;
    // For mesh() after a frame that kept no surface.
    double lastIso = kNoIso;
    bool lastKept = false;
    unsigned lastThreads = 0;
    bool lastClosing = true;
    GradientStencil lastStencil = GradientStencil::Central;
    mutable Mesh lateMesh;
    mutable double lateMeshIso = kNoIso;
    mutable bool lateMeshClosing = true;
    mutable GradientStencil lateMeshStencil = GradientStencil::Central;

    ZBufferKernelSet& active() { return onFallback ? *cpuFallback : *kernels; }
    void forgetSurface() {
        keptIso = kNoIso;
        touchIso = kNoIso;
        lateMeshIso = kNoIso;
        lateMesh = Mesh();
    }
    // What mesh() extracts after a frame that kept no whole surface.
    void rememberFrame(const SilhouetteSettings& settings) {
        lastIso = settings.isoReal;
        lastThreads = settings.threads;
        lastClosing = settings.closeAtBorder;
        lastStencil = settings.gradientStencil;
    }
    void keepWhole(ZBufferKernelSet& set, const SilhouetteSettings& settings,
                   SilhouetteFrame& frame);
    void frameOn(ZBufferKernelSet& set, const Camera& camera, const SilhouetteSettings& settings,
                 SilhouetteFrame& frame);
    void fallBack(const OutOfDeviceMemory& error);
};

ZBufferKernelSet::DeviceShading ZBufferKernelSet::shadeWhole(const Camera&, const SurfaceShading&,
                                                             core::ImageRgba8&,
                                                             std::vector<float>*) {
    throw core::Error(std::string("method 3 (") + std::string(backendName()) + ")",
                      "this back-end shades the iso panel from the host mesh");
}

// Extracts the whole surface of settings' iso-value unless the kept one is it (mode a).
void ZBufferSilhouetteRenderer::State::keepWhole(ZBufferKernelSet& set,
                                                 const SilhouetteSettings& settings,
                                                 SilhouetteFrame& frame) {
    const bool reuse = settings.mode == ExtractionMode::CachedA && keptIso == settings.isoReal &&
                       keptClosing == settings.closeAtBorder &&
                       keptStencil == settings.gradientStencil;
    if (reuse)
        return;
    keptIso = kNoIso;
    touches = set.extractWhole(storedIsoValue(*volume, settings.isoReal), settings, frame);
    touchIso = settings.isoReal;
    keptIso = settings.isoReal;
    keptClosing = settings.closeAtBorder;
    keptStencil = settings.gradientStencil;
}

void ZBufferSilhouetteRenderer::State::frameOn(ZBufferKernelSet& set, const Camera& camera,
                                               const SilhouetteSettings& settings,
                                               SilhouetteFrame& frame) {
    const double storedIso = storedIsoValue(*volume, settings.isoReal);
    set.beginFrame(camera, settings, frame);
    const bool whole = settings.brickCells == 0 && set.keepsWholeSurface(camera, settings);
    if (whole) {
        keepWhole(set, settings, frame);
        set.drawWhole(camera, settings, settings.closeAtBorder || !touches, frame);
    } else {
        keptIso = kNoIso;
        if (!settings.closeAtBorder && !(touchIso == settings.isoReal)) {
            touches = surfaceTouchesBorder(*volume, storedIso);
            touchIso = settings.isoReal;
        }
        set.drawPieces(camera, settings, storedIso, settings.closeAtBorder || !touches, frame);
    }
    const float epsilon = settings.visibility ? depthEpsilon(camera, *volume) : 0.0f;
    set.resolve(settings, epsilon, frame);
    lastKept = whole;
}

void ZBufferSilhouetteRenderer::State::fallBack(const OutOfDeviceMemory& error) {
    keptIso = kNoIso;
    if (!onFallback && kernels->fallBack()) {
        kLog.warning(std::string("method 3 (") + std::string(kernels->backendName()) +
                     "): " + error.what() + "; trying slabs");
        return;
    }
    kLog.warning(std::string("method 3 (") + std::string(kernels->backendName()) +
                 "): " + error.what() + "; rendering on the CPU");
    kernels->bind(nullptr); // frees what the failed attempt holds
    if (!cpuFallback)
        cpuFallback = makeCpuZBufferKernels();
    cpuFallback->bind(volume);
    onFallback = true;
}

ZBufferSilhouetteRenderer::ZBufferSilhouetteRenderer(Backend backend)
    : m_state(std::make_unique<State>()) {
    if (backend == Backend::Cuda) {
        m_state->kernels = makeCudaZBufferKernels();
        if (!m_state->kernels)
            throw core::Error("method 3", "this build has no CUDA back-end");
    } else {
        m_state->kernels = makeCpuZBufferKernels();
    }
}

ZBufferSilhouetteRenderer::~ZBufferSilhouetteRenderer() = default;

std::string_view ZBufferSilhouetteRenderer::backendName() const {
    return m_state->onFallback ? m_state->cpuFallback->backendName()
                               : m_state->kernels->backendName();
}

bool ZBufferSilhouetteRenderer::drawsToFrameTargets() const {
    return !m_state->onFallback && m_state->kernels->drawsToFrameTargets();
}

void ZBufferSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    State& s = *m_state;
    s.volume = &volume;
    s.onFallback = false;
    s.kernels->bind(&volume);
    if (s.cpuFallback)
        s.cpuFallback->bind(nullptr);
    s.forgetSurface();
}

void ZBufferSilhouetteRenderer::setVolumeWithDeviceCopy(const volume::Volume& volume,
                                                        DeviceVoxelCopy copy) {
    setVolume(volume);
    m_state->kernels->useDeviceCopy(copy);
}

void ZBufferSilhouetteRenderer::releaseVolume() {
    State& s = *m_state;
    s.kernels->bind(nullptr);
    if (s.cpuFallback)
        s.cpuFallback->bind(nullptr);
    s.volume = nullptr;
    s.onFallback = false;
    s.forgetSurface();
    s.lastIso = kNoIso;
}

const Mesh& ZBufferSilhouetteRenderer::mesh() const {
    State& s = *m_state;
    if (s.lastKept) {
        if (const Mesh* kept = s.active().keptMesh())
            return *kept;
    }
    if (s.volume && !std::isnan(s.lastIso) &&
        !(s.lateMeshIso == s.lastIso && s.lateMeshClosing == s.lastClosing &&
          s.lateMeshStencil == s.lastStencil)) {
        // After a frame that kept no surface: the whole surface only now, for a caller that
        // asks for it.
        IsoSurfaceOptions options;
        options.threads = s.lastThreads;
        options.closeAtBorder = s.lastClosing;
        options.gradientStencil = s.lastStencil;
        extractIsoSurface(*s.volume, s.lastIso, options, s.lateMesh);
        s.lateMeshIso = s.lastIso;
        s.lateMeshClosing = s.lastClosing;
        s.lateMeshStencil = s.lastStencil;
    }
    return s.lateMesh;
}

std::optional<Mesh> ZBufferSilhouetteRenderer::contourTriangles(const Camera& camera) const {
    State& s = *m_state;
    if (!s.lastKept)
        return std::nullopt;
    return s.active().contourTriangles(camera);
}

SilhouetteFrame ZBufferSilhouetteRenderer::renderFrame(const Camera& camera,
                                                       const SilhouetteSettings& settings) {
    State& s = *m_state;
    if (!s.volume)
        throw core::Error("method 3 (z-buffer)", "no volume bound: call setVolume first");
    if (settings.brickCells < 0)
        throw core::Error("method 3 (z-buffer)", "brickCells must be 0 (whole volume) or positive");
    if (settings.cancel && settings.cancel->isCancelled())
        throw core::Cancelled();
    s.rememberFrame(settings);
    s.lastKept = false;
    for (;;) {
        SilhouetteFrame frame;
        try {
            s.frameOn(s.active(), camera, settings, frame);
            return frame;
        } catch (const OutOfDeviceMemory& error) {
            s.fallBack(error);
        }
    }
}

std::optional<ZBufferSilhouetteRenderer::DeviceShadedSurface>
ZBufferSilhouetteRenderer::shadeOnDevice(const Camera& camera, const SilhouetteSettings& settings,
                                         const SurfaceShading& shading, bool wantDepth) {
    State& s = *m_state;
    if (!s.volume || s.onFallback || !s.kernels->shadesOnDevice() || settings.brickCells != 0)
        return std::nullopt;
    if (settings.cancel && settings.cancel->isCancelled())
        throw core::Cancelled();
    DeviceShadedSurface out;
    try {
        SilhouetteFrame frame;
        // The budget is the frame's (beginFrame sets it); a surface kept by the last silhouette
        // frame is whole (pieces forget it).
        s.kernels->beginFrame(camera, settings, frame);
        if (!s.kernels->keepsWholeSurface(camera, settings))
            return std::nullopt;
        s.keepWhole(*s.kernels, settings, frame);
        s.rememberFrame(settings);
        s.lastKept = true;
        out.extractMs = frame.times.extractMs;
        const ZBufferKernelSet::DeviceShading shaded =
            s.kernels->shadeWhole(camera, shading, out.image, wantDepth ? &out.depth : nullptr);
        out.triangles = shaded.triangles;
        out.shadeMs = shaded.rasterMs + shaded.shadeMs;
    } catch (const OutOfDeviceMemory& error) {
        kLog.warning(std::string("iso panel on the device: ") + error.what() +
                     "; shaded from the host mesh");
        s.kernels->bind(s.volume); // frees what the attempt holds
        s.forgetSurface();
        s.lastKept = false;
        return std::nullopt;
    }
    return out;
}

float ZBufferSilhouetteRenderer::depthEpsilon(const Camera& camera, const volume::Volume& volume) {
    return depthKeyTolerance(camera, volumeBounds(volume));
}

} // namespace lw::render
