#include "review/panel_render_job.h"

#include "lw/core/log.h"
#include "lw/render/shaded_surface_cpu.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/report/export_image.h"
#include "review/qt_image.h"
#include "review/review_panel.h"

#include <QPainter>
#include <cstdio>
#include <string>

namespace lw::gui {
namespace {

constexpr core::LogCategory kLog("lw.gui");

std::string milliseconds(double ms) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f ms", ms);
    return text;
}

} // namespace

QImage shadeIsoOnCpu(const render::Mesh* mesh, const render::Camera& camera,
                     const render::SilhouetteGlOptions& options, unsigned threads,
                     std::vector<float>* depth) {
    render::SurfaceShading shading = render::glPanelShading(camera, options);
    shading.threads = threads;
    return toQImage(render::shadeSurfaceCpu(mesh ? *mesh : render::Mesh(), camera, shading, depth));
}

QImage linesToImage(const render::PixelMask& lines, const ReviewSettings& appearance,
                    bool transparent, double lineWidth) {
    // Antialiased strokes of the line width through the line pixels (PixelMask::strokeCoverage),
    // the line colour blended over the background, or over nothing with the coverage as alpha.
    const std::vector<std::uint8_t> coverage = lines.strokeCoverage(lineWidth);
    QImage image(lines.width(), lines.height(), QImage::Format_ARGB32);
    const QColor line = appearance.lineColour, background = appearance.background;
    const QRgb empty = transparent ? qRgba(0, 0, 0, 0) : background.rgb();
    const auto blend = [](int from, int to, int weight) {
        return (from * (255 - weight) + to * weight + 127) / 255;
    };
    for (int y = 0; y < lines.height(); ++y) {
        auto* row = reinterpret_cast<QRgb*>(image.scanLine(y));
        const std::uint8_t* source = coverage.data() + std::size_t(y) * std::size_t(lines.width());
        for (int x = 0; x < lines.width(); ++x) {
            const int c = source[x];
            if (c == 0)
                row[x] = empty;
            else if (transparent)
                row[x] = qRgba(line.red(), line.green(), line.blue(), c);
            else
                row[x] = qRgb(blend(background.red(), line.red(), c),
                              blend(background.green(), line.green(), c),
                              blend(background.blue(), line.blue(), c));
        }
    }
    return image;
}

QImage linesOverHiddenLines(const render::PixelMask& lines,
                            const std::vector<render::Polyline>& hidden,
                            const ReviewSettings& appearance, double lineWidth) {
    QImage image(lines.width(), lines.height(), QImage::Format_ARGB32_Premultiplied);
    image.fill(appearance.background);
    QPainter painter(&image);
    report::strokeHiddenLines(painter, hidden, lineWidth);
    painter.drawImage(0, 0, linesToImage(lines, appearance, true, lineWidth));
    painter.end();
    return image;
}

render::ReviewFrameRequest panelFrameRequest(const PanelRenderJob& job, bool polylines) {
    const ReviewSettings& appearance = job.appearance;
    render::ReviewFrameRequest request;
    request.iso = job.iso;
    request.method = appearance.method;
    request.backend = appearance.backend;
    request.settings = appearance.silhouetteSettings(job.brickCells, job.iso);
    request.settings.mode = render::ExtractionMode::CachedA; // one frame: nothing to extract again
    request.sampling = appearance.volumeSampling();
    request.camera = job.camera;
    request.wantSilhouette = true;
    request.suggestive = appearance.suggestiveContours;
    request.wantIsoImage = true;
    request.isoOnCpu = job.isoOnCpu;
    request.isoShadedByCuda = appearance.cudaShadesIsoPanel;
    request.isoCamera = job.camera;
    request.isoOptions = panelGlOptions(PanelKind::Iso, appearance, job.camera, job.bounds);
    request.wantPolylines = polylines;
    request.hiddenLines = appearance.hiddenLines;
    request.polylineOptions.minLengthPx = double(appearance.minStrokePixels);
    return request;
}

std::pair<QImage, QImage> panelsOfFrame(render::ReviewFrame&& frame, const PanelRenderJob& job,
                                        PanelVectors* vectors) {
    // Exports are rare and slow enough to say where their time went.
    kLog.info("export panels at " + std::to_string(job.camera.width()) + " x " +
              std::to_string(job.camera.height()) + ": silhouette " +
              milliseconds(frame.silhouette ? frame.silhouette->times.totalMs() : 0.0) +
              ", polylines " + milliseconds(frame.polylinesMs) + " (their surface " +
              milliseconds(frame.polylineSurfaceMs) + "), iso panel " +
              milliseconds(frame.isoRenderMs) + (frame.isoOnDevice ? " (device)" : ""));
    QImage iso = frame.isoImage ? toQImage(*frame.isoImage) : QImage();
    if (vectors) {
        vectors->lines = std::move(frame.polylines.visible);
        vectors->hidden = std::move(frame.polylines.hidden);
        if (!vectors->lines.empty()) {
            // The picture strokes them over a blank panel (report::panelsOf): no raster to draw.
            QImage blank(job.camera.width(), job.camera.height(), QImage::Format_RGB32);
            blank.fill(job.appearance.background);
            return {std::move(iso), std::move(blank)};
        }
    }
    return {std::move(iso),
            linesToImage(frame.silhouette->lines, job.appearance, false, job.appearance.lineWidth)};
}

std::pair<QImage, QImage> renderPanelJob(const PanelRenderJob& job, PanelVectors* vectors) {
    if (job.renderOnWorker)
        return job.renderOnWorker(job, vectors);
    // A frame of renderers of its own: the surface again from the volume, shaded on the CPU or
    // on a headless context of this thread's own (no Qt context may be current here).
    render::ReviewFrameRenderer frames(job.volume);
    return panelsOfFrame(frames.render(panelFrameRequest(job, vectors != nullptr)), job, vectors);
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
