#include "lw/render/visibility_tolerance.h"

#include <algorithm>
#include <limits>

namespace lw::render {

float depthKeyTolerance(const Camera& camera, const Aabb& box) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i < 8; ++i) {
        const double key = 1.0 - camera.project(box.corner(i)).ndcDepth;
        lo = std::min(lo, key);
        hi = std::max(hi, key);
    }
    return float(kRelativeDepthTolerance * (hi - lo));
}

} // namespace lw::render
