#pragma once

#include "lw/evaluation/analytic_shapes.h"
#include "lw/render/camera.h"
#include "lw/render/pixel_mask.h"

namespace lw::evaluation {

// Ground truth for the accuracy measure, computed from the analytic function alone (no marching
// cubes, no mesh), so it can judge every silhouette method.
//
// Definition (Burns et al. 2005): the occluding contour is the set of surface points where the
// normal is perpendicular to the view ray (N . V = 0); we want its visible part. On a closed
// surface the first hit of a ray is always front-facing (N . V > 0), so N . V never changes sign
// between first hits; the visible contour shows instead as a change in the number of crossings:
// on one side of it the ray passes through an extra in/out pair (the fold) in front of
// everything the ray on the other side hits. That covers both the silhouette against the
// background (the other side hits nothing) and interior contours (the other side hits a farther
// part of the surface), and ignores hidden folds (their extra pair lies behind the first hit).
//
// Discretisation: every pixel-centre ray is traced through the whole shape (sphere tracing with
// the shape's Lipschitz bound, crossings refined by bisection). For each pair of 4-neighbours
// whose rays differ in this way, the transition is located to 1/1024 pixel by bisection along the
// segment joining the two pixel centres, and the pixel containing the transition point is marked
// - the pixel the true contour curve passes through where it crosses that segment. Two rays a
// pixel apart may also hide a fold: where the fold's body runs on into the surface behind it
// within that pixel (a blob in front of one it merges with, a torus nearly edge-on), both count
// the same crossings and only the first hit jumps from the near sheet to the far one. Where the
// first hits of two neighbours lie farther apart in depth than a surface inclined 76 degrees
// would put them (4 pixel footprints per pixel), the segment between them is halved, down to
// 1/64 pixel, until the fold shows as above. Features thinner than 1e-2 pixel along a ray, and
// folds that hide in equal counts with a depth step under that slope, are not resolved.
render::PixelMask trueContourMask(const AnalyticShape& shape, const render::Camera& camera);

// Pixels whose centre ray hits the shape (the filled silhouette).
render::PixelMask coverageMask(const AnalyticShape& shape, const render::Camera& camera);

// All surface crossings along a ray, in ray parameter order (t >= 0, unit direction); an even
// count for rays that start and end outside. For tests and tools; `stepFloor` is the smallest
// step (mm) taken while marching.
std::vector<double> rayCrossings(const AnalyticShape& shape, const render::Ray& ray,
                                 double stepFloor);

} // namespace lw::evaluation
