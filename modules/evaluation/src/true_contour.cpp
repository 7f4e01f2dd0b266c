#include "lw/evaluation/true_contour.h"

#include "lw/core/parallel.h"
#include "neighbour_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace lw::evaluation {

using render::Aabb;
using render::Camera;
using render::PixelMask;
using render::Ray;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Refinement of the contour position between two pixel centres: 2^-10 px.
constexpr int kSegmentBisections = 10;
// Safety net against pathological fields; sphere tracing normally needs a few hundred steps.
constexpr int kMaxMarchSteps = 200000;

// What the contour test needs from one ray: the number of crossings and the first two.
struct RaySummary {
    int count = 0;
    double first = kInfinity;
    double second = kInfinity;
};

// [tEnter, tExit] of the ray inside the box, or false when it misses.
bool clipToBox(const Ray& ray, const Aabb& box, double& tEnter, double& tExit) {
    tEnter = 0.0;
    tExit = kInfinity;
    for (int axis = 0; axis < 3; ++axis) {
        const double o = ray.origin[axis], d = ray.direction[axis];
        if (d == 0.0) {
            if (o < box.min[axis] || o > box.max[axis])
                return false;
            continue;
        }
        double t0 = (box.min[axis] - o) / d, t1 = (box.max[axis] - o) / d;
        if (t0 > t1)
            std::swap(t0, t1);
        tEnter = std::max(tEnter, t0);
        tExit = std::min(tExit, t1);
    }
    return tEnter <= tExit;
}

template <typename OnCrossing>
void marchRay(const AnalyticShape& shape, const Aabb& box, const Ray& ray, double stepFloor,
              OnCrossing&& onCrossing) {
    double t = 0.0, tEnd = 0.0;
    if (!clipToBox(ray, box, t, tEnd))
        return;
    const double lipschitz = shape.lipschitz();
    double f = shape.value(ray.at(t));
    for (int step = 0; step < kMaxMarchSteps && t < tEnd; ++step) {
        // |f| / L is a distance the surface cannot be closer than, on either side of it.
        const double tNext = std::min(t + std::max(std::abs(f) / lipschitz, stepFloor), tEnd);
        const double fNext = shape.value(ray.at(tNext));
        if ((f >= kShapeIso) != (fNext >= kShapeIso)) {
            double lo = t, hi = tNext;
            const bool loInside = f >= kShapeIso;
            while (hi - lo > 1e-2 * stepFloor) {
                const double mid = 0.5 * (lo + hi);
                if ((shape.value(ray.at(mid)) >= kShapeIso) == loInside)
                    lo = mid;
                else
                    hi = mid;
            }
            if (!onCrossing(0.5 * (lo + hi)))
                return;
        }
        t = tNext;
        f = fNext;
    }
}

RaySummary summarise(const AnalyticShape& shape, const Aabb& box, const Ray& ray,
                     double stepFloor) {
    RaySummary summary;
    marchRay(shape, box, ray, stepFloor, [&](double t) {
        if (summary.count == 0)
            summary.first = t;
        else if (summary.count == 1)
            summary.second = t;
        ++summary.count;
        return true;
    });
    return summary;
}

// True when `more` passes through an extra in/out pair in front of everything `fewer` hits:
// a visible fold (occluding contour) lies between the two rays.
bool visibleFoldBetween(const RaySummary& more, const RaySummary& fewer) {
    return more.count > fewer.count && (fewer.count == 0 || fewer.first > more.second);
}

// The box the rays are clipped to: the shape's box, grown a little so entry points lie outside.
Aabb marchBox(const AnalyticShape& shape) {
    Aabb box = shape.bounds();
    const double grow = 1e-3 * glm::length(box.size()) + 1e-9;
    box.min -= grow;
    box.max += grow;
    return box;
}

double stepFloorFor(const Camera& camera) {
    return 1e-2 * camera.pixelFootprint(glm::length(camera.target() - camera.eye()));
}

} // namespace

std::vector<double> rayCrossings(const AnalyticShape& shape, const Ray& ray, double stepFloor) {
    std::vector<double> crossings;
    marchRay(shape, marchBox(shape), ray, stepFloor, [&](double t) {
        crossings.push_back(t);
        return true;
    });
    return crossings;
}

PixelMask coverageMask(const AnalyticShape& shape, const Camera& camera) {
    const Aabb box = marchBox(shape);
    const double stepFloor = stepFloorFor(camera);
    PixelMask mask(camera.width(), camera.height());
    core::parallelFor(std::size_t(camera.height()), [&](std::size_t row) {
        const int y = int(row);
        for (int x = 0; x < camera.width(); ++x) {
            bool hit = false;
            marchRay(shape, box, camera.rayThroughPixel(x, y), stepFloor, [&](double) {
                hit = true;
                return false;
            });
            mask.set(x, y, hit);
        }
    });
    return mask;
}

PixelMask trueContourMask(const AnalyticShape& shape, const Camera& camera) {
    const int width = camera.width(), height = camera.height();
    const Aabb box = marchBox(shape);
    const double stepFloor = stepFloorFor(camera);

    std::vector<RaySummary> rays(static_cast<std::size_t>(width) *
                                 static_cast<std::size_t>(height));
    core::parallelFor(std::size_t(height), [&](std::size_t row) {
        for (int x = 0; x < width; ++x)
            rays[row * std::size_t(width) + std::size_t(x)] =
                summarise(shape, box, camera.rayThroughPixel(x, int(row)), stepFloor);
    });

    return detail::markNeighbourPairs(
        width, height, [&](int x, int y, int bx, int by) -> std::optional<std::pair<int, int>> {
            const int dx = bx - x, dy = by - y;
            const RaySummary& a = rays[std::size_t(y) * std::size_t(width) + std::size_t(x)];
            const RaySummary& b = rays[std::size_t(by) * std::size_t(width) + std::size_t(bx)];
            const bool foldOnA = visibleFoldBetween(a, b);
            if (!foldOnA && !visibleFoldBetween(b, a))
                return std::nullopt;
            // Bisect along the segment between the pixel centres: sMore keeps the fold side.
            const RaySummary& fewer = foldOnA ? b : a;
            double sMore = foldOnA ? 0.0 : 1.0;
            double sFewer = foldOnA ? 1.0 : 0.0;
            for (int i = 0; i < kSegmentBisections; ++i) {
                const double s = 0.5 * (sMore + sFewer);
                const glm::dvec2 p{x + 0.5 + s * dx, y + 0.5 + s * dy};
                const RaySummary mid = summarise(shape, box, camera.rayThroughPoint(p), stepFloor);
                (visibleFoldBetween(mid, fewer) ? sMore : sFewer) = s;
            }
            const double s = 0.5 * (sMore + sFewer);
            return s < 0.5 ? std::pair{x, y} : std::pair{bx, by};
        });
}

} // namespace lw::evaluation
