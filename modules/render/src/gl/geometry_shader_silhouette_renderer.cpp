#include "lw/render/geometry_shader_silhouette_renderer.h"

#include "gl_api.h"
#include "lw/core/error.h"
#include "lw/core/log.h"
#include "lw/render/gl_context.h"
#include "lw/render/silhouette_gl_renderer.h"

#include <chrono>
#include <optional>

namespace lw::render {
namespace {

constexpr core::LogCategory kLog("lw.render");

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The silhouette panel's colours: black lines on white, so "not background" is a line pixel.
constexpr core::Rgba8 kBackground{255, 255, 255, 255};

} // namespace

struct GeometryShaderSilhouetteRenderer::State {
    std::unique_ptr<GlContext> ownedContext;
    GlContext* context = nullptr;
    SilhouetteGlRenderer gl;
    const volume::Volume* volume = nullptr;
    Mesh mesh;
    // What the uploaded mesh was extracted with; empty when there is none (or the volume changed).
    std::optional<double> meshIso;
    int meshBrickCells = 0;

    // Extracts and uploads when `force` or the cached mesh was made with other settings;
    // returns the time spent (0 when the cache was used).
    double ensureMesh(const SilhouetteSettings& settings, bool force) {
        if (!volume)
            throw core::Error("method 1", "render called before setVolume");
        if (!force && meshIso && *meshIso == settings.isoReal &&
            meshBrickCells == settings.brickCells)
            return 0.0;
        const auto start = Clock::now();
        IsoSurfaceOptions options;
        options.brickCells = settings.brickCells;
        options.threads = settings.threads;
        meshIso.reset(); // a failed extraction or upload leaves no stale cache behind
        extractIsoSurface(*volume, settings.isoReal, options, mesh);
        gl.uploadMesh(mesh);
        glFinish(); // the upload is part of this stage, not of the next draw
        meshIso = settings.isoReal;
        meshBrickCells = settings.brickCells;
        return msSince(start);
    }
};

GeometryShaderSilhouetteRenderer::GeometryShaderSilhouetteRenderer()
    : m_state(std::make_unique<State>()) {
    m_state->ownedContext = std::make_unique<EglHeadlessContext>();
    m_state->context = m_state->ownedContext.get();
    kLog.info("method 1 on " + m_state->context->description());
}

GeometryShaderSilhouetteRenderer::GeometryShaderSilhouetteRenderer(GlContext& context)
    : m_state(std::make_unique<State>()) {
    m_state->context = &context;
}

GeometryShaderSilhouetteRenderer::~GeometryShaderSilhouetteRenderer() {
    // GL objects belong to the context: free them while it is still alive and current.
    try {
        m_state->context->makeCurrent();
        m_state->gl.release();
    } catch (const std::exception& error) {
        kLog.warning(std::string("method 1: GL objects not released: ") + error.what());
    }
}

void GeometryShaderSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    m_state->volume = &volume;
    m_state->meshIso.reset();
    m_state->mesh = Mesh{};
}

const Mesh& GeometryShaderSilhouetteRenderer::mesh() const {
    return m_state->mesh;
}

std::string GeometryShaderSilhouetteRenderer::contextDescription() const {
    return m_state->context->description();
}

SilhouetteFrame GeometryShaderSilhouetteRenderer::render(const Camera& camera,
                                                         const SilhouetteSettings& settings) {
    State& s = *m_state;
    s.context->makeCurrent();
    SilhouetteFrame frame;
    frame.times.extractMs = s.ensureMesh(settings, settings.mode == ExtractionMode::EveryFrameB);

    SilhouetteGlOptions options;
    options.panel = GlPanel::Silhouette;
    options.visibility = settings.visibility;
    options.lineColour = {0.0f, 0.0f, 0.0f, 1.0f};
    options.background = {1.0f, 1.0f, 1.0f, 1.0f};
    options.countSegments = true;
    // Nothing queued before this point may be billed to the draw.
    glFinish();
    const auto start = Clock::now();
    const SilhouetteGlStats stats = s.gl.render(camera, options);
    glFinish();
    frame.lines = PixelMask::fromImage(s.gl.readImage(), kBackground);
    frame.times.drawMs = msSince(start);
    frame.triangles = stats.triangles;
    frame.segments = stats.segments;
    return frame;
}

core::ImageRgba8
GeometryShaderSilhouetteRenderer::renderIsoPanel(const Camera& camera,
                                                 const SilhouetteSettings& settings) {
    State& s = *m_state;
    s.context->makeCurrent();
    s.ensureMesh(settings, false);
    SilhouetteGlOptions options;
    options.panel = GlPanel::Iso;
    options.visibility = settings.visibility;
    return s.gl.renderImage(camera, options);
}

} // namespace lw::render
