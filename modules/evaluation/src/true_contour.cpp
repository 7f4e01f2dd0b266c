#include "lw/evaluation/true_contour.h"

#include "lw/core/parallel.h"
#include "neighbour_pairs.h"

#include <algorithm>
#include <cmath>
#include <limits>
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
// Between neighbouring rays whose first hits jump in depth, the segment is halved down to
// 2^-6 px looking for a fold the crossing counts hide (findFolds); a jump is a depth difference
// over 4 pixel footprints per pixel of distance (a surface inclined over 76 degrees).
constexpr int kPairSubdivisions = 6;
constexpr double kJumpFootprints = 4.0;
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

// The segment between two neighbouring pixel centres, `from` + s * `step` for s in [0, 1], and
// what tracing a ray through a point of it needs.
struct PixelPair {
    const AnalyticShape& shape;
    const Aabb& box;
    const Camera& camera;
    double stepFloor;
    glm::dvec2 from;
    glm::dvec2 step;

    RaySummary rayAt(double s) const {
        return summarise(shape, box, camera.rayThroughPoint(from + s * step), stepFloor);
    }
};

struct PairSample {
    double s = 0.0;
    RaySummary ray;
};

// Where between two samples of a pair, one of which sees a visible fold the other does not
// (visibleFoldBetween), the fold's contour is: bisection to 2^-kSegmentBisections of their
// distance.
double locateFold(const PixelPair& pair, const PairSample& a, const PairSample& b) {
    const bool foldOnA = visibleFoldBetween(a.ray, b.ray);
    const RaySummary& fewer = foldOnA ? b.ray : a.ray;
    double sMore = foldOnA ? a.s : b.s;
    double sFewer = foldOnA ? b.s : a.s;
    for (int i = 0; i < kSegmentBisections; ++i) {
        const double s = 0.5 * (sMore + sFewer);
        (visibleFoldBetween(pair.rayAt(s), fewer) ? sMore : sFewer) = s;
    }
    return 0.5 * (sMore + sFewer);
}

// Whether the first hits of two rays `pixels` apart lie farther apart in depth than a surface
// inclined up to atan(kJumpFootprints) from facing the camera would put them: a visible fold
// may then lie between them even though their crossing counts do not show it (see findFolds).
bool firstHitsJump(const PixelPair& pair, const RaySummary& a, const RaySummary& b, double pixels) {
    if (a.count == 0 || b.count == 0)
        return false; // a hit beside a miss is a fold already (visibleFoldBetween)
    const double footprint = pair.camera.pixelFootprint(std::min(a.first, b.first));
    return std::abs(a.first - b.first) > kJumpFootprints * footprint * pixels;
}

// Appends the position s of each visible fold between two samples of a pair. A fold shows
// between two rays as an extra in/out pair in front (visibleFoldBetween) only while its far
// side is open: where the fold's body runs on into the surface behind it within the rays'
// distance (a blob in front of another it merges with, a torus seen nearly edge-on, the ends of
// an interior contour), both rays count the same crossings and only the first hit jumps from
// the near sheet to the far one. There the segment is halved, down to 2^-kPairSubdivisions px,
// until the fold shows between two samples close enough to see it.
void findFolds(const PixelPair& pair, const PairSample& a, const PairSample& b, int depth,
               std::vector<double>& folds) {
    if (visibleFoldBetween(a.ray, b.ray) || visibleFoldBetween(b.ray, a.ray)) {
        folds.push_back(locateFold(pair, a, b));
        return;
    }
    if (depth == kPairSubdivisions || !firstHitsJump(pair, a.ray, b.ray, b.s - a.s))
        return;
    const double s = 0.5 * (a.s + b.s);
    const PairSample middle{s, pair.rayAt(s)};
    findFolds(pair, a, middle, depth + 1, folds);
    findFolds(pair, middle, b, depth + 1, folds);
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
        width, height, [&](int x, int y, int bx, int by, std::vector<std::pair<int, int>>& marks) {
            const RaySummary& a = rays[std::size_t(y) * std::size_t(width) + std::size_t(x)];
            const RaySummary& b = rays[std::size_t(by) * std::size_t(width) + std::size_t(bx)];
            const PixelPair pair{shape,           box, camera, stepFloor, {x + 0.5, y + 0.5},
                                 {bx - x, by - y}};
            std::vector<double> found;
            findFolds(pair, {0.0, a}, {1.0, b}, 0, found);
            // The pixel the contour curve passes through where it crosses the segment.
            for (const double s : found)
                marks.push_back(s < 0.5 ? std::pair{x, y} : std::pair{bx, by});
        });
}

} // namespace lw::evaluation
