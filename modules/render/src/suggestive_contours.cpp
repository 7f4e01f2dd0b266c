#include "lw/render/suggestive_contours.h"

#include "lw/core/error.h"
#include "lw/core/parallel.h"
#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"
#include "lw/render/zbuffer_silhouette_renderer.h"
#include "view_transform.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

namespace lw::render {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

constexpr std::size_t kChunk = 4096;

// Calls body(first, end) over [0, count) in chunks on the pool.
template <typename Body> void forChunks(std::size_t count, unsigned threads, Body&& body) {
    core::parallelForRanges(count, kChunk, body, threads);
}

// For each vertex, the triangles that use it (compressed rows).
struct VertexTriangles {
    std::vector<std::uint32_t> start; // vertexCount + 1
    std::vector<std::uint32_t> triangles;

    explicit VertexTriangles(const Mesh& mesh) : start(mesh.vertexCount() + 1, 0) {
        for (const std::uint32_t v : mesh.indices)
            ++start[v + 1];
        for (std::size_t v = 0; v < mesh.vertexCount(); ++v)
            start[v + 1] += start[v];
        triangles.resize(mesh.indices.size());
        std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
        for (std::size_t i = 0; i < mesh.indices.size(); ++i)
            triangles[fill[mesh.indices[i]]++] = std::uint32_t(i / 3);
    }
};

// The gradient of the piecewise-linear `value` over triangle t, in the triangle's plane, and
// twice its area (the weight): grad = sum_i value_i N x (opposite edge) / |N|^2.
glm::vec3 triangleGradient(const Mesh& mesh, std::size_t t, const std::vector<float>& value,
                           float& weight) {
    const std::uint32_t* v = &mesh.indices[3 * t];
    const glm::vec3 p0 = mesh.positions[v[0]], p1 = mesh.positions[v[1]], p2 = mesh.positions[v[2]];
    const glm::vec3 n = glm::cross(p1 - p0, p2 - p0);
    const float n2 = glm::dot(n, n);
    weight = std::sqrt(n2);
    if (!(n2 > 0.0f))
        return glm::vec3(0.0f);
    return (value[v[0]] * glm::cross(n, p2 - p1) + value[v[1]] * glm::cross(n, p0 - p2) +
            value[v[2]] * glm::cross(n, p1 - p0)) /
           n2;
}

} // namespace

SuggestiveTest::SuggestiveTest(const SuggestiveContourSettings& settings, double featureSize)
    : m_minCosine(std::cos(settings.maxViewAngleDeg * std::numbers::pi / 180.0)),
      m_threshold(settings.derivativeThreshold / (featureSize * featureSize)) {}

bool SuggestiveTest::passes(double derivative, double nDotV) const {
    if (!(nDotV > m_minCosine))
        return false;
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - nDotV * nDotV));
    return derivative * sinTheta / nDotV > m_threshold;
}

void addLines(PixelMask& into, const PixelMask& lines) {
    if (into.width() != lines.width() || into.height() != lines.height())
        throw core::Error("suggestive contours", "the line masks differ in size");
    for (std::size_t i = 0; i < into.pixels().size(); ++i)
        into.pixels()[i] = into.pixels()[i] || lines.pixels()[i];
}

struct SuggestiveContourRenderer::State {
    const volume::Volume& volume;
    const Mesh& mesh;
    SurfaceDerivatives derivatives;
    VertexTriangles adjacency;
    std::vector<kernels::cpu::TriangleCluster> clusters;
    bool closed = false;
    double halfDiagonal = 1.0;
    double derivativesMs = 0.0;
    // Per-frame scratch.
    kernels::cpu::ScreenVertices screen;
    kernels::cpu::DepthBuffer surfaceDepth, lineDepth;
    kernels::cpu::TileMask needed;

    State(const volume::Volume& v, const Mesh& m, unsigned threads, GradientStencil stencil)
        : volume(v), mesh(m), derivatives(surfaceDerivatives(v, m, threads, stencil)),
          adjacency(m) {}

    // D_w kappa_r at the vertices of triangles that kappa_r crosses zero in and that face the
    // viewer within the test's angle (others: 0).
    std::vector<float> crossingDerivatives(const std::vector<kernels::RadialCurvature>& curvature,
                                           const std::vector<float>& kr, double minCosine,
                                           unsigned threads) const;
};

