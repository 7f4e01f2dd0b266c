#pragma once

// One frame of the review: both panels' pictures for one iso-value and camera, asked for once.
// The GUI's render worker hands a ReviewFrameRequest to ReviewFrameRenderer and gets back what
// the panels show; which surface is reused, where the iso panel is shaded and whether a host
// mesh is made at all is decided here, next to the engine, so that the engine's tests (no Qt)
// cover it.
//
// Two paths for the shaded iso panel:
//   device  the back-end resolves to CUDA and this build has CUDA-GL interop. CUDA's rasterizer
//           lights the surface on the device and only the image and its depth come to the host:
//           for method 3 (S) the surface its silhouette frame keeps there, for method 1 the one
//           its CUDA extraction wrote into its GL buffers (one marching cubes serves both
//           panels); for method 2 and method 3's L a surface of the panel's own. With
//           isoShadedByCuda off, GL draws the panel from method 1's buffers instead. Either way
//           the mesh never reaches host memory and the triangle count is the device's.
//   host    anywhere else: the mesh is extracted (or copied from the silhouette renderer that
//           drew it) on the host and shaded on the CPU or with GL.
// When the device path cannot start (no EGL device, interop refused) the frame takes the host
// path; the reason is logged once and kept in ReviewFrame::backendNote.
//
// Not thread-safe; one thread drives it (its GL contexts belong to that thread).

#include "lw/core/image.h"
#include "lw/core/progress.h"
#include "lw/render/camera.h"
#include "lw/render/gl_context.h"
#include "lw/render/iso_surface.h"
#include "lw/render/renderer_factory.h"
#include "lw/render/silhouette_gl_renderer.h"
#include "lw/render/silhouette_renderer.h"
#include "lw/render/surface_sampling.h"
#include "lw/render/visible_polylines.h"
#include "lw/volume/volume.h"

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace lw::render {

struct ReviewFrameRequest {
    double iso = 0.0; // real units (HU for CT)
    SilhouetteMethod method = SilhouetteMethod::ZBuffer;
    Backend backend = Backend::Auto;
    // The methods' settings (isoReal and cancel are set from this request).
    SilhouetteSettings settings;
    // The volume the methods draw: as loaded, or resampled (surface_sampling.h); the copy is kept
    // while this stays (per iso-value where it is the shape-based field of thick slices).
    VolumeSampling sampling;
    Camera camera; // the silhouette panel's

    bool wantSilhouette = false; // draw the silhouette (else a GL panel draws method 1 itself)
    bool suggestive = false;     // with the silhouette: its suggestive contours too (host mesh)
    // A host mesh of the iso-value for a panel that draws it with its own GL; `forceExtract`
    // (mode b) extracts again even where the kept one is of this iso-value.
    bool wantMesh = false;
    bool forceExtract = false;
    // The shaded iso panel, drawn here: on the device where it can (by CUDA's rasterizer even
    // for a software-GL display), else on the CPU (`isoOnCpu`: the software-GL display's
    // choice) or with GL.
    bool wantIsoImage = false;
    bool isoOnCpu = false;
    // On the device path CUDA's rasterizer shades the panel; false: GL draws it from the buffers
    // of method 1's CUDA extraction (the way before CUDA shaded it).
    bool isoShadedByCuda = true;
    Camera isoCamera;
    SilhouetteGlOptions isoOptions;

    // Optional: where the silhouette may go instead of host memory (SilhouetteSettings::
    // frameTarget), and the context it belongs to, made current for the silhouette alone.
    GlFrameTarget* silhouetteTarget = nullptr;
    GlContext* silhouetteTargetContext = nullptr;
    // Optional: the context the frame's own GL work goes into (method 1, the iso panel), the
    // same one for the renderer's whole life, outliving it; null: a headless EGL context of the
    // renderer's own. A GUI passes one of its window system's: where a thread has used GLX,
    // glvnd will not make an EGL context current on it.
    GlContext* glContext = nullptr;

    // The silhouette (and its suggestive contours) as polylines too (visible_polylines.h: the
    // exports' strokes and paths), cut by the frame's mask; `hiddenLines` adds the hidden runs.
    // They need the surface on the host: made on demand (downloaded or extracted) and counted.
    bool wantPolylines = false;
    bool hiddenLines = false;
    PolylineOptions polylineOptions;

    const core::CancelToken* cancel = nullptr; // a newer request stops this one (Cancelled)
};

struct ReviewFrame {
    std::optional<SilhouetteFrame> silhouette;
    PolylineSplit polylines;  // with wantPolylines
    double polylinesMs = 0.0; // the host surface they need (made or kept) and the split
    double polylineSurfaceMs = 0.0; // of it: the surface (downloaded, selected or made)
    // A host mesh of the request's iso-value when one was asked for (wantMesh) or made for the
    // host path; null on the device path.
    std::shared_ptr<const Mesh> mesh;
    double meshMs = 0.0; // marching cubes (and any copy) for the surface; 0 when it was kept
    // The iso panel when wanted: RGBA8 top row first, its depth ([0, 1], 1 = nothing) for picking.
    std::optional<core::ImageRgba8> isoImage;
    std::vector<float> isoDepth;
    double isoRenderMs = 0.0;
    // The surface's triangle count wherever it was made (host or device); nullopt when this frame
    // made or drew no whole surface (a method 2 frame alone).
    std::optional<std::size_t> surfaceTriangles;
    bool isoOnDevice = false; // the iso panel came from the device path
    glm::ivec3 refinement{1}; // how the drawn volume split the loaded one's cells
    // The volume the methods drew: the source itself, or its resampled copy (for the slice
    // views, whose contours then follow the surface drawn, not the grey values between slices).
    std::shared_ptr<const volume::Volume> drawnVolume;
    std::string backend; // the silhouette's back-end that actually ran
    std::string backendNote;
    // Where the frame's time went, wall clock (ms): the drawn copy made and bound (a new
    // iso-value of thick slices; 0 when kept), the silhouette with what follows it on the host,
    // and the iso panel (device or host, with its extraction where it made one).
    struct StageMs {
        double volume = 0.0, silhouette = 0.0, isoPanel = 0.0;
    } stageMs;
};

class ReviewFrameRenderer {
public:
    explicit ReviewFrameRenderer(std::shared_ptr<const volume::Volume> source);
    ~ReviewFrameRenderer();
    ReviewFrameRenderer(const ReviewFrameRenderer&) = delete;
    ReviewFrameRenderer& operator=(const ReviewFrameRenderer&) = delete;

    // Throws core::Cancelled, core::Error, std::bad_alloc (after which release() is wise).
    ReviewFrame render(const ReviewFrameRequest& request);
    // Drops renderers, contexts and caches on the calling (driving) thread.
    void release();

    // Test hook: host meshes this renderer made (extracted, copied or downloaded) so far.
    std::size_t hostMeshesMade() const;

private:
    struct State;
    std::unique_ptr<State> m_state;
};

// Whether a request for `backend` shades the iso panel on the device (the back-end resolves to
// CUDA for method 1's extraction, which needs CUDA-GL interop), before trying.
bool reviewIsoOnDevice(Backend backend);

} // namespace lw::render
