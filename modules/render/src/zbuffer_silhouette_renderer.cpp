#include "lw/render/zbuffer_silhouette_renderer.h"

#include "lw/core/error.h"
#include "lw/kernels/cpu/zbuffer_rasterizer_cpu.h"
#include "view_transform.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>

namespace lw::render {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The brick a triangle came from, found from its centroid: a marching-cubes triangle's vertices
// lie on the edges of one cell, so the centroid lies in that cell. The mapping only decides which
// brick's pass draws the triangle; any partition gives the same buffers (per-pixel maxima do not
// depend on order), so a centroid on a cell face is harmless.
class CellLocator {
public:
    explicit CellLocator(const volume::Volume& volume) : m_geometry(volume.geometry()) {
        const glm::dmat3 columns(m_geometry.spacingI() * m_geometry.axisI(),
                                 m_geometry.spacingJ() * m_geometry.axisJ(),
                                 m_geometry.stackAxis());
        m_inverse = glm::inverse(columns);
        m_cells = glm::max(volume.dims() - 1, glm::ivec3(1));
    }

    glm::ivec3 cellOf(glm::dvec3 patient) const {
        const glm::dvec3 q = m_inverse * (patient - m_geometry.origin());
        const auto& offsets = m_geometry.sliceOffsets();
        double k = 0.0;
        if (offsets.size() >= 2) {
            // Uneven slices: the stack coordinate is piecewise linear in k.
            const auto upper = std::upper_bound(offsets.begin(), offsets.end(), q.z);
            const auto k0 = std::clamp<std::ptrdiff_t>(upper - offsets.begin() - 1, 0,
                                                       std::ptrdiff_t(offsets.size()) - 2);
            const double gap = offsets[std::size_t(k0) + 1] - offsets[std::size_t(k0)];
            k = double(k0) + (gap != 0.0 ? (q.z - offsets[std::size_t(k0)]) / gap : 0.0);
        } else {
            const double step = m_geometry.sliceStep();
            k = step != 0.0 ? q.z / step : 0.0;
        }
        auto cell = [](double v, int count) {
            return std::clamp(int(std::floor(v)), 0, count - 1);
        };
        return {cell(q.x, m_cells.x), cell(q.y, m_cells.y), cell(k, m_cells.z)};
    }

private:
    const volume::VolumeGeometry& m_geometry;
    glm::dmat3 m_inverse{1.0};
    glm::ivec3 m_cells{1};
};

// True when a voxel on the volume's border is inside (>= iso): only then can the surface be cut
// open by the border. Marching cubes gives a watertight mesh otherwise, and on a closed surface
// back faces are always hidden behind front faces, so the depth pass may cull them (half the work).
bool surfaceTouchesBorder(const volume::Volume& volume, double storedIso) {
    const glm::ivec3 d = volume.dims();
    return volume::dispatchVoxelType(volume.voxelType(), [&](auto zero) {
        using T = decltype(zero);
        const T* voxels = volume.dataAs<T>();
        auto inside = [&](int x, int y, int z) {
            return double(voxels[volume.index(x, y, z)]) >= storedIso;
        };
        for (int z = 0; z < d.z; ++z) {
            const bool zFace = z == 0 || z == d.z - 1;
            for (int y = 0; y < d.y; ++y) {
                if (zFace || y == 0 || y == d.y - 1) {
                    for (int x = 0; x < d.x; ++x)
                        if (inside(x, y, z))
                            return true;
                } else if (inside(0, y, z) || inside(d.x - 1, y, z)) {
                    return true;
                }
            }
        }
        return false;
    });
}

} // namespace

struct ZBufferSilhouetteRenderer::State {
    const volume::Volume* volume = nullptr;
    Mesh mesh;
    bool meshValid = false;
    double meshIso = std::numeric_limits<double>::quiet_NaN();
    int meshBrickCells = -1;
    bool meshClosed = false; // the surface does not reach the volume's border

