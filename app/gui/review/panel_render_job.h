#pragma once

// Re-rendering the review's panels at another size (export) from a copy of their settings, so it
// can run on any thread: one frame of the engine (render/review_frame.h), either the review's
// own render worker's (the surface kept on the device) or a fresh one's. ReviewWidget::renderJob()
// makes the copy.

#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/pixel_mask.h"
#include "lw/render/review_frame.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/visible_polylines.h"
#include "lw/volume/volume.h"
#include "settings/review_settings.h"

#include <QImage>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

namespace lw::gui {

struct PanelVectors;

struct PanelRenderJob {
    std::shared_ptr<const volume::Volume> volume;
    render::Camera camera;     // at the export size
    render::Aabb bounds;       // what the camera frames (the depth tolerance's box)
    ReviewSettings appearance; // line width already scaled to the size
    double iso = 0.0;
    int brickCells = 0;
    bool isoOnCpu = true; // shade with the CPU rasterizer (software GL), else a headless GL context
    // Where set, renderPanelJob() hands the job to this (the review's render worker, whose engine
    // keeps the surface on the device and whose GL context shares the panels'), from any thread
    // but the worker's; else the job renders with renderers of its own.
    std::function<std::pair<QImage, QImage>(const PanelRenderJob&, PanelVectors*)> renderOnWorker;
};

// The silhouette panel's lines as vectors (render/visible_polylines.h, panel pixels), for the
// exports to draw as antialiased strokes or paths: the visible ones (suggestive contours with
// them) and, where the settings ask for them, the hidden ones.
struct PanelVectors {
    std::vector<render::Polyline> lines;
    std::vector<render::Polyline> hidden;
};

// The engine's frame request for `job` (render/review_frame.h): both panels at the job's
// camera, with the silhouette's polylines when `polylines`.
render::ReviewFrameRequest panelFrameRequest(const PanelRenderJob& job, bool polylines);

// The panels of a frame made for `job` as the exports take them (the silhouette widened to the
// job's line width), its polylines moved into `vectors` where given.
std::pair<QImage, QImage> panelsOfFrame(render::ReviewFrame&& frame, const PanelRenderJob& job,
                                        PanelVectors* vectors);

// Thread-safe: reads only `job`. Throws core::Error when a renderer fails. `vectors` (optional)
// receives the silhouette's lines as vectors.
std::pair<QImage, QImage> renderPanelJob(const PanelRenderJob& job,
                                         PanelVectors* vectors = nullptr);
// The iso panel shaded by the CPU rasterizer in the GL panel's light and colours (`options`),
// with its depth for picking when `depth` is given; a null mesh gives the background.
QImage shadeIsoOnCpu(const render::Mesh* mesh, const render::Camera& camera,
                     const render::SilhouetteGlOptions& options, unsigned threads = 0,
                     std::vector<float>* depth = nullptr);
// Iso left, silhouette right, on the background colour.
QImage sideBySide(const QImage& iso, const QImage& silhouette, QColor background);
// A silhouette mask as the panels show it: antialiased strokes `lineWidth` pixels wide in
// `lineColour` through the line pixels (render::PixelMask::strokeCoverage), on the background or
// (transparent, the coverage as alpha) on nothing.
QImage linesToImage(const render::PixelMask& lines, const ReviewSettings& appearance,
                    bool transparent, double lineWidth);
// The silhouette panel with its hidden lines under the visible ones, as the exports draw them:
// the hidden polylines stroked thin, dashed and grey (report::strokeHiddenLines), the visible
// mask's strokes (linesToImage) over them.
QImage linesOverHiddenLines(const render::PixelMask& lines,
                            const std::vector<render::Polyline>& hidden,
                            const ReviewSettings& appearance, double lineWidth);

} // namespace lw::gui
