#include "lw/evaluation/suggestive_reference.h"

#include "lw/core/parallel.h"
#include "lw/evaluation/true_contour.h"
#include "lw/kernels/radial_curvature.h"
#include "neighbour_pairs.h"

#include <cmath>
#include <utility>
#include <vector>

namespace lw::evaluation {

using render::Camera;
using render::PixelMask;

namespace {

constexpr double kHessianStep = 1e-4;    // mm
constexpr double kDerivativeStep = 1e-2; // mm
constexpr int kBisections = 10;          // 2^-10 pixel

kernels::Sym3T<double> analyticHessian(const AnalyticShape& shape, glm::dvec3 p) {
    glm::dvec3 row[3];
    for (int a = 0; a < 3; ++a) {
        glm::dvec3 step(0.0);
        step[a] = kHessianStep;
        row[a] = (shape.gradient(p + step) - shape.gradient(p - step)) / (2.0 * kHessianStep);
    }
    return kernels::symmetrised<double>(row);
}

kernels::RadialCurvatureT<double> curvatureAt(const AnalyticShape& shape, glm::dvec3 p,
                                              const Camera& camera) {
    const bool ortho = camera.isOrthographic();
    return kernels::radialCurvature<double>(p, shape.gradient(p), analyticHessian(shape, p),
                                            ortho ? -camera.forward() : camera.eye(), ortho);
}

// The first surface point along the ray through continuous pixel `pixel`.
struct Hit {
    bool hit = false;
    double t = 0.0;
    glm::dvec3 point{0.0};
    double kr = 0.0;
};

Hit firstHit(const AnalyticShape& shape, const Camera& camera, glm::dvec2 pixel, double stepFloor) {
    const render::Ray ray = camera.rayThroughPoint(pixel);
    const std::vector<double> crossings = rayCrossings(shape, ray, stepFloor);
    Hit hit;
    if (crossings.empty())
        return hit;
    hit.hit = true;
    hit.t = crossings.front();
    hit.point = ray.at(hit.t);
    hit.kr = curvatureAt(shape, hit.point, camera).kr;
    return hit;
}

// Both rays see the same sheet of the surface: no occluding contour between them.
bool sameSheet(const Hit& a, const Hit& b, const Camera& camera) {
    if (!a.hit || !b.hit)
        return false;
    const double depth = glm::dot(a.point - camera.eye(), camera.forward());
    return std::abs(a.t - b.t) < kMaxDepthJumpPixels * camera.pixelFootprint(depth);
}

} // namespace

AnalyticRadialCurvature analyticRadialCurvature(const AnalyticShape& shape, glm::dvec3 point,
                                                const Camera& camera) {
    const kernels::RadialCurvatureT<double> at = curvatureAt(shape, point, camera);
    AnalyticRadialCurvature out;
    out.kr = at.kr;
    out.nDotV = at.nDotV;
    const glm::dvec3 step = kDerivativeStep * at.w;
    out.derivative = (curvatureAt(shape, point + step, camera).kr -
                      curvatureAt(shape, point - step, camera).kr) /
                     (2.0 * kDerivativeStep);
    return out;
}

PixelMask trueSuggestiveContourMask(const AnalyticShape& shape, const Camera& camera,
                                    const render::SuggestiveContourSettings& settings,
                                    double featureSize) {
    const int width = camera.width(), height = camera.height();
    const render::SuggestiveTest test(settings, settings.featureSize > 0.0 ? settings.featureSize
                                                                           : featureSize);
    // As trueContourMask: a hundredth of a pixel at the target.
    const double stepFloor =
        1e-2 * camera.pixelFootprint(glm::length(camera.target() - camera.eye()));
    std::vector<Hit> hits(std::size_t(width) * std::size_t(height));
    core::parallelFor(std::size_t(height), [&](std::size_t row) {
        for (int x = 0; x < width; ++x)
            hits[row * std::size_t(width) + std::size_t(x)] =
                firstHit(shape, camera, {x + 0.5, row + 0.5}, stepFloor);
    });
    return detail::markNeighbourPairs(
        width, height, [&](int x, int y, int bx, int by, std::vector<std::pair<int, int>>& marks) {
            const Hit& a = hits[std::size_t(y) * std::size_t(width) + std::size_t(x)];
            const Hit& b = hits[std::size_t(by) * std::size_t(width) + std::size_t(bx)];
            if (!sameSheet(a, b, camera) || (a.kr >= 0.0) == (b.kr >= 0.0))
                return;
            double sA = 0.0, sB = 1.0; // kappa_r has a's sign at sA, b's at sB
            Hit last = a;
            for (int i = 0; i < kBisections; ++i) {
                const double s = 0.5 * (sA + sB);
                last = firstHit(shape, camera, {x + 0.5 + s * (bx - x), y + 0.5 + s * (by - y)},
                                stepFloor);
                if (!sameSheet(last, a, camera))
                    return; // an occluding contour crosses the pair after all
                ((last.kr >= 0.0) == (a.kr >= 0.0) ? sA : sB) = s;
            }
            const AnalyticRadialCurvature c = analyticRadialCurvature(shape, last.point, camera);
            if (!test.passes(c.derivative, c.nDotV))
                return;
            marks.push_back(0.5 * (sA + sB) < 0.5 ? std::pair{x, y} : std::pair{bx, by});
        });
}

} // namespace lw::evaluation