SuggestiveContourRenderer::SuggestiveContourRenderer(const volume::Volume& volume, const Mesh& mesh,
                                                     double isoReal, unsigned threads,
                                                     GradientStencil stencil) {
    const auto start = Clock::now();
    m_state = std::make_unique<State>(volume, mesh, threads, stencil);
    State& s = *m_state;
    kernels::cpu::buildClusters(mesh.positions.data(), mesh.indices.data(), 0,
                                std::uint32_t(mesh.triangleCount()), s.clusters);
    // A closed surface lets the depth pass cull back faces, as method 3 does.
    s.closed = !surfaceTouchesBorder(volume, storedIsoValue(volume, isoReal));
    if (!mesh.positions.empty()) {
        glm::vec3 lo = mesh.positions.front(), hi = lo;
        for (const glm::vec3& p : mesh.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        s.halfDiagonal = std::max(1e-6, 0.5 * double(glm::length(hi - lo)));
    }
    s.derivativesMs = msSince(start);
}

SuggestiveContourRenderer::~SuggestiveContourRenderer() = default;

const Mesh& SuggestiveContourRenderer::mesh() const {
    return m_state->mesh;
}

double SuggestiveContourRenderer::derivativesMs() const {
    return m_state->derivativesMs;
}

double SuggestiveContourRenderer::featureSize(const SuggestiveContourSettings& settings) const {
    return settings.featureSize > 0.0 ? settings.featureSize : m_state->halfDiagonal;
}

std::vector<kernels::RadialCurvature>
SuggestiveContourRenderer::vertexCurvature(const Camera& camera, unsigned threads) const {
    const State& s = *m_state;
    const bool ortho = camera.isOrthographic();
    const glm::vec3 eyeOrDirection = ortho ? glm::vec3(-camera.forward()) : glm::vec3(camera.eye());
    std::vector<kernels::RadialCurvature> out(s.mesh.vertexCount());
    forChunks(out.size(), threads, [&](std::size_t first, std::size_t end) {
        for (std::size_t v = first; v < end; ++v)
            out[v] = kernels::radialCurvature(s.mesh.positions[v], s.derivatives.gradient[v],
                                              s.derivatives.hessian[v], eyeOrDirection, ortho);
    });
    return out;
}

std::vector<float> SuggestiveContourRenderer::State::crossingDerivatives(
    const std::vector<kernels::RadialCurvature>& curvature, const std::vector<float>& kr,
    double minCosine, unsigned threads) const {
    // Only the vertices of crossed triangles need the derivative (a few percent of them on
    // smooth shapes; back faces never), and only the triangles around those need a gradient.
    const std::size_t triangles = mesh.triangleCount(), vertices = kr.size();
    std::vector<std::uint8_t> crossed(triangles, 0);
    forChunks(triangles, threads, [&](std::size_t first, std::size_t end) {
        for (std::size_t t = first; t < end; ++t) {
            const std::uint32_t* v = &mesh.indices[3 * t];
            const bool s0 = kr[v[0]] >= 0.0f;
            const bool facing = curvature[v[0]].nDotV > minCosine ||
                                curvature[v[1]].nDotV > minCosine ||
                                curvature[v[2]].nDotV > minCosine;
            crossed[t] = facing && (s0 != (kr[v[1]] >= 0.0f) || s0 != (kr[v[2]] >= 0.0f));
        }
    });
    const auto anyAround = [&](std::size_t v, const std::vector<std::uint8_t>& flag) {
        for (std::uint32_t i = adjacency.start[v]; i < adjacency.start[v + 1]; ++i)
            if (flag[adjacency.triangles[i]])
                return true;
        return false;
    };
    std::vector<std::uint8_t> wanted(vertices, 0);
    forChunks(vertices, threads, [&](std::size_t first, std::size_t end) {
        for (std::size_t v = first; v < end; ++v)
            wanted[v] = anyAround(v, crossed);
    });
    // Gradients (times twice the area) of the triangles touching a wanted vertex.
    std::vector<glm::vec3> weighted(triangles);
    std::vector<float> weight(triangles, -1.0f);
    forChunks(triangles, threads, [&](std::size_t first, std::size_t end) {
        for (std::size_t t = first; t < end; ++t) {
            const std::uint32_t* v = &mesh.indices[3 * t];
            if (!(wanted[v[0]] || wanted[v[1]] || wanted[v[2]]))
                continue;
            const glm::vec3 gradient = triangleGradient(mesh, t, kr, weight[t]);
            weighted[t] = gradient * weight[t];
        }
    });
    std::vector<float> derivative(vertices, 0.0f);
    forChunks(vertices, threads, [&](std::size_t first, std::size_t end) {
        for (std::size_t v = first; v < end; ++v) {
            if (!wanted[v])
                continue;
            // Area-weighted mean of the surrounding triangles' gradients: a lone sliver of
            // marching cubes would otherwise turn noise in kappa_r into a huge derivative.
            glm::vec3 sum(0.0f);
            float weights = 0.0f;
            for (std::uint32_t i = adjacency.start[v]; i < adjacency.start[v + 1]; ++i) {
                sum += weighted[adjacency.triangles[i]];
                weights += weight[adjacency.triangles[i]];
            }
            if (weights > 0.0f)
                derivative[v] = glm::dot(sum / weights, curvature[v].w);
        }
    });
    return derivative;
}

std::vector<EdgeSegment>
SuggestiveContourRenderer::segments(const Camera& camera,
                                    const SuggestiveContourSettings& settings) const {
    const State& s = *m_state;
    const std::vector<kernels::RadialCurvature> curvature =
        vertexCurvature(camera, settings.threads);
    std::vector<float> kr(curvature.size()), nDotV(curvature.size());
    for (std::size_t v = 0; v < curvature.size(); ++v) {
        kr[v] = curvature[v].kr;
        nDotV[v] = curvature[v].nDotV;
    }
    const SuggestiveTest test(settings, featureSize(settings));
    const std::vector<float> derivative =
        s.crossingDerivatives(curvature, kr, test.minCosine(), settings.threads);
    const std::size_t triangles = s.mesh.triangleCount();
    std::vector<std::vector<EdgeSegment>> chunks((triangles + kChunk - 1) / kChunk);
    forChunks(triangles, settings.threads, [&](std::size_t first, std::size_t end) {
        std::vector<EdgeSegment>& out = chunks[first / kChunk];
        for (std::size_t t = first; t < end; ++t) {
            const std::uint32_t* v = &s.mesh.indices[3 * t];
            const float value[3] = {kr[v[0]], kr[v[1]], kr[v[2]]};
            kernels::IsolineCrossing c;
            if (!kernels::isolineCrossing(value, c))
                continue;
            const std::uint32_t lone = v[c.lone], o1 = v[c.other1], o2 = v[c.other2];
            // The test at the segment's midpoint, from the attributes at its two ends.
            const auto atMid = [&](const std::vector<float>& a) {
                return 0.5 * (double(a[lone]) + c.ta * (a[o1] - a[lone]) + a[lone] +
                              c.tb * (a[o2] - a[lone]));
            };
            if (!test.passes(atMid(derivative), atMid(nDotV)))
                continue;
            const glm::vec3 p = s.mesh.positions[lone];
            out.push_back(
                {{p + c.ta * (s.mesh.positions[o1] - p), p + c.tb * (s.mesh.positions[o2] - p)},
                 {meshEdgeKey(lone, o1), meshEdgeKey(lone, o2)}});
        }
    });
    std::vector<EdgeSegment> all;
    for (const auto& chunk : chunks)
        all.insert(all.end(), chunk.begin(), chunk.end());
    return all;
}

SuggestiveFrame SuggestiveContourRenderer::render(const Camera& camera,
                                                  const SuggestiveContourSettings& settings) {
    const auto start = Clock::now();
    State& s = *m_state;
    const unsigned threads = settings.threads;
    SuggestiveFrame frame;
    frame.kept = segments(camera, settings);
    const std::vector<EdgeSegment>& kept = frame.kept;
    const kernels::cpu::ViewTransform view = toViewTransform(camera);
    std::vector<kernels::cpu::ScreenSegment> screen;
    screen.reserve(kept.size());
    for (const EdgeSegment& segment : kept) {
        kernels::cpu::ScreenSegment out;
        if (kernels::cpu::projectPoint(view, glm::dvec3(segment.point[0]), out.a, out.keyA) &&
            kernels::cpu::projectPoint(view, glm::dvec3(segment.point[1]), out.b, out.keyB))
            screen.push_back(out);
    }
    s.lineDepth.reset(camera.width(), camera.height(), threads);
    kernels::cpu::drawSegmentsDepth(screen.data(), screen.size(), s.lineDepth, threads);
    if (settings.visibility) {
        // Method 3's depth pass, only where the colour pass will look.
        s.surfaceDepth.reset(camera.width(), camera.height(), threads);
        kernels::cpu::projectVertices(s.mesh.positions.data(), s.mesh.normals.data(),
                                      s.mesh.vertexCount(), view, s.screen, threads);
        s.needed.markAroundLines(s.lineDepth, threads);
        kernels::cpu::drawClustersDepth(s.screen, s.mesh.indices.data(), s.clusters.data(),
                                        s.clusters.size(), view, s.needed, s.surfaceDepth, threads,
                                        s.closed);
    }
    frame.lines = PixelMask(camera.width(), camera.height());
    kernels::cpu::resolveSilhouette(s.surfaceDepth, s.lineDepth,
                                    ZBufferSilhouetteRenderer::depthEpsilon(camera, s.volume),
                                    settings.visibility, frame.lines.pixels().data(), threads);
    frame.lines.pruneStrokes(settings.minStrokePixels, kStrokeGapPixels); // none under 2 px
    frame.ms = msSince(start);
    return frame;
}

} // namespace lw::render
