#pragma once

// Suggestive contours (DeCarlo et al. 2003), extracted from a volume the way Burns et al. 2005
// do: per-vertex radial curvature kappa_r from the voxel field's gradient and Hessian
// (surface_derivatives.h, radial_curvature.h), its zero crossings found on the marching-cubes
// triangles like Burns' silhouette segments, and kept where
//
//   D_w kappa_r * tan(theta) > derivativeThreshold / L^2     (theta: angle between n and v)
//   cos(theta) > cos(maxViewAngleDeg)
//
// - D_w kappa_r > 0 is the definition (n.v has a local minimum along w there); the derivative
//   is the mesh gradient of kappa_r (per triangle, area-weighted at the vertices) along w.
// - The factor tan(theta) = |w| / (n.v) is the form of the test in DeCarlo et al.'s rtsc
//   (D_w kappa_r / n.v with |v| = 1): head-on (theta -> 0) w and with it kappa_r have no
//   stable direction, and the test removes those points first. The threshold is relative to
//   the size L of the object (kappa_r' is 1/mm^2), so it does not depend on units or scale.
// - Within maxViewAngleDeg of grazing (theta -> 90 deg) the zero crossings crowd against the
//   occluding contour: on a sphere of radius R pixels the band theta > 80 deg is R (1 - sin 80)
//   = 1.5 % of R wide in the image, so a line there doubles the silhouette instead of adding
//   a stroke, and it is where the per-vertex normal's error weighs most in n.v.
//
// Visibility is method 3's rule (zbuffer_rules.h resolvePixel, the same depth tolerance): the
// segments into one z-buffer, the surface's triangles into another, a segment pixel drawn when
// it is not behind the surface of its 3x3 neighbourhood. CPU only (no CUDA version yet).

#include "lw/render/camera.h"
#include "lw/render/iso_surface.h"
#include "lw/render/pixel_mask.h"
#include "lw/render/surface_derivatives.h"
#include "lw/render/visible_polylines.h"
#include "lw/volume/volume.h"

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace lw::render {

struct SuggestiveContourSettings {
    // tau in D_w kappa_r tan(theta) > tau / L^2 (dimensionless; see above).
    double derivativeThreshold = 1.0;
    double maxViewAngleDeg = 80.0;
    // L in mm; 0: half the diagonal of the surface's bounding box.
    double featureSize = 0.0;
    bool visibility = true;
    // Strokes (8-connected groups of pixels) smaller than this are dropped (0: none).
    int minStrokePixels = 0;
    unsigned threads = 0; // 0 = all cores
};

// The test above, shared with the analytic reference (lw_evaluation) so both judge the same
// definition; `featureSize` is L (mm).
class SuggestiveTest {
public:
    SuggestiveTest(const SuggestiveContourSettings& settings, double featureSize);
    // `derivative`: D_w kappa_r along the unit w (1/mm^2); `nDotV`: cos(theta).
    bool passes(double derivative, double nDotV) const;
    // cos of the largest view angle passed: a triangle whose vertices all have n.v at or below
    // it cannot hold a passing point (n.v is interpolated), so it needs no derivative.
    double minCosine() const { return m_minCosine; }

private:
    double m_minCosine;
    double m_threshold; // tau / L^2
};

// Sets every pixel of `into` that `lines` has on (suggestive contours drawn with the silhouette;
// the sizes must agree, else core::Error).
void addLines(PixelMask& into, const PixelMask& lines);

struct SuggestiveFrame {
    PixelMask lines;
    // The kept segments (before visibility), as segments() gives them: chained into visible
    // polylines for vector output without computing them again.
    std::vector<EdgeSegment> kept;
    double ms = 0.0; // this frame (the per-vertex derivatives are not in it)
};

// One mesh of one volume: the view-independent per-vertex derivatives and the mesh's adjacency
// are computed in the constructor; every view then costs a frame. The volume and mesh must
// outlive it.
class SuggestiveContourRenderer {
public:
    // `stencil`: the gradient the mesh's normals were made with (surfaceDerivatives).
    SuggestiveContourRenderer(const volume::Volume& volume, const Mesh& mesh, double isoReal,
                              unsigned threads = 0,
                              GradientStencil stencil = GradientStencil::Central);
    ~SuggestiveContourRenderer();
    SuggestiveContourRenderer(const SuggestiveContourRenderer&) = delete;
    SuggestiveContourRenderer& operator=(const SuggestiveContourRenderer&) = delete;

    const Mesh& mesh() const;
    double derivativesMs() const; // the constructor's time
    double featureSize(const SuggestiveContourSettings& settings) const;

    // kappa_r per vertex for the camera.
    std::vector<kernels::RadialCurvature> vertexCurvature(const Camera& camera,
                                                          unsigned threads = 0) const;
    // The kept segments (patient mm, with the mesh edges their ends lie on, so chainSegments()
    // joins them), before visibility.
    std::vector<EdgeSegment> segments(const Camera& camera,
                                      const SuggestiveContourSettings& settings) const;
    // The visible segments drawn into a mask of the camera's size.
    SuggestiveFrame render(const Camera& camera, const SuggestiveContourSettings& settings);

private:
    struct State;
    std::unique_ptr<State> m_state;
};

} // namespace lw::render
