#include "lw/render/visible_polylines.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/silhouette_segment.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <memory>

namespace lw::render {
namespace {

// Triangles per parallel range: enough to amortise handing a range out, few enough that two
// threads balance on a surface whose contour crowds in one part of the index order.
constexpr std::size_t kTriangleGrain = std::size_t(1) << 15;
constexpr std::uint32_t kNoVertex = std::numeric_limits<std::uint32_t>::max();

// d (silhouetteDistance) at every vertex: each triangle's crossing test needs all three.
std::vector<float> vertexDistances(const Mesh& mesh, const Camera& camera) {
    const bool ortho = camera.isOrthographic();
    const glm::vec3 eyeOrDirection = ortho ? glm::vec3(-camera.forward()) : glm::vec3(camera.eye());
    std::vector<float> distance(mesh.vertexCount());
    core::parallelForRanges(distance.size(), 4 * kTriangleGrain,
                            [&](std::size_t begin, std::size_t end) {
                                for (std::size_t v = begin; v < end; ++v)
                                    distance[v] = kernels::silhouetteDistance(
                                        mesh.positions[v], mesh.normals[v], eyeOrDirection, ortho);
                            });
    return distance;
}

// Burns' rule (kernels/common) for triangle t: its segment and which edges the ends lie on.
bool crossing(const Mesh& mesh, const std::vector<float>& distance, std::size_t t,
              kernels::SegmentEndpoints& ends, kernels::IsolineCrossing& crossed) {
    const std::uint32_t* v = &mesh.indices[3 * t];
    const glm::vec3 p[3] = {mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]]};
    const float d[3] = {distance[v[0]], distance[v[1]], distance[v[2]]};
    return kernels::silhouetteSegment(p, d, ends, &crossed);
}

// The triangles that hold a segment, in index order: ranges in parallel, joined in their order,
// so the result is the serial loop's whatever the number of threads. Only their indices are kept
// (a few in ten of the mesh): the segments are computed again once their edges can be named.
std::vector<std::uint32_t> crossedTriangles(const Mesh& mesh, const std::vector<float>& distance) {
    const std::size_t count = mesh.triangleCount();
    std::vector<std::vector<std::uint32_t>> parts((count + kTriangleGrain - 1) / kTriangleGrain);
    core::parallelForRanges(count, kTriangleGrain, [&](std::size_t begin, std::size_t end) {
        std::vector<std::uint32_t>& part = parts[begin / kTriangleGrain];
        kernels::SegmentEndpoints ends;
        kernels::IsolineCrossing crossed;
        for (std::size_t t = begin; t < end; ++t)
            if (crossing(mesh, distance, t, ends, crossed))
                part.push_back(std::uint32_t(t));
    });
    std::vector<std::uint32_t> triangles;
    for (const auto& part : parts)
        triangles.insert(triangles.end(), part.begin(), part.end());
    return triangles;
}

