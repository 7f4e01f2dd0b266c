#pragma once

// Ground truth for suggestive contours, from the analytic function alone (no volume, no marching
// cubes, no mesh), as trueContourMask() is for the occluding contour: it judges
// render::SuggestiveContourRenderer with the same thresholds (render::SuggestiveTest).
//
// At a surface point p: the analytic gradient, the Hessian as central differences of the
// analytic gradient (step 1e-4 mm), kappa_r from them (kernels::radialCurvature, in double), and
// D_w kappa_r as the central difference of kappa_r along the unit w (step 1e-2 mm; the view
// vector is recomputed at each point, as for the mesh).
//
// Image: every pixel-centre ray's first hit (the visible surface). For each pair of
// 4-neighbours that both hit the same sheet of the surface (their depths differ by less than
// kMaxDepthJumpPixels pixel footprints: within 80 degrees of grazing the depth changes by at
// most tan 80 = 5.7 pixels a pixel) and whose kappa_r differ in sign, the zero is located to
// 1/1024 pixel by bisection along the segment between the two centres; the pixel holding it is
// marked when the test passes there.

#include "lw/evaluation/analytic_shapes.h"
#include "lw/render/camera.h"
#include "lw/render/pixel_mask.h"
#include "lw/render/suggestive_contours.h"

namespace lw::evaluation {

struct AnalyticRadialCurvature {
    double kr = 0.0;         // 1/mm, convex > 0
    double nDotV = 0.0;      // cos theta
    double derivative = 0.0; // D_w kappa_r along the unit w, 1/mm^2
};

inline constexpr double kMaxDepthJumpPixels = 8.0;

AnalyticRadialCurvature analyticRadialCurvature(const AnalyticShape& shape, glm::dvec3 point,
                                                const render::Camera& camera);

// `featureSize` is L of the test (settings.featureSize when > 0, else this).
render::PixelMask trueSuggestiveContourMask(const AnalyticShape& shape,
                                            const render::Camera& camera,
                                            const render::SuggestiveContourSettings& settings,
                                            double featureSize);

} // namespace lw::evaluation
