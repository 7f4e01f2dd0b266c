#pragma once

// One interface for the paper's three silhouette methods, whatever the back-end (CPU, CUDA, GL).
//
//   method 1  marching cubes mesh + geometry-shader silhouette, depth-tested against the surface
//   method 2  silhouette-only extraction per active cell + ray-cast visibility (no mesh kept)
//   method 3  own z-buffer rasterizer: triangles -> zbuffer1, segments -> zbuffer2, compare
//
// Chunked ("L") variants are the same code with a brick schedule (settings.brickCells > 0);
// the whole-volume ("S") variant is the one-brick case.

#include "lw/core/image.h"
#include "lw/core/progress.h"
#include "lw/kernels/triangle_mesh.h"
#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/pixel_mask.h"
#include "lw/volume/volume.h"

#include <array>
#include <cstddef>
#include <glm/glm.hpp>
#include <optional>
#include <string_view>

namespace lw::render {

class GlFrameTarget; // gl_frame_target.h

using Mesh = kernels::TriangleMesh; // iso_surface.h

enum class SilhouetteMethod { GeometryShader = 1, RayCastVisibility = 2, ZBuffer = 3 };

// Mode a: the extraction is cached and only the view changes; mode b: re-extract every frame.
enum class ExtractionMode { CachedA, EveryFrameB };

// The stroke pruning the review and the CLI's render and export apply unless told otherwise: on
// the shared CT series 10-14 % of the line pixels lie in groups under 10 pixels, the specks of
// voxel-scale noise (issue 7).
inline constexpr int kDefaultMinStrokePixels = 10;
// Stroke pruning keeps groups of pixels up to this far apart whole until the gaps between stroke
// ends are bridged (PixelMask::pruneStrokes): methods 1 and 2 break a contour where it grazes
// the surface (1-px GL lines against the offset depth; segments whose endpoint rays fail), and
// 8-connected pruning of the unbridged pieces dropped real outline (on the demo CT, method 1 kept
// 0.85 of the outline with it, 0.97 without pruning).
inline constexpr int kStrokeGapPixels = 1;

struct SilhouetteSettings {
    double isoReal = 300.5; // real units (HU for CT); the volume's value mapping converts it
    int brickCells = 0;     // 0: whole volume (S); > 0: bricks of this many cells per axis (L)
    ExtractionMode mode = ExtractionMode::CachedA;
    bool visibility = true; // false: every silhouette segment is drawn (paper, tables 2-4)
    bool testAlongSegment =
        false;            // method 2: test points along each segment, not only its endpoints
    unsigned threads = 0; // CPU back-end: 0 = all cores
    // CUDA back-end: the device memory a frame may use (bytes); 0 = the free memory less a margin.
    // Method 3 streams the volume through it in slabs when the whole volume does not fit, and
    // always in the chunked (L) variant.
    std::size_t gpuMemoryBudget = 0;
    // CUDA back-end, streamed slabs: at most this many cell layers a slab (0: as many as the
    // budget allows). Thin slabs exercise the slab seams; the budget alone decides in normal use.
    int gpuSlabLayers = 0;
    // Strokes (groups of line pixels up to kStrokeGapPixels apart) smaller than this are
    // dropped after the method has drawn: the speckle of noise on real CT; then, once one-pixel
    // gaps between stroke ends are bridged, 8-connected pieces under half of it
    // (PixelMask::pruneStrokes). 0 or 1: every pixel kept (the methods
    // as published; the accuracy and speed measurements use that).
    int minStrokePixels = 0;
    // Close the iso-surface where the volume's border cuts it (iso_surface.h): the cut outline is
    // then a contour like any other. Off only to compare with the methods as published.
    bool closeAtBorder = true;
    // The normals' gradient (iso_surface.h): the marching-cubes normals of methods 1 and 3,
    // method 2's vertices and the suggestive contours' derivatives all take it.
    GradientStencil gradientStencil = GradientStencil::Central;
    // A newer request (the GUI's iso slider) sets it: the frame stops at the next brick, stage or
    // kernel work unit and render() throws core::Cancelled. Not owned; null for none.
    const core::CancelToken* cancel = nullptr;
    // A GL texture of the camera's size to draw the lines into instead of host memory, its GL
    // context current on the calling thread (the GUI's silhouette panel). Method 3 on CUDA with
    // CUDA-GL interop draws there when frameTargetUse() allows; every other method and back-end,
    // and CUDA where interop fails (logged once), fill SilhouetteFrame::lines as without one.
    // Not owned; null for none.
    GlFrameTarget* frameTarget = nullptr;
};

// Whether a frame may go into a frame target, and if not why.
enum class FrameTargetUse {
    Texture,     // yes
    NoTarget,    // none given
    SizeDiffers, // the texture is not the frame's size (a resize the caller has not caught up with)
};
// `targetSize` is the texture's ({0, 0}: none), `frameSize` the camera's. Stroke pruning does not
// stand in the way: the back-end that draws into a target prunes on the device.
FrameTargetUse frameTargetUse(glm::ivec2 targetSize, glm::ivec2 frameSize);
// The same for `settings.frameTarget` and `camera`.
FrameTargetUse frameTargetUse(const SilhouetteSettings& settings, const Camera& camera);

// Wall-clock time of each stage of one frame, in milliseconds (0 when a stage did not run,
// e.g. extraction in mode a after the first frame).
struct StageTimes {
    double extractMs = 0.0;
    double silhouetteMs = 0.0;
    double visibilityMs = 0.0;
    double drawMs = 0.0;
    double totalMs() const { return extractMs + silhouetteMs + visibilityMs + drawMs; }
};

struct SilhouetteFrame {
    PixelMask lines;             // silhouette pixels on the camera's viewport, row 0 at the top
    bool drewToTarget = false;   // the lines went into settings.frameTarget; `lines` is empty
    bool strokesPruned = false;  // the back-end dropped the short strokes itself (the CUDA ones)
    std::size_t triangles = 0;   // triangles extracted (method 2: triangles visited)
    std::size_t segments = 0;    // silhouette segments found (before visibility)
    std::size_t deviceBytes = 0; // CUDA back-end: device memory held at the most (0 on the CPU)
    StageTimes times;
};

// A bound volume's voxels where the CUDA device holds them already, in the volume's own layout
// (the thick-slice field that DrawnVolumeMaker makes there), or null: a CUDA back-end copies
// them device to device instead of uploading the host's 43 MB at every iso-value of the demo.
struct DeviceVoxelCopy {
    const void* voxels = nullptr;
    // The copy's largest stored value per border face (x low, x high, y low, y high, z low,
    // z high: kernels::cpu::BorderFaceMaxima), where the maker found them on the device: the
    // renderers' border caps take them instead of reading the faces of the host's voxels.
    std::optional<std::array<double, 6>> faceMaxima;
};

class SilhouetteRenderer {
public:
    virtual ~SilhouetteRenderer() = default;
    virtual SilhouetteMethod method() const = 0;
    virtual std::string_view backendName() const = 0;
    // Binds a volume; it must outlive the renderer, the next setVolume or releaseVolume. Drops
    // cached results.
    virtual void setVolume(const volume::Volume& volume) = 0;
    // setVolume where `copy` holds the same voxels on the CUDA device; the copy must stay valid
    // and unchanged until the next setVolume (the renderer reads it at its next extraction).
    // Back-ends that upload nothing ignore it.
    virtual void setVolumeWithDeviceCopy(const volume::Volume& volume, DeviceVoxelCopy copy) {
        (void)copy;
        setVolume(volume);
    }
    // Unbinds the volume, for a renderer that outlives it (a new volume comes later): what was
    // kept of it goes, on the host and on the device. The CUDA back-end page-locks a streamed
    // volume's memory with the driver; left registered, a later allocation at the same address
    // would be read through the old pages by every CUDA copy in the process. The renderers that
    // keep nothing but the pointer need not override it.
    virtual void releaseVolume() {}
    // One frame: the method's lines (renderFrame, per method and back-end), then what every
    // method and back-end shares: strokes under settings.minStrokePixels dropped.
    SilhouetteFrame render(const Camera& camera, const SilhouetteSettings& settings);
    // The iso-surface mesh of the last frame, on the host, for the shaded panel (so both panels
    // show the same surface); null for a method that keeps no mesh (method 2). May extract or
    // download it on first use after a frame that did not need it on the host.
    virtual const Mesh* surfaceMesh() const { return nullptr; }
    // Of that surface, where it is on the device: only the triangles that may hold `camera`'s
    // contour (contour_triangles.h), for the vector lines -- a few in a hundred of what
    // surfaceMesh() would download. nullopt where the renderer has no such surface on the device.
    virtual std::optional<Mesh> contourTriangles(const Camera& camera) const {
        (void)camera;
        return std::nullopt;
    }
    // Whether a frame given settings.frameTarget may draw its lines there (method 3 on CUDA
    // with CUDA-GL interop): callers ask the renderer, not its method or back-end name.
    virtual bool drawsToFrameTargets() const { return false; }
    // The shaded iso panel of this camera drawn by the renderer itself (a method that draws with
    // OpenGL shades with its own shaders), or nothing: the caller shades surfaceMesh() or an
    // extracted mesh on the CPU.
    virtual std::optional<core::ImageRgba8> shadedIsoPanel(const Camera& camera,
                                                           const SilhouetteSettings& settings) {
        (void)camera;
        (void)settings;
        return std::nullopt;
    }

protected:
    virtual SilhouetteFrame renderFrame(const Camera& camera,
                                        const SilhouetteSettings& settings) = 0;
};

// The surface the last frame of `renderer` drew with `settings`, on the host: a copy of the
// renderer's own, or for a method that keeps none (method 2, a chunked frame of method 1)
// extracted as its frame's (at
// settings.isoReal, closed at the border when settings.closeAtBorder). What the suggestive
// contours are drawn on, so that they and the silhouette see one surface.
Mesh surfaceOfFrame(const SilhouetteRenderer& renderer, const volume::Volume& volume,
                    const SilhouetteSettings& settings);

} // namespace lw::render