// splitmix64's finaliser: every bit of a key reaches the low bits a slot is taken from
// (grid-aligned coordinates and vertex numbers have many zero bits).
std::uint64_t mixBits(std::uint64_t x) {
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

std::size_t tableCapacity(std::size_t most) {
    std::size_t capacity = 16;
    while (capacity < 2 * most)
        capacity *= 2;
    return capacity;
}

// A table's slots, shared by threads through std::atomic_ref: allocated without the serial
// zeroing a vector of atomics would do, and filled in parallel.
template <typename T> class SharedSlots {
public:
    SharedSlots(std::size_t count, T empty) : m_slots(new T[count]), m_count(count) {
        core::parallelForRanges(count, kTriangleGrain, [&](std::size_t begin, std::size_t end) {
            std::fill(m_slots.get() + begin, m_slots.get() + end, empty);
        });
    }
    std::atomic_ref<T> operator[](std::size_t i) const { return std::atomic_ref<T>(m_slots[i]); }
    std::size_t size() const { return m_count; }

private:
    std::unique_ptr<T[]> m_slots;
    std::size_t m_count;
};

// Open addressing on the position bits of vertices, filled by several threads at once: a slot
// keeps the smallest vertex index of its position (an atomic minimum), so what it holds at the
// end does not depend on the order the threads inserted in.
class PositionTable {
public:
    PositionTable(const Mesh& mesh, std::size_t most)
        : m_mesh(mesh), m_slots(tableCapacity(most), kNoVertex), m_mask(m_slots.size() - 1) {}
    void insert(std::uint32_t v) {
        for (std::size_t slot = firstSlot(v);; slot = (slot + 1) & m_mask) {
            std::uint32_t held = m_slots[slot].load(std::memory_order_relaxed);
            if (held == kNoVertex &&
                m_slots[slot].compare_exchange_strong(held, v, std::memory_order_relaxed))
                return;
            if (!samePosition(held, v))
                continue; // another position's slot (a taken slot never changes position)
            while (v < held &&
                   !m_slots[slot].compare_exchange_weak(held, v, std::memory_order_relaxed)) {
            }
            return;
        }
    }
    // After every insert: the smallest vertex index inserted with `v`'s position bits.
    std::uint32_t smallestWithBits(std::uint32_t v) const {
        for (std::size_t slot = firstSlot(v);; slot = (slot + 1) & m_mask) {
            const std::uint32_t held = m_slots[slot].load(std::memory_order_relaxed);
            if (samePosition(held, v))
                return held;
        }
    }

private:
    std::size_t firstSlot(std::uint32_t v) const {
        std::uint32_t bits[3];
        std::memcpy(bits, &m_mesh.positions[v], sizeof bits);
        return std::size_t(mixBits(mixBits(std::uint64_t(bits[0]) << 32 | bits[1]) ^ bits[2])) &
               m_mask;
    }
    bool samePosition(std::uint32_t a, std::uint32_t b) const {
        return std::memcmp(&m_mesh.positions[a], &m_mesh.positions[b], sizeof(glm::vec3)) == 0;
    }

    const Mesh& m_mesh;
    SharedSlots<std::uint32_t> m_slots;
    std::size_t m_mask;
};

// Each vertex of the `triangles` mapped to the smallest vertex index with the same position bits
// (other entries unset). A surface closed at the volume border repeats the border-plane vertices
// of the open surface in its cap (border_cap_cpu.h): welding them lets a contour run from the
// side of a cut bone onto its cut face in one chain; the contour triangles of a device's surface
// (contour_triangles.h) repeat every shared vertex. Only the crossed triangles' vertices are
// welded: the chains compare edges for equality only, which the same welding of fewer vertices
// keeps. Counted, inserted and looked up in parallel; the result is the serial one.
std::vector<std::uint32_t> weldedIds(const Mesh& mesh,
                                     const std::vector<std::uint32_t>& triangles) {
    constexpr std::uint32_t kMarked = 0;
    std::vector<std::uint32_t> welded(mesh.vertexCount(), kNoVertex);
    for (const std::uint32_t t : triangles)
        for (int k = 0; k < 3; ++k)
            welded[mesh.indices[3 * std::size_t(t) + k]] = kMarked;
    const std::size_t vertices = welded.size();
    std::vector<std::size_t> counts((vertices + kTriangleGrain - 1) / kTriangleGrain, 0);
    core::parallelForRanges(vertices, kTriangleGrain, [&](std::size_t begin, std::size_t end) {
        counts[begin / kTriangleGrain] =
            std::size_t(std::count(welded.begin() + begin, welded.begin() + end, kMarked));
    });
    std::size_t marked = 0;
    for (const std::size_t count : counts)
        marked += count;
    PositionTable table(mesh, marked);
    core::parallelForRanges(vertices, kTriangleGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
            if (welded[v] == kMarked)
                table.insert(std::uint32_t(v));
    });
    core::parallelForRanges(vertices, kTriangleGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t v = begin; v < end; ++v)
            if (welded[v] == kMarked)
                welded[v] = table.smallestWithBits(std::uint32_t(v));
    });
    return welded;
}

// The segments of the crossed triangles, in their order, with the edges they cross named by
// welded vertex indices (meshEdgeKey): the lone vertex's two edges, in the order
// silhouetteSegment() gives the endpoints.
std::vector<EdgeSegment> edgeSegments(const Mesh& mesh, const Camera& camera) {
    const std::vector<float> distance = vertexDistances(mesh, camera);
    const std::vector<std::uint32_t> triangles = crossedTriangles(mesh, distance);
    const std::vector<std::uint32_t> welded = weldedIds(mesh, triangles);
    std::vector<EdgeSegment> segments(triangles.size());
    core::parallelForRanges(
        triangles.size(), kTriangleGrain, [&](std::size_t begin, std::size_t end) {
            kernels::SegmentEndpoints ends;
            kernels::IsolineCrossing crossed;
            for (std::size_t s = begin; s < end; ++s) {
                crossing(mesh, distance, triangles[s], ends, crossed);
                const std::uint32_t* v = &mesh.indices[3 * std::size_t(triangles[s])];
                const std::uint32_t lone = welded[v[crossed.lone]];
                segments[s] = {{ends.a, ends.b},
                               {meshEdgeKey(lone, welded[v[crossed.other1]]),
                                meshEdgeKey(lone, welded[v[crossed.other2]])}};
            }
        });
    return segments;
}

