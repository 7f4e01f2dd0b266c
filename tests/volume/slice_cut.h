#pragma once

// What the slice tests compare a contour with: the cut of a marching-cubes mesh through the
// slice plane, and distances from points to a set of segments (a grid of buckets, so tens of
// thousands of segments are searched in a few neighbouring buckets).

#include "lw/kernels/triangle_mesh.h"
#include "lw/volume/slice_contour.h"
#include "lw/volume/slice_plane.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <unordered_map>
#include <vector>

namespace lw::test {

// The segments where the plane at `position` cuts the mesh's triangles, in image coordinates.
inline std::vector<volume::ContourSegment>
meshCut(const kernels::TriangleMesh& mesh, const volume::SliceGeometry& plane, double position) {
    std::vector<volume::ContourSegment> cut;
    for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
        glm::dvec3 v[3];
        double d[3];
        for (int c = 0; c < 3; ++c) {
            v[c] = glm::dvec3(mesh.positions[mesh.indices[t + std::size_t(c)]]);
            d[c] = plane.positionOf(v[c]) - position;
        }
        glm::dvec2 crossings[3];
        int count = 0;
        for (int c = 0; c < 3; ++c) {
            const int n = (c + 1) % 3;
            if ((d[c] < 0.0) != (d[n] < 0.0)) {
                const double s = d[c] / (d[c] - d[n]);
                crossings[count++] = plane.pixelOf(v[c] + s * (v[n] - v[c]));
            }
        }
        if (count == 2)
            cut.push_back({crossings[0], crossings[1]});
    }
    return cut;
}

// Plane positions at `fractions` of the mesh's extent along the plane's normal, nudged off the
// grid's planes so that no vertex lies exactly on one.
inline std::vector<double> positionsThroughMesh(const kernels::TriangleMesh& mesh,
                                                const volume::SliceGeometry& plane,
                                                const std::vector<double>& fractions) {
    double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
    for (const glm::vec3& p : mesh.positions) {
        lo = std::min(lo, plane.positionOf(glm::dvec3(p)));
        hi = std::max(hi, plane.positionOf(glm::dvec3(p)));
    }
    std::vector<double> positions;
    for (double f : fractions)
        positions.push_back(lo + f * (hi - lo) + 0.0137);
    return positions;
}

inline double pointSegmentDistance(glm::dvec2 p, const volume::ContourSegment& s) {
    const glm::dvec2 ab = s.b - s.a;
    const double len2 = glm::dot(ab, ab);
    const double t = len2 > 0.0 ? std::clamp(glm::dot(p - s.a, ab) / len2, 0.0, 1.0) : 0.0;
    return glm::length(p - (s.a + t * ab));
}

// Segments in square buckets `bucket` pixels wide; distance() searches the buckets within
// `reach` of the point and answers infinity when no segment is that near.
class SegmentGrid {
public:
    SegmentGrid(std::vector<volume::ContourSegment> segments, double bucket)
        : m_segments(std::move(segments)), m_bucket(bucket) {
        for (std::size_t n = 0; n < m_segments.size(); ++n) {
            const auto& s = m_segments[n];
            const glm::ivec2 lo = cellOf(glm::min(s.a, s.b)), hi = cellOf(glm::max(s.a, s.b));
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x)
                    m_cells[key({x, y})].push_back(n);
        }
    }

    double distance(glm::dvec2 p, double reach) const {
        double best = std::numeric_limits<double>::infinity();
        const glm::ivec2 lo = cellOf(p - reach), hi = cellOf(p + reach);
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) {
                const auto it = m_cells.find(key({x, y}));
                if (it == m_cells.end())
                    continue;
                for (std::size_t n : it->second)
                    best = std::min(best, pointSegmentDistance(p, m_segments[n]));
            }
        return best <= reach ? best : std::numeric_limits<double>::infinity();
    }

private:
    glm::ivec2 cellOf(glm::dvec2 p) const { return glm::ivec2(glm::floor(p / m_bucket)); }
    static long long key(glm::ivec2 c) { return (long long)(c.x) * 1000003LL + c.y; }

    std::vector<volume::ContourSegment> m_segments;
    double m_bucket;
    std::unordered_map<long long, std::vector<std::size_t>> m_cells;
};

// The distances (pixels) from points along `from` (every `stepPx`, ends included) that `keep`
// accepts to the nearest segment of `to`; infinity where none is within `reach`.
inline std::vector<double> distancesAlong(const std::vector<volume::ContourSegment>& from,
                                          const SegmentGrid& to, double stepPx, double reach,
                                          const std::function<bool(glm::dvec2)>& keep) {
    std::vector<double> distances;
    for (const auto& s : from) {
        const int steps = std::max(1, int(std::ceil(glm::length(s.b - s.a) / stepPx)));
        for (int n = 0; n <= steps; ++n) {
            const glm::dvec2 p = s.a + (double(n) / steps) * (s.b - s.a);
            if (keep(p))
                distances.push_back(to.distance(p, reach));
        }
    }
    return distances;
}

// The largest of distancesAlong; `compared` counts the points.
inline double largestDistance(const std::vector<volume::ContourSegment>& from,
                              const SegmentGrid& to, double stepPx, double reach,
                              const std::function<bool(glm::dvec2)>& keep,
                              std::size_t* compared = nullptr) {
    const std::vector<double> distances = distancesAlong(from, to, stepPx, reach, keep);
    if (compared)
        *compared += distances.size();
    return distances.empty() ? 0.0 : *std::max_element(distances.begin(), distances.end());
}

} // namespace lw::test