    // L variant: the mesh's triangles regrouped by brick, and where each brick starts.
    std::vector<std::uint32_t> brickIndices;
    std::vector<std::size_t> brickStarts; // triangle offsets, one more than the brick count
    std::vector<std::size_t> brickCounts; // scratch for the counting sort
    std::vector<std::uint32_t> triangleBrick;

    // Triangle clusters of the index buffer in use (never straddling a brick in the L variant).
    std::vector<kernels::cpu::TriangleCluster> clusters;
    kernels::cpu::TileMask needed;

    kernels::cpu::ScreenVertices screen;
    kernels::cpu::DepthBuffer surfaceDepth; // zbuffer1
    kernels::cpu::DepthBuffer lineDepth;    // zbuffer2
    kernels::cpu::SegmentScratch scratch;
    std::vector<kernels::cpu::ScreenSegment> segments;

    void buildClusters(bool chunked) {
        clusters.clear();
        if (!chunked) {
            kernels::cpu::buildClusters(mesh.positions.data(), mesh.indices.data(), 0,
                                        std::uint32_t(mesh.triangleCount()), clusters);
            return;
        }
        for (std::size_t b = 0; b + 1 < brickStarts.size(); ++b)
            kernels::cpu::buildClusters(
                mesh.positions.data(), brickIndices.data(), std::uint32_t(brickStarts[b]),
                std::uint32_t(brickStarts[b + 1] - brickStarts[b]), clusters);
    }

    void partitionByBrick(int brickCells) {
        const glm::ivec3 cells = glm::max(volume->dims() - 1, glm::ivec3(1));
        const glm::ivec3 grid = (cells + brickCells - 1) / brickCells;
        const std::size_t brickCount =
            std::size_t(grid.x) * std::size_t(grid.y) * std::size_t(grid.z);
        const std::size_t triangles = mesh.triangleCount();
        const CellLocator locator(*volume);
        triangleBrick.resize(triangles);
        brickCounts.assign(brickCount, 0);
        for (std::size_t t = 0; t < triangles; ++t) {
            const std::uint32_t* tri = mesh.indices.data() + 3 * t;
            const glm::dvec3 centroid =
                (glm::dvec3(mesh.positions[tri[0]]) + glm::dvec3(mesh.positions[tri[1]]) +
                 glm::dvec3(mesh.positions[tri[2]])) /
                3.0;
            const glm::ivec3 b = locator.cellOf(centroid) / brickCells;
            const std::size_t brick =
                std::size_t(b.x) +
                std::size_t(grid.x) * (std::size_t(b.y) + std::size_t(grid.y) * std::size_t(b.z));
            triangleBrick[t] = std::uint32_t(brick);
            ++brickCounts[brick];
        }
        brickStarts.assign(brickCount + 1, 0);
        for (std::size_t b = 0; b < brickCount; ++b)
            brickStarts[b + 1] = brickStarts[b] + brickCounts[b];
        brickIndices.resize(mesh.indices.size());
        std::fill(brickCounts.begin(), brickCounts.end(), 0);
        for (std::size_t t = 0; t < triangles; ++t) {
            const std::size_t brick = triangleBrick[t];
            const std::size_t slot = brickStarts[brick] + brickCounts[brick]++;
            std::copy_n(mesh.indices.data() + 3 * t, 3, brickIndices.data() + 3 * slot);
        }
    }
};

ZBufferSilhouetteRenderer::ZBufferSilhouetteRenderer() : m_state(std::make_unique<State>()) {}
ZBufferSilhouetteRenderer::~ZBufferSilhouetteRenderer() = default;

void ZBufferSilhouetteRenderer::setVolume(const volume::Volume& volume) {
    m_state->volume = &volume;
    m_state->meshValid = false;
}

const Mesh& ZBufferSilhouetteRenderer::mesh() const {
    return m_state->mesh;
}

