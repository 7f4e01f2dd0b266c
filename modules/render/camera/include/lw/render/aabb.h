#pragma once

#include <algorithm>
#include <glm/glm.hpp>

namespace lw::volume {
class Volume;
}

namespace lw::render {

// An axis-aligned box in patient coordinates (LPS, mm).
struct Aabb {
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};

    glm::dvec3 center() const { return 0.5 * (min + max); }
    glm::dvec3 size() const { return max - min; }
    // Radius of the sphere through the corners.
    double radius() const { return 0.5 * glm::length(max - min); }
    bool isValid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
    // Corner i: bit 0 picks x, bit 1 y, bit 2 z (0 = min, 1 = max).
    glm::dvec3 corner(int i) const {
        return {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
    }
    void extend(glm::dvec3 p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    static Aabb around(glm::dvec3 p) { return {p, p}; }
    static Aabb unite(const Aabb& a, const Aabb& b) {
        return {glm::min(a.min, b.min), glm::max(a.max, b.max)};
    }
};

// The patient-space box of a volume's voxel centres (exact for tilted and unevenly spaced
// stacks: the grid's extreme points are its corners).
Aabb volumeBounds(const volume::Volume& volume);

// The patient-space box of the part of the volume that can hold the iso-surface at `isoReal`
// (real units): the union of the bricks whose min/max admit it. Frames the surface rather than
// the scanner's field of view full of air; the whole volume's box when no brick does.
Aabb surfaceBounds(const volume::Volume& volume, double isoReal);

} // namespace lw::render
