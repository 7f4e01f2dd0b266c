#pragma once

// Rendering the two panels of one view headless, shared by `render` and `export`: the options
// both accept (method, back-end, chunks, mode, visibility, threads, view, camera, size, iso) and
// the frame itself (the silhouette by the chosen method, the shaded iso-surface beside it).

#include "arguments.h"
#include "lw/core/image.h"
#include "lw/evaluation/view_sweep.h"
#include "lw/render/camera.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/render/suggestive_contours.h"
#include "lw/render/surface_sampling.h"
#include "lw/render/visible_polylines.h"
#include "lw/volume/volume.h"

#include <filesystem>
#include <glm/glm.hpp>
#include <iosfwd>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace lw::cli {

struct RenderRequest {
    render::SilhouetteMethod method = render::SilhouetteMethod::ZBuffer;
    render::Backend backend = render::Backend::Auto;
    render::SilhouetteSettings settings; // isoReal set, brickCells once the volume is known
    bool wantIso = false;
    bool wantSilhouette = true;
    int repeat = 0;
    int lineRadius = 0; // silhouette lines widened to 2 * lineRadius + 1 pixels (exports)
    // Suggestive contours drawn with the silhouette (render --suggestive); visibility and stroke
    // pruning follow `settings`.
    bool suggestive = false;
    render::SuggestiveContourSettings suggestiveSettings;
};

struct RenderedPanels {
    core::ImageRgba8 iso;
    core::ImageRgba8 silhouette;
    render::PixelMask lines;      // the silhouette frame's mask, before any widening
    render::PixelMask suggestive; // the suggestive contours' mask (empty unless requested)
    std::vector<render::Polyline> suggestivePolylines; // their visible parts, for SVG
};

// The option names parseRenderRequest and parseCameraView read.
const std::set<std::string>& panelRenderOptions();

// --method, --backend, --mode, --visibility, --threads, --iso (required; `command` names the
// command in the usage error). Panels and repeat are left to the caller.
RenderRequest parseRenderRequest(const Arguments& arguments, const std::string& command);
// --suggestive-threshold TAU (render and export) into the request's suggestive settings.
void parseSuggestiveThreshold(const Arguments& arguments, RenderRequest& request);
// --min-stroke PX (default `defaultMinStroke`), --border closed|open (default closed) and
// --gradient into `settings`, as `render`, `export` and `bench` read them; throws UsageError for
// a bad value.
void parseLineOptions(const Arguments& arguments, int defaultMinStroke,
                      render::SilhouetteSettings& settings);
// --gradient central|smoothed (default central): the normals' finite differences.
render::GradientStencil parseGradientOption(const Arguments& arguments);
// --oversample auto|off and --thick-slices smooth|linear (defaults from `fallback`), then
// `volume` replaced by its resampled copy where the rule asks for one
// (render/surface_sampling.h): what the review draws. `render`, `quality` and `export` default
// to auto and smooth, `bench` to the grid as loaded. Returns the plan it followed.
render::SamplingPlan oversampleForRendering(const Arguments& arguments,
                                            render::VolumeSampling fallback,
                                            volume::Volume& volume);
// What a report says of the grid drawn: "as loaded", "oversampled to WxHxD" or "shape-based
// across thick slices, WxHxD".
std::string samplingDescription(const render::SamplingPlan& plan, glm::ivec3 drawnDims);
// --thin-walls MM: the widest wall slid between thick slices (render/surface_sampling.h), 0 to
// 100 mm, `fallback` where not given.
double parseThinWalls(const Arguments& arguments, double fallback);
// --oversample auto|off, --thick-slices smooth|linear and --thin-walls (defaults from
// `fallback`); throws UsageError for another value.
render::VolumeSampling parseVolumeSampling(const Arguments& arguments,
                                           render::VolumeSampling fallback);
// --view, --camera; the bounds are set once the volume is known (frameSurface).
render::CameraSetup parseCameraView(const Arguments& arguments);
// --size, default 512x512.
glm::ivec2 parsePanelSize(const Arguments& arguments);
// --chunks for this volume and the camera bounds around its surface at the request's iso-value.
void fitToVolume(const Arguments& arguments, const volume::Volume& volume, RenderRequest& request,
                 render::CameraSetup& setup);

// Renders the panels the request wants (the renderer's volume is set here) and reports the
// silhouette frame's counts and stage times on `out`.
RenderedPanels renderPanels(render::SilhouetteRenderer& renderer, const volume::Volume& volume,
                            const render::Camera& camera, const RenderRequest& request,
                            std::ostream& out);

// How the vector lines are drawn (render --format svg, export): --line-width PX (unset: the
// command's default), --line-colour #RRGGBB, --hidden-lines (the hidden parts thin, dashed and
// grey under the visible ones).
struct LineStyle {
    std::optional<double> widthPx;
    std::string colour = "#000000";
    bool hidden = false;
};
// The option and flag names parseLineStyle reads.
const std::set<std::string>& lineStyleOptions();
inline constexpr const char* kHiddenLinesFlag = "hidden-lines";
// Throws UsageError for a width outside (0, 64], a colour not #RRGGBB, or hidden lines asked for
// without `visibility` (nothing is hidden then).
LineStyle parseLineStyle(const Arguments& arguments, bool visibility);

// The silhouette of `lines` (a frame of `renderer` for `camera`) as polylines, visible and, with
// `withHidden`, hidden: the mesh the frame drew (or, for method 2, which keeps none, the same
// surface extracted on the CPU).
render::PolylineSplit silhouettePolylines(render::SilhouetteRenderer& renderer,
                                          const volume::Volume& volume,
                                          const render::Camera& camera,
                                          const RenderRequest& request, bool withHidden,
                                          const render::PixelMask& lines);

// The renderer of `method` on `backend`, for the commands that measure every method (`accuracy`,
// `quality`): method 1 without an OpenGL context gives null and a note saying why, so they still
// run on a machine without EGL; any other failure throws.
std::unique_ptr<render::SilhouetteRenderer> createRendererOrSkip(render::SilhouetteMethod method,
                                                                 render::Backend backend,
                                                                 std::vector<std::string>& notes);

// What the commands that measure drawings over the view sweep (`quality`, `thick-slices`) read
// alike: the render options, the camera, --size (default `defaultSize`), --view/--views (default
// the sweep), --json and --images DIR.
struct ViewSweepOptions {
    RenderRequest request; // the settings of `render`, stroke pruning as there
    render::CameraSetup setup;
    glm::ivec2 size{0};
    std::vector<evaluation::View> views;
    bool json = false;
    std::optional<std::filesystem::path> imagesDir;
};
ViewSweepOptions parseViewSweepOptions(const Arguments& arguments, const std::string& command,
                                       const std::string& defaultSize);

// The iso-surface left, its silhouette right, the same height.
core::ImageRgba8 sideBySide(const core::ImageRgba8& left, const core::ImageRgba8& right);

} // namespace lw::cli