// The ends (2 s + side) on each edge, gathered by several threads at once: open addressing on
// the edge key, a slot holding the first two ends that arrive and whether more came. Which two
// arrive first varies; a slot with exactly two ends holds the same pair whatever the order.
class EdgeEnds {
public:
    static constexpr std::uint64_t kNoEdge = std::numeric_limits<std::uint64_t>::max();
    static constexpr std::uint32_t kNoEnd = std::numeric_limits<std::uint32_t>::max();
    static constexpr std::uint32_t kMore = kNoEnd - 1;

    explicit EdgeEnds(std::size_t ends)
        : m_edge(tableCapacity(ends), kNoEdge), m_first(m_edge.size(), kNoEnd),
          m_second(m_edge.size(), kNoEnd), m_mask(m_edge.size() - 1) {}
    void add(std::uint64_t edge, std::uint32_t end) {
        std::size_t slot = std::size_t(mixBits(edge)) & m_mask;
        for (;; slot = (slot + 1) & m_mask) {
            std::uint64_t held = m_edge[slot].load(std::memory_order_relaxed);
            if (held == kNoEdge &&
                m_edge[slot].compare_exchange_strong(held, edge, std::memory_order_relaxed))
                break;
            if (held == edge)
                break;
        }
        std::uint32_t none = kNoEnd;
        if (m_first[slot].compare_exchange_strong(none, end, std::memory_order_relaxed))
            return;
        none = kNoEnd;
        if (!m_second[slot].compare_exchange_strong(none, end, std::memory_order_relaxed))
            m_second[slot].store(kMore, std::memory_order_relaxed); // a third end: no link
    }
    std::size_t slots() const { return m_edge.size(); }
    // The two ends of slot i when exactly two arrived; false otherwise.
    bool pair(std::size_t i, std::uint32_t& a, std::uint32_t& b) const {
        a = m_first[i].load(std::memory_order_relaxed);
        b = m_second[i].load(std::memory_order_relaxed);
        return a != kNoEnd && b != kNoEnd && b != kMore;
    }

private:
    SharedSlots<std::uint64_t> m_edge;
    SharedSlots<std::uint32_t> m_first, m_second;
    std::size_t m_mask;
};

// For each segment end (2 s + side), the other segment through its edge when exactly two ends
// lie on that edge and they belong to different segments; else none (a border edge or a fold
// ends a chain there). Gathered in parallel (EdgeEnds); the links do not depend on the order.
constexpr std::size_t kNoSegment = std::numeric_limits<std::size_t>::max();
std::vector<std::size_t> segmentLinks(const std::vector<EdgeSegment>& segments) {
    const std::size_t endCount = 2 * segments.size();
    if (endCount >= EdgeEnds::kMore)
        throw core::Error("vector lines", "more silhouette segments than 2^31");
    EdgeEnds ends(endCount);
    core::parallelForRanges(endCount, kTriangleGrain, [&](std::size_t begin, std::size_t end) {
        for (std::size_t e = begin; e < end; ++e)
            ends.add(segments[e / 2].edge[e % 2], std::uint32_t(e));
    });
    std::vector<std::size_t> links(endCount, kNoSegment);
    core::parallelForRanges(ends.slots(), kTriangleGrain, [&](std::size_t begin, std::size_t end) {
        std::uint32_t a = 0, b = 0;
        for (std::size_t i = begin; i < end; ++i)
            if (ends.pair(i, a, b) && a / 2 != b / 2) {
                links[a] = b / 2;
                links[b] = a / 2;
            }
    });
    return links;
}

