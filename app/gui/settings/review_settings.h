#pragma once

// What the settings page chooses and the review applies live: method, chunking, memory budget,
// mode, visibility, lines, background, projection, back-end and the iso presets. Stored with
// QSettings (the tests point QSettings at a temporary directory).

#include "lw/render/camera.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/render/surface_sampling.h"

#include <QColor>
#include <QList>
#include <QString>
#include <cstddef>
#include <glm/glm.hpp>

class QSettings;

namespace lw::gui {

enum class Chunking { Off, Auto, Fixed };

// Where the shaded iso panel and method 1 draw: in the panels' own GL context, or on the render
// worker's headless context with the image shown in the panel. Auto draws on the worker where
// CUDA shades the iso panel (the panels then show images: no GL composition of the window) or
// where the panels' context is a software rasterizer (llvmpipe), whose vertex work would block
// the UI thread; in the panels otherwise (a GPU's GL without CUDA).
enum class PanelGl { Auto, InPanels, OnWorker };

struct IsoPreset {
    QString name;
    double hu = 0.0;
    friend bool operator==(const IsoPreset&, const IsoPreset&) = default;
};

struct ReviewSettings {
    render::SilhouetteMethod method = render::SilhouetteMethod::ZBuffer;
    Chunking chunking = Chunking::Auto;
    int fixedBrickCells = 64;   // Chunking::Fixed
    int memoryBudgetMiB = 2048; // Chunking::Auto goes chunked (L) above this
    // Device memory a CUDA frame may use (SilhouetteSettings::gpuMemoryBudget); 0 = automatic:
    // the free device memory less a margin. Over it, frames stream slabs, then go to the CPU.
    int gpuMemoryBudgetMiB = 0;
    render::ExtractionMode mode = render::ExtractionMode::CachedA;
    bool visibility = true;
    bool testAlongSegment = false; // method 2: along the segment, not only its endpoints
    int minStrokePixels = render::kDefaultMinStrokePixels; // 0: keep every line pixel
    bool closeAtBorder = true; // the surface closed where the volume's border cuts it
    // The normals' gradient: smoothed for noisy scans (render/iso_surface.h GradientStencil).
    render::GradientStencil gradientStencil = render::GradientStencil::Central;
    // Coarse axes split for finer triangles (render/surface_sampling.h): on by default.
    render::Oversampling oversampling = render::Oversampling::Auto;
    // Thick slices smoothed across by a cubic B-spline (render/surface_sampling.h): on by default.
    render::ThickSlices thickSlices = render::ThickSlices::Smooth;
    render::VolumeSampling volumeSampling() const { return {oversampling, thickSlices}; }
    // The methods' settings these choose, for `brickCells` (0: S) at `iso` (real units).
    render::SilhouetteSettings silhouetteSettings(int brickCells, double iso) const;
    bool suggestiveContours = false; // drawn with the silhouette (render/suggestive_contours.h)
    double lineWidth = 1.0;          // pixels
    QColor lineColour = QColor(0, 0, 0);
    // The silhouette panel and the exports also draw the silhouette's hidden parts thin, dashed
    // and grey (render/svg_lines.h).
    bool hiddenLines = false;
    QColor background = QColor(255, 255, 255);
    // The iso contour on the slice panels: yellow shows on every grey of a CT window.
    QColor contourColour = QColor(255, 255, 0);
    bool silhouetteOnIso = false;
    render::Projection projection = render::Projection::Perspective;
    render::Backend backend = render::Backend::Auto;
    PanelGl panelGl = PanelGl::Auto;
    // Where the surface is on the CUDA device, CUDA's rasterizer shades the iso panel from it
    // (render/review_frame.h); off: OpenGL draws it from the GL buffers CUDA wrote.
    // No page control: a switch for comparing the two and for a driver where one misbehaves.
    bool cudaShadesIsoPanel = true;
    QList<IsoPreset> presets = defaultPresets();

    static QList<IsoPreset> defaultPresets();
    static ReviewSettings load(QSettings& settings);
    void save(QSettings& settings) const;

    // Cells per brick for a volume of `dims` and `bytes` under these settings: 0 = whole
    // volume (S). Auto goes chunked when the whole-volume path would not fit the budget: the
    // volume plus a mesh that, on CT, peaks near the volume's own size (BENCHMARKS.md).
    int brickCellsFor(glm::ivec3 dims, std::size_t bytes) const;

    friend bool operator==(const ReviewSettings&, const ReviewSettings&) = default;
};

QString methodName(render::SilhouetteMethod method);

} // namespace lw::gui
