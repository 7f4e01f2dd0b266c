#pragma once

// Re-rendering the review's panels at another size (export) from a copy of what they show, so
// it can run on any thread: the iso panel shaded from the mesh on screen, the silhouette by a
// fresh renderer of the chosen method. ReviewWidget::renderJob() makes the copy.

#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/pixel_mask.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/visible_polylines.h"
#include "lw/volume/volume.h"
#include "settings/review_settings.h"

#include <QImage>
#include <memory>
#include <utility>
#include <vector>

namespace lw::gui {

struct PanelRenderJob {
    std::shared_ptr<const volume::Volume> volume;
    // The iso panel's surface; null where the review keeps it on the device (extracted then).
    std::shared_ptr<const render::Mesh> mesh;
    render::Camera camera;     // at the export size
    render::Aabb bounds;       // what the camera frames (the depth tolerance's box)
    ReviewSettings appearance; // line width already scaled to the size
    double iso = 0.0;
    int brickCells = 0;
    bool isoOnCpu = true; // shade with the CPU rasterizer (software GL), else a headless GL context
};

// The silhouette panel's lines as vectors (render/visible_polylines.h, panel pixels), for the
// exports to draw as antialiased strokes or paths: the visible ones (suggestive contours with
// them) and, where the settings ask for them, the hidden ones.
struct PanelVectors {
    std::vector<render::Polyline> lines;
    std::vector<render::Polyline> hidden;
};

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
// The square dilation radius (pixels) that widens a one-pixel line to `lineWidth`.
int lineDilationRadius(double lineWidth);
// A silhouette mask as the panels show it: lines in `lineColour` widened to `lineWidth` pixels by
// a square dilation, on the background or (transparent) on nothing.
QImage linesToImage(const render::PixelMask& lines, const ReviewSettings& appearance,
                    bool transparent, double lineWidth);

} // namespace lw::gui