// Walks from segment `start`, leaving through its end `side`, appending each next endpoint.
void walkChain(const std::vector<EdgeSegment>& segments, const std::vector<std::size_t>& links,
               std::vector<std::uint8_t>& used, std::size_t start, int side,
               std::vector<glm::vec3>& points, bool& closed) {
    std::size_t current = start;
    for (;;) {
        const std::uint64_t edge = segments[current].edge[side];
        const std::size_t next = links[2 * current + std::size_t(side)];
        if (next == kNoSegment)
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

// A chain sampled at samplesPerPixel along its projection, and what the mask says of each sample.
// For a closed chain the samples are cyclic (the last is followed by the first).
enum class SampleState : std::uint8_t { Outside, Hidden, Visible };
struct ChainSamples {
    std::vector<glm::dvec2> points;
    std::vector<std::uint8_t> vertex; // one of the chain's own points: kept in the polylines
    std::vector<double> weight;       // the length of chain the sample stands for (pixels)
    std::vector<SampleState> state;
    bool closed = false;
};

ChainSamples sampleChain(const std::vector<glm::dvec2>& pixels, bool closed,
                         double samplesPerPixel) {
    ChainSamples chain;
    chain.closed = closed;
    const std::size_t n = pixels.size();
    const std::size_t steps = closed ? n : n - 1;
    for (std::size_t i = 0; i < steps; ++i) {
        const glm::dvec2 a = pixels[i], b = pixels[(i + 1) % n];
        const double length = glm::length(b - a);
        const int samples = std::max(1, int(std::ceil(length * samplesPerPixel)));
        // Each segment's end is the next one's start: sampled once, as that start.
        for (int s = 0; s < samples; ++s) {
            chain.points.push_back(a + (b - a) * (double(s) / samples));
            chain.vertex.push_back(s == 0 ? 1 : 0);
            chain.weight.push_back(length / samples);
        }
    }
    if (!closed) {
        chain.points.push_back(pixels.back());
        chain.vertex.push_back(1);
        chain.weight.push_back(0.0);
    }
    return chain;
}

// Calls visit(start, count, whole) for each maximal run of equal `values`: count samples from
// `start`, indices modulo the size (on a closed chain a run may wrap past the end). A closed chain
// of one value is one run from 0 with `whole` set.
template <typename Value, typename Visit>
void forEachRun(const std::vector<Value>& values, bool closed, Visit&& visit) {
    const std::size_t n = values.size();
    std::size_t start = 0;
    if (closed) { // start where a run starts, so that none is split at the chain's first point
        while (start < n && values[start] == values[(start + n - 1) % n])
            ++start;
        if (start == n) {
            if (n > 0)
                visit(std::size_t(0), n, true);
            return;
        }
    }
    for (std::size_t i = 0; i < n;) {
        const std::size_t begin = i;
        const Value value = values[(start + i) % n];
        while (i < n && values[(start + i) % n] == value)
            ++i;
        visit((start + begin) % n, i - begin, false);
    }
}

// A visible run shorter than minLengthPx (classify, 3.): the share of it that must lie on its own
// pixels, and its least length. Measured on the demo and phantom:64 with every method: at 0.9
// more of the mask lies within a pixel of the polylines than with the tolerance alone (recall
// >= 0.99), and the ticks that 0.5 let through stay hidden. Runs under 2 px (mostly whole tiny
// chains) add nothing a reader sees within the one-pixel tolerance of the stroke they lie on,
// but doubled the number of paths on the demo.
constexpr double kShortRunOwnShare = 0.9;
constexpr double kShortRunMinPx = 2.0;

// The pixel a sample lies in.
glm::ivec2 pixelOf(glm::dvec2 p) {
    return {int(std::floor(p.x)), int(std::floor(p.y))};
}

// Along the chain (lengths in pixels), each sample's distance to the nearest sample with `own`
// set, not counting across samples without `near` (a candidate run ends there). A closed chain
// is swept twice round, so distances carry past its first point.
std::vector<double> distanceToOwn(const ChainSamples& chain, const std::vector<std::uint8_t>& own,
                                  const std::vector<std::uint8_t>& near) {
    const std::size_t n = chain.points.size();
    constexpr double kFar = std::numeric_limits<double>::infinity();
    std::vector<double> distance(n, kFar);
    const std::size_t laps = chain.closed ? 2 : 1;
    double d = kFar;
    for (std::size_t k = 0; k < laps * n; ++k) { // forwards
        const std::size_t i = k % n;
        d = !near[i] ? kFar : own[i] ? 0.0 : d + chain.weight[(i + n - 1) % n];
        distance[i] = std::min(distance[i], d);
    }
    d = kFar;
    for (std::size_t k = laps * n; k-- > 0;) { // backwards
        const std::size_t i = k % n;
        d = !near[i] ? kFar : own[i] ? 0.0 : d + chain.weight[i];
        distance[i] = std::min(distance[i], d);
    }
    return distance;
}

// Marks each sample visible, hidden or outside the image. The mask dilated by tolerancePx
// (`near`) bounds what may be visible: a chain's sub-pixel position may lie beside the pixel its
// frame drew. That test alone is not enough: where lines are dense, a hidden chain running a
// pixel beside a visible line passes it too and came out as false hatching (on the demo and
// phantom:64, one polyline pixel in five was off the mask). So the decision rests on the
// samples whose own pixel the mask has on: a visible line lies on its raster pixels but for short
// stretches (where the raster steps diagonally past the chain, or its ends), a hidden one beside
// it meets them only where it touches or crosses the line.
//   1. A sample is a candidate when it is near and within tolerancePx of chain length of a sample
//      on its own pixel (no sample off `near` between): runs end where the chain leaves the
//      raster line, not a pixel beside it.
//   2. A run of candidates is visible when at least minOwnPixelShare of its length lies on its
//      own pixels: a hidden chain crossing or touching a line leaves a short run, mostly beside it.
//   3. A run shorter than minLengthPx is visible only when nearly all of it is own
//      (kShortRunOwnShare, kShortRunMinPx): the frame's stroke pruning already took the speckle
//      off the mask, so such a run is a piece of a kept stroke (between two places where this
//      chain leaves it); a short run half beside the line is a hidden chain crossing it (a tick).
// The rest of the chain in the image is hidden, so hidden lines run on beside the visible ones.
// Each chain is decided from the mask and its own samples alone, in order: deterministic.
void classify(ChainSamples& chain, const PixelMask& lines, const PixelMask& near,
              const PolylineOptions& options) {
    const double ownReach = double(std::max(0, options.tolerancePx));
    const std::size_t n = chain.points.size();
    std::vector<std::uint8_t> own(n, 0), nearby(n, 0);
    chain.state.assign(n, SampleState::Outside);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::ivec2 at = pixelOf(chain.points[i]);
        if (!lines.contains(at.x, at.y))
            continue;
        chain.state[i] = SampleState::Hidden;
        nearby[i] = near.get(at.x, at.y) ? 1 : 0;
        own[i] = lines.get(at.x, at.y) ? 1 : 0;
    }
    const std::vector<double> distance = distanceToOwn(chain, own, nearby);
    std::vector<std::uint8_t> candidate(n, 0);
    for (std::size_t i = 0; i < n; ++i)
        candidate[i] = nearby[i] && distance[i] <= ownReach ? 1 : 0;
    forEachRun(candidate, chain.closed, [&](std::size_t start, std::size_t count, bool whole) {
        if (!candidate[start])
            return;
        double length = 0.0, ownLength = 0.0;
        std::size_t ownSamples = 0;
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t i = (start + k) % n;
            length += chain.weight[i];
            ownLength += own[i] ? chain.weight[i] : 0.0;
            ownSamples += own[i];
        }
        // By length, as samples crowd on short segments; by count where the run has none.
        const double share = length > 0.0 ? ownLength / length : double(ownSamples) / double(count);
        if (!whole) // the last sample's length leads out of the run
            length -= chain.weight[(start + count - 1) % n];
        const bool visible = share >= options.minOwnPixelShare &&
                             (length >= options.minLengthPx ||
                              (share >= kShortRunOwnShare && length >= kShortRunMinPx));
        if (visible)
            for (std::size_t k = 0; k < count; ++k)
                chain.state[(start + k) % n] = SampleState::Visible;
    });
}

