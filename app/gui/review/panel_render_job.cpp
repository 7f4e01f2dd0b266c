#include "review/panel_render_job.h"

#include "lw/render/gl_context.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/suggestive_contours.h"
#include "lw/render/surface_sampling.h"
#include "review/qt_image.h"
#include "review/review_panel.h"

#include <QPainter>
#include <cstring>
#include <optional>

namespace lw::gui {
namespace {

// `mesh`: the surface on screen, or (the review keeps its surface on the device) the one made
// here on demand from the drawn volume.
QImage renderIso(const PanelRenderJob& job, const render::Mesh& mesh) {
    const render::SilhouetteGlOptions options =
        panelGlOptions(PanelKind::Iso, job.appearance, job.camera, job.bounds);
    if (job.isoOnCpu)
        return shadeIsoOnCpu(&mesh, job.camera, options);
    // A headless context of this thread's own (no Qt context may be current here).
    render::EglHeadlessContext context;
    render::SilhouetteGlRenderer gl;
    gl.uploadMesh(mesh);
    return toQImage(gl.renderImage(job.camera, options)); // gl goes before the context
}

render::Mesh extractedSurface(const PanelRenderJob& job, const volume::Volume& volume) {
    render::IsoSurfaceOptions options;
    options.closeAtBorder = job.appearance.closeAtBorder;
    options.gradientStencil = job.appearance.gradientStencil;
    return render::extractIsoSurface(volume, job.iso, options);
}

} // namespace

QImage shadeIsoOnCpu(const render::Mesh* mesh, const render::Camera& camera,
                     const render::SilhouetteGlOptions& options, unsigned threads,
                     std::vector<float>* depth) {
    render::SurfaceShading shading = render::glPanelShading(camera, options);
    shading.threads = threads;
    return toQImage(render::shadeSurfaceCpu(mesh ? *mesh : render::Mesh(), camera, shading, depth));
}

int lineDilationRadius(double lineWidth) {
    return int((lineWidth - 1.0) / 2.0 + 0.5);
}

QImage linesToImage(const render::PixelMask& lines, const ReviewSettings& appearance,
                    bool transparent, double lineWidth) {
    const int radius = lineDilationRadius(lineWidth);
    const render::PixelMask mask = radius > 0 ? lines.dilated(radius) : lines;
    QImage image(mask.width(), mask.height(), QImage::Format_ARGB32);
    const QRgb line = appearance.lineColour.rgb();
    const QRgb background = transparent ? qRgba(0, 0, 0, 0) : appearance.background.rgb();
    const auto& pixels = mask.pixels();
    for (int y = 0; y < mask.height(); ++y) {
        auto* row = reinterpret_cast<QRgb*>(image.scanLine(y));
        const std::uint8_t* source = pixels.data() + std::size_t(y) * std::size_t(mask.width());
        for (int x = 0; x < mask.width(); ++x)
            row[x] = source[x] ? line : background;
    }
    return image;
}

std::pair<QImage, QImage> renderPanelJob(const PanelRenderJob& job, PanelVectors* vectors) {
    // The volume the review's methods draw (its oversampled copy where the settings make one).
    const std::shared_ptr<const volume::Volume> volume =
        render::volumeToRender(job.volume, job.appearance.volumeSampling(), job.iso);
    QImage iso = renderIso(job, job.mesh ? *job.mesh : extractedSurface(job, *volume));
    auto renderer = render::createSilhouetteRenderer(job.appearance.method, job.appearance.backend);
    renderer->setVolume(*volume);
    render::SilhouetteSettings settings;
    settings.isoReal = job.iso;
    settings.brickCells = job.brickCells;
    settings.visibility = job.appearance.visibility;
    settings.testAlongSegment = job.appearance.testAlongSegment;
    settings.minStrokePixels = job.appearance.minStrokePixels;
    settings.closeAtBorder = job.appearance.closeAtBorder;
    settings.gradientStencil = job.appearance.gradientStencil;
    render::SilhouetteFrame frame = renderer->render(job.camera, settings);
    render::PolylineOptions options;
    options.minLengthPx = double(settings.minStrokePixels);
    std::optional<render::Mesh> surface;
    if (vectors || job.appearance.suggestiveContours)
        surface = render::surfaceOfFrame(*renderer, *volume, settings);
    if (vectors) {
        render::PolylineSplit split =
            render::splitPolylines(*surface, job.camera, frame.lines, options,
                                   job.appearance.hiddenLines && settings.visibility);
        vectors->lines = std::move(split.visible);
        vectors->hidden = std::move(split.hidden);
    }
    if (job.appearance.suggestiveContours) {
        render::SuggestiveContourRenderer suggestive(*volume, *surface, job.iso, 0,
                                                     settings.gradientStencil);
        render::SuggestiveContourSettings lines;
        lines.visibility = settings.visibility;
        lines.minStrokePixels = settings.minStrokePixels;
        const render::SuggestiveFrame contours = suggestive.render(job.camera, lines);
        render::addLines(frame.lines, contours.lines);
        if (vectors) {
            const std::vector<render::Polyline> more = render::visiblePolylines(
                render::chainSegments(contours.kept), job.camera, contours.lines, options);
            vectors->lines.insert(vectors->lines.end(), more.begin(), more.end());
        }
    }
    return {iso, linesToImage(frame.lines, job.appearance, false, job.appearance.lineWidth)};
}

QImage sideBySide(const QImage& iso, const QImage& silhouette, QColor background) {
    QImage pair(iso.width() + silhouette.width(), std::max(iso.height(), silhouette.height()),
                QImage::Format_RGB32);
    pair.fill(background);
    QPainter painter(&pair);
    painter.drawImage(0, 0, iso);
    painter.drawImage(iso.width(), 0, silhouette);
    return pair;
}

} // namespace lw::gui
