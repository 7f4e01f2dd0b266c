#include "lw/render/visible_polylines.h"

#include "lw/kernels/silhouette_segment.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>

namespace lw::render {
namespace {

// Each vertex's first index with the same position bits. A surface closed at the volume border
// repeats the border-plane vertices of the open surface in its cap (border_cap_cpu.h): welding
// them lets a contour run from the side of a cut bone onto its cut face in one chain.
std::vector<std::uint32_t> weldedIds(const Mesh& mesh) {
    struct Key {
        std::uint32_t bits[3];
        bool operator==(const Key& o) const {
            return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
        }
    };
    struct Hash {
        std::size_t operator()(const Key& k) const {
            return std::size_t(k.bits[0]) * 73856093u ^ std::size_t(k.bits[1]) * 19349663u ^
                   std::size_t(k.bits[2]) * 83492791u;
        }
    };
    std::unordered_map<Key, std::uint32_t, Hash> first;
    first.reserve(mesh.vertexCount());
    std::vector<std::uint32_t> ids(mesh.vertexCount());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v) {
        Key key;
        std::memcpy(key.bits, &mesh.positions[v], sizeof key.bits);
        ids[v] = first.try_emplace(key, std::uint32_t(v)).first->second;
    }
    return ids;
}

// Burns' rule per triangle (kernels/common), with the crossed edges named: the lone vertex's
// two edges, in the order silhouetteSegment() gives the endpoints.
std::vector<EdgeSegment> edgeSegments(const Mesh& mesh, const Camera& camera) {
    const bool ortho = camera.isOrthographic();
    const glm::vec3 eyeOrDirection = ortho ? glm::vec3(-camera.forward()) : glm::vec3(camera.eye());
    std::vector<float> distance(mesh.vertexCount());
    for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
        distance[v] =
            kernels::silhouetteDistance(mesh.positions[v], mesh.normals[v], eyeOrDirection, ortho);
    const std::vector<std::uint32_t> welded = weldedIds(mesh);
    std::vector<EdgeSegment> segments;
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
        const std::uint32_t* v = &mesh.indices[3 * t];
        const std::uint32_t w[3] = {welded[v[0]], welded[v[1]], welded[v[2]]};
        const glm::vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
        const float d[3] = {distance[v[0]], distance[v[1]], distance[v[2]]};
        kernels::SegmentEndpoints ends;
        kernels::IsolineCrossing crossing;
        if (!kernels::silhouetteSegment(p, d, ends, &crossing))
            continue;
        segments.push_back({{ends.a, ends.b},
                            {meshEdgeKey(w[crossing.lone], w[crossing.other1]),
                             meshEdgeKey(w[crossing.lone], w[crossing.other2])}});
    }
    return segments;
}

// Walks from segment `start`, leaving through its end `side`, appending each next endpoint.
void walkChain(const std::vector<EdgeSegment>& segments,
               const std::unordered_multimap<std::uint64_t, std::size_t>& byEdge,
               std::vector<std::uint8_t>& used, std::size_t start, int side,
               std::vector<glm::vec3>& points, bool& closed) {
    std::size_t current = start;
    for (;;) {
        const std::uint64_t edge = segments[current].edge[side];
        const auto [first, last] = byEdge.equal_range(edge);
        std::size_t next = current;
        for (auto it = first; it != last; ++it)
            if (it->second != current)
                next = it->second;
        if (next == current || std::distance(first, last) != 2)
            return; // a border edge or a fold: the chain ends here
        if (next == start) {
            closed = true;
            return;
        }
        if (used[next])
            return;
        used[next] = 1;
        side = segments[next].edge[0] == edge ? 1 : 0; // leave through the other end
        points.push_back(segments[next].point[side]);
        current = next;
    }
}

// Ramer-Douglas-Peucker: drops the points within `tolerance` pixels of the line through their
// neighbours kept (a chain has a point per triangle crossed: several a pixel on a fine mesh).
void simplify(std::vector<glm::vec2>& points, double tolerance) {
    if (points.size() < 3 || tolerance <= 0.0)
        return;
    std::vector<std::uint8_t> keep(points.size(), 0);
    keep.front() = keep.back() = 1;
    std::vector<std::pair<std::size_t, std::size_t>> spans{{0, points.size() - 1}};
    while (!spans.empty()) {
        const auto [first, last] = spans.back();
        spans.pop_back();
        const glm::dvec2 a(points[first]), b(points[last]);
        const glm::dvec2 direction = b - a;
        const double length = glm::length(direction);
        double farthest = 0.0;
        std::size_t at = first;
        for (std::size_t i = first + 1; i < last; ++i) {
            const glm::dvec2 p(points[i]);
            const double distance =
                length > 0.0
                    ? std::abs(direction.x * (p.y - a.y) - direction.y * (p.x - a.x)) / length
                    : glm::length(p - a);
            if (distance > farthest) {
                farthest = distance;
                at = i;
            }
        }
        if (farthest > tolerance) {
            keep[at] = 1;
            spans.push_back({first, at});
            spans.push_back({at, last});
        }
    }
    std::size_t out = 0;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (keep[i])
            points[out++] = points[i];
    points.resize(out);
}