SilhouetteFrame ZBufferSilhouetteRenderer::render(const Camera& camera,
                                                  const SilhouetteSettings& settings) {
    State& s = *m_state;
    if (!s.volume)
        throw core::Error("method 3 (z-buffer)", "no volume bound: call setVolume first");
    if (settings.brickCells < 0)
        throw core::Error("method 3 (z-buffer)", "brickCells must be 0 (whole volume) or positive");
    const unsigned threads = settings.threads;
    SilhouetteFrame frame;

    const bool reuse = settings.mode == ExtractionMode::CachedA && s.meshValid &&
                       s.meshIso == settings.isoReal && s.meshBrickCells == settings.brickCells;
    if (!reuse) {
        const auto start = Clock::now();
        s.meshValid = false;
        IsoSurfaceOptions options;
        options.brickCells = settings.brickCells;
        options.threads = threads;
        extractIsoSurface(*s.volume, settings.isoReal, options, s.mesh);
        if (settings.brickCells > 0)
            s.partitionByBrick(settings.brickCells);
        s.buildClusters(settings.brickCells > 0);
        s.meshClosed =
            !surfaceTouchesBorder(*s.volume, s.volume->valueMapping().toStored(settings.isoReal));
        s.meshValid = true;
        s.meshIso = settings.isoReal;
        s.meshBrickCells = settings.brickCells;
        frame.times.extractMs = msSince(start);
    }
    frame.triangles = s.mesh.triangleCount();

    const kernels::cpu::ViewTransform view = toViewTransform(camera);
    const int width = camera.width(), height = camera.height();

    auto start = Clock::now();
    kernels::cpu::projectVertices(s.mesh.positions.data(), s.mesh.normals.data(),
                                  s.mesh.vertexCount(), view, s.screen, threads);
    frame.times.silhouetteMs += msSince(start);

    start = Clock::now();
    if (settings.visibility)
        s.surfaceDepth.reset(width, height, threads);
    s.lineDepth.reset(width, height, threads);
    frame.times.drawMs += msSince(start);

    // The L variant's index buffer holds the triangles grouped brick by brick, and the passes walk
    // it in that order into the same buffers, so bricks go through serially; the work list is
    // shared across brick borders because starting threads per brick costs more than a small
    // brick takes. Both buffers keep per-pixel maxima, so S and L give identical images.
    // The silhouette pass runs first so the depth pass can skip the clusters and triangles that
    // cannot reach a pixel the colour pass compares against: zbuffer1 is exact wherever it is read.
    const bool chunked = settings.brickCells > 0;
    const std::uint32_t* indices = chunked ? s.brickIndices.data() : s.mesh.indices.data();
    s.segments.clear();
    start = Clock::now();
    kernels::cpu::findSilhouetteSegments(s.mesh.positions.data(), s.screen, indices,
                                         frame.triangles, view, s.scratch, s.segments, threads);
    frame.times.silhouetteMs += msSince(start);

    start = Clock::now();
    kernels::cpu::drawSegmentsDepth(s.segments.data(), s.segments.size(), s.lineDepth, threads);
    frame.times.drawMs += msSince(start);

    if (settings.visibility) {
        start = Clock::now();
        s.needed.markAroundLines(s.lineDepth, threads);
        kernels::cpu::drawClustersDepth(s.screen, indices, s.clusters.data(), s.clusters.size(),
                                        view, s.needed, s.surfaceDepth, threads, s.meshClosed);
        frame.times.visibilityMs += msSince(start);
    }
    frame.segments = s.segments.size();

    start = Clock::now();
    float epsilon = 0.0f;
    if (settings.visibility) {
        // Depth-key range of the volume's box for this camera.
        const Aabb box = volumeBounds(*s.volume);
        double lo = std::numeric_limits<double>::infinity(), hi = -lo;
        for (int i = 0; i < 8; ++i) {
            const double key = 1.0 - camera.project(box.corner(i)).ndcDepth;
            lo = std::min(lo, key);
            hi = std::max(hi, key);
        }
        epsilon = float(kRelativeDepthEpsilon * (hi - lo));
    }
    frame.lines = PixelMask(width, height);
    kernels::cpu::resolveSilhouette(s.surfaceDepth, s.lineDepth, epsilon, settings.visibility,
                                    frame.lines.pixels().data(), threads);
    frame.times.drawMs += msSince(start);
    return frame;
}

} // namespace lw::render