// Appends the runs of samples in state `wanted` of at least `minLength` pixels to `out`: each
// run's first and last samples (where visibility changes) and the chain's own points between; a
// closed chain all in that state as one closed polyline of its points.
void appendRuns(const ChainSamples& chain, SampleState wanted, double minLength, double simplifyPx,
                std::vector<Polyline>& out) {
    const std::size_t n = chain.points.size();
    forEachRun(chain.state, chain.closed, [&](std::size_t start, std::size_t count, bool whole) {
        if (chain.state[start] != wanted)
            return;
        Polyline run;
        run.closed = whole;
        for (std::size_t k = 0; k < count; ++k) {
            const std::size_t i = (start + k) % n;
            if (chain.vertex[i] || (!whole && (k == 0 || k + 1 == count)))
                run.points.push_back(glm::vec2(chain.points[i]));
        }
        double length = 0.0;
        for (std::size_t i = 1; i < run.points.size(); ++i)
            length += glm::length(glm::dvec2(run.points[i]) - glm::dvec2(run.points[i - 1]));
        if (whole && run.points.size() > 1)
            length += glm::length(glm::dvec2(run.points.front()) - glm::dvec2(run.points.back()));
        if (run.points.size() < 2 || length < minLength)
            return;
        simplify(run.points, simplifyPx);
        out.push_back(std::move(run));
    });
}