// Appends the runs of the chain's projected points that `shown` shows (wantShown) or that lie in
// the image where it shows nothing (!wantShown: the hidden lines) to `out`.
void cutByMask(const std::vector<glm::dvec2>& pixels, bool closed, const PixelMask& shown,
               bool wantShown, const PolylineOptions& options, std::vector<Polyline>& out) {
    const auto visible = [&](glm::dvec2 p) {
        const int x = int(std::floor(p.x)), y = int(std::floor(p.y));
        return shown.contains(x, y) && shown.get(x, y) == wantShown;
    };
    Polyline run;
    double runLength = 0.0;
    const auto flush = [&] {
        if (run.points.size() >= 2 && runLength >= options.minLengthPx) {
            simplify(run.points, options.simplifyPx);
            out.push_back(run);
        }
        run = Polyline();
        runLength = 0.0;
    };
    // A run keeps the chain's own vertices and the points where visibility changes; the samples
    // between only decide where those are.
    const std::size_t n = pixels.size();
    const std::size_t steps = closed ? n : n - 1;
    bool allVisible = true;
    for (std::size_t i = 0; i < steps; ++i) {
        const glm::dvec2 a = pixels[i], b = pixels[(i + 1) % n];
        const double length = glm::length(b - a);
        const int samples = std::max(1, int(std::ceil(length * options.samplesPerPixel)));
        glm::dvec2 lastVisible = a;
        for (int s = 0; s <= samples; ++s) {
            const glm::dvec2 p = a + (b - a) * (double(s) / samples);
            if (!visible(p)) {
                allVisible = false;
                if (!run.points.empty()) {
                    if (glm::dvec2(run.points.back()) != lastVisible) {
                        runLength += glm::length(lastVisible - glm::dvec2(run.points.back()));
                        run.points.push_back(glm::vec2(lastVisible));
                    }
                    flush();
                }
                continue;
            }
            lastVisible = p;
            if (run.points.empty() || s == samples) {
                if (!run.points.empty())
                    runLength += glm::length(p - glm::dvec2(run.points.back()));
                run.points.push_back(glm::vec2(p));
            }
        }
    }
    if (closed && allVisible && !run.points.empty()) {
        run.points.pop_back(); // the first point again
        run.closed = true;
    }
    flush();
}

} // namespace

std::uint64_t meshEdgeKey(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
}

std::vector<SilhouetteChain> chainSilhouette(const Mesh& mesh, const Camera& camera) {
    return chainSegments(edgeSegments(mesh, camera));
}

std::vector<SilhouetteChain> chainSegments(const std::vector<EdgeSegment>& segments) {
    std::unordered_multimap<std::uint64_t, std::size_t> byEdge;
    byEdge.reserve(segments.size() * 2);
    for (std::size_t s = 0; s < segments.size(); ++s)
        for (const std::uint64_t edge : segments[s].edge)
            byEdge.emplace(edge, s);
    std::vector<std::uint8_t> used(segments.size(), 0);
    std::vector<SilhouetteChain> chains;
    for (std::size_t s = 0; s < segments.size(); ++s) {
        if (used[s])
            continue;
        used[s] = 1;
        // Backwards from end 0 first (reversed afterwards), then forwards from end 1.
        std::vector<glm::vec3> back;
        bool closed = false;
        walkChain(segments, byEdge, used, s, 0, back, closed);
        SilhouetteChain chain;
        chain.points.assign(back.rbegin(), back.rend());
        chain.points.push_back(segments[s].point[0]);
        chain.points.push_back(segments[s].point[1]);
        if (!closed)
            walkChain(segments, byEdge, used, s, 1, chain.points, closed);
        else
            chain.points.erase(chain.points.begin()); // the loop's first point is its last
        chain.closed = closed;
        chains.push_back(std::move(chain));
    }
    return chains;
}

std::vector<Polyline> visiblePolylines(const Mesh& mesh, const Camera& camera,
                                       const PixelMask& lines, const PolylineOptions& options) {
    return visiblePolylines(chainSilhouette(mesh, camera), camera, lines, options);
}

std::vector<Polyline> visiblePolylines(const std::vector<SilhouetteChain>& chains,
                                       const Camera& camera, const PixelMask& lines,
                                       const PolylineOptions& options) {
    return splitPolylines(chains, camera, lines, options, false).visible;
}

PolylineSplit splitPolylines(const std::vector<SilhouetteChain>& chains, const Camera& camera,
                             const PixelMask& lines, const PolylineOptions& options,
                             bool withHidden) {
    const PixelMask shown = lines.dilated(std::max(0, options.tolerancePx));
    PolylineSplit split;
    for (const SilhouetteChain& chain : chains) {
        std::vector<glm::dvec2> pixels;
        pixels.reserve(chain.points.size());
        for (const glm::vec3& p : chain.points)
            pixels.push_back(camera.project(glm::dvec3(p)).pixel);
        if (pixels.size() < 2)
            continue;
        cutByMask(pixels, chain.closed, shown, true, options, split.visible);
        if (withHidden)
            cutByMask(pixels, chain.closed, shown, false, options, split.hidden);
    }
    return split;
}

PolylineSplit splitPolylines(const Mesh& mesh, const Camera& camera, const PixelMask& lines,
                             const PolylineOptions& options, bool withHidden) {
    return splitPolylines(chainSilhouette(mesh, camera), camera, lines, options, withHidden);
}

} // namespace lw::render