// One chain's visible and, with `withHidden`, hidden runs appended to `split`.
void splitChain(const SilhouetteChain& chain, const Camera& camera, const PixelMask& lines,
                const PixelMask& near, const PolylineOptions& options, bool withHidden,
                PolylineSplit& split) {
    std::vector<glm::dvec2> pixels;
    pixels.reserve(chain.points.size());
    for (const glm::vec3& p : chain.points)
        pixels.push_back(camera.project(glm::dvec3(p)).pixel);
    if (pixels.size() < 2)
        return;
    ChainSamples samples = sampleChain(pixels, chain.closed, options.samplesPerPixel);
    classify(samples, lines, near, options);
    // classify() applied minLengthPx to the visible runs already.
    appendRuns(samples, SampleState::Visible, 0.0, options.simplifyPx, split.visible);
    if (withHidden)
        appendRuns(samples, SampleState::Hidden, options.minLengthPx, options.simplifyPx,
                   split.hidden);
}

} // namespace

std::uint64_t meshEdgeKey(std::uint32_t a, std::uint32_t b) {
    return a < b ? (std::uint64_t(a) << 32 | b) : (std::uint64_t(b) << 32 | a);
}

std::vector<SilhouetteChain> chainSilhouette(const Mesh& mesh, const Camera& camera) {
    return chainSegments(edgeSegments(mesh, camera));
}

std::vector<SilhouetteChain> chainSegments(const std::vector<EdgeSegment>& segments) {
    const std::vector<std::size_t> links = segmentLinks(segments);
    std::vector<std::uint8_t> used(segments.size(), 0);
    std::vector<SilhouetteChain> chains;
    for (std::size_t s = 0; s < segments.size(); ++s) {
        if (used[s])
            continue;
        used[s] = 1;
        // Backwards from end 0 first (reversed afterwards), then forwards from end 1.
        std::vector<glm::vec3> back;
        bool closed = false;
        walkChain(segments, links, used, s, 0, back, closed);
        SilhouetteChain chain;
        chain.points.assign(back.rbegin(), back.rend());
        chain.points.push_back(segments[s].point[0]);
        chain.points.push_back(segments[s].point[1]);
        if (!closed)
            walkChain(segments, links, used, s, 1, chain.points, closed);
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
    const PixelMask near = lines.dilated(std::max(0, options.tolerancePx));
    // Each chain is decided by itself: ranges of chains in parallel, joined in chain order.
    constexpr std::size_t kChainGrain = 64;
    std::vector<PolylineSplit> parts((chains.size() + kChainGrain - 1) / kChainGrain);
    core::parallelForRanges(chains.size(), kChainGrain, [&](std::size_t begin, std::size_t end) {
        PolylineSplit& part = parts[begin / kChainGrain];
        for (std::size_t c = begin; c < end; ++c)
            splitChain(chains[c], camera, lines, near, options, withHidden, part);
    });
    PolylineSplit split;
    for (PolylineSplit& part : parts) {
        std::move(part.visible.begin(), part.visible.end(), std::back_inserter(split.visible));
        std::move(part.hidden.begin(), part.hidden.end(), std::back_inserter(split.hidden));
    }
    return split;
}

PolylineSplit splitPolylines(const Mesh& mesh, const Camera& camera, const PixelMask& lines,
                             const PolylineOptions& options, bool withHidden) {
    return splitPolylines(chainSilhouette(mesh, camera), camera, lines, options, withHidden);
}

} // namespace lw::render
