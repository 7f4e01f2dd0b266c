#include "lw/render/iso_surface.h"

#include "lw/core/error.h"
#include "lw/kernels/cpu/border_cap_cpu.h"
#include "lw/kernels/cpu/marching_cubes_cpu.h"
#include "lw/volume/bricks.h"

#include <algorithm>
#include <charconv>

namespace lw::render {

std::string_view gradientStencilName(GradientStencil stencil) {
    return stencil == GradientStencil::Smoothed ? "smoothed" : "central";
}

std::optional<GradientStencil> parseGradientStencil(std::string_view name) {
    for (const GradientStencil stencil : {GradientStencil::Central, GradientStencil::Smoothed})
        if (name == gradientStencilName(stencil))
            return stencil;
    return std::nullopt;
}

int autoBrickCells(glm::ivec3 dims) {
    // 64 cells: small enough that skipping empty bricks pays on CT (air, soft tissue), large
    // enough that the per-brick apron and bookkeeping stay a few percent.
    const int largest = std::max({dims.x, dims.y, dims.z}) - 1;
    return std::max(1, std::min(64, largest));
}

int parseChunks(const std::string& text, glm::ivec3 dims) {
    if (text == "off")
        return 0;
    if (text == "auto")
        return autoBrickCells(dims);
    int value = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (error != std::errc() || end != text.data() + text.size() || value < 1)
        throw core::Error("--chunks " + text,
                          "expected off, auto or a positive number of cells per brick");
    return value;
}

struct IsoSurfaceExtractor::Impl {
    volume::BrickGrid grid;
};

IsoSurfaceExtractor::IsoSurfaceExtractor(const volume::Volume& volume,
                                         const IsoSurfaceOptions& options)
    : m_volume(volume), m_options(options), m_impl(new Impl) {
    const glm::ivec3 cells = glm::max(volume.dims() - 1, glm::ivec3(0));
    const int edge =
        options.brickCells > 0 ? options.brickCells : std::max({cells.x, cells.y, cells.z, 1});
    m_impl->grid = volume::BrickGrid::forExtraction(volume, glm::ivec3(edge));
}

IsoSurfaceExtractor::~IsoSurfaceExtractor() {
    delete m_impl;
}

double storedIsoValue(const volume::Volume& volume, double isoReal) {
    const auto& mapping = volume.valueMapping();
    if (mapping.slope == 0.0)
        throw core::Error("iso-surface", "the volume's value mapping has slope 0");
    if (mapping.slope < 0.0)
        throw core::Error("iso-surface",
                          "a negative rescale slope is not supported (inside would flip)");
    return mapping.toStored(isoReal);
}

void IsoSurfaceExtractor::extract(double isoReal, Mesh& mesh, IsoSurfaceStats* stats,
                                  const core::CancelToken* cancel) const {
    const double storedIso = storedIsoValue(m_volume, isoReal);
    // The cap first (six faces: cheap), so marching cubes reserves room for it behind the mesh
    // and the whole closed surface is counted against the limit before anything is allocated.
    const Mesh cap = m_options.closeAtBorder
                         ? kernels::cpu::borderCap(m_volume, storedIso, m_options.gradientStencil)
                         : Mesh();
    const kernels::cpu::McOutputBudget budget{m_options.limits.maxBytes, cap.vertexCount(),
                                              cap.triangleCount()};
    const kernels::cpu::McResult result = kernels::cpu::marchingCubes(
        m_volume, m_impl->grid, storedIso, mesh, m_options.threads,
        cancel ? cancel : m_options.cancel, m_options.gradientStencil, budget);
    if (result.status == kernels::cpu::McStatus::Cancelled)
        throw core::Cancelled();
    if (result.status == kernels::cpu::McStatus::TooManyVertices)
        throw core::Error("iso-surface at " + std::to_string(isoReal),
                          "the mesh has more than 2^32 vertices; extract a smaller region");
    if (result.status == kernels::cpu::McStatus::OverByteLimit) {
        const std::uint64_t vertices = result.vertices + cap.vertexCount();
        const std::uint64_t triangles = result.triangles + cap.triangleCount();
        m_options.limits.checkAllocation(std::size_t(kernels::meshBytes(vertices, triangles)),
                                         std::to_string(vertices) + " vertices, " +
                                             std::to_string(triangles) + " triangles",
                                         "iso-surface at " + std::to_string(isoReal), "the mesh");
    }
    if (stats) {
        stats->totalBricks = result.totalBricks;
        stats->activeBricks = result.activeBricks;
    }
    kernels::cpu::appendMesh(mesh, cap);
}

Mesh IsoSurfaceExtractor::extract(double isoReal, IsoSurfaceStats* stats) const {
    Mesh mesh;
    extract(isoReal, mesh, stats);
    return mesh;
}

void extractIsoSurface(const volume::Volume& volume, double isoReal,
                       const IsoSurfaceOptions& options, Mesh& mesh, IsoSurfaceStats* stats) {
    IsoSurfaceExtractor(volume, options).extract(isoReal, mesh, stats);
}

Mesh extractIsoSurface(const volume::Volume& volume, double isoReal,
                       const IsoSurfaceOptions& options, IsoSurfaceStats* stats) {
    Mesh mesh;
    extractIsoSurface(volume, isoReal, options, mesh, stats);
    return mesh;
}

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

bool surfaceIsClosed(const volume::Volume& volume, double storedIso, bool closeAtBorder) {
    return closeAtBorder || !surfaceTouchesBorder(volume, storedIso);
}

const Mesh& BorderCapCache::cap(const volume::Volume& volume, double storedIso,
                                GradientStencil stencil) {
    if (!m_faceMaxima || m_volume != &volume)
        m_faceMaxima = kernels::cpu::borderFaceMaxima(volume).value; // once per volume
    if (!m_valid || m_volume != &volume || !(m_iso == storedIso) || m_stencil != stencil) {
        const kernels::cpu::BorderFaceMaxima faces{*m_faceMaxima};
        m_cap = kernels::cpu::borderCap(volume, storedIso, stencil, &faces);
        m_volume = &volume;
        m_iso = storedIso;
        m_stencil = stencil;
        m_valid = true;
    }
    return m_cap;
}

void BorderCapCache::useFaceMaxima(const volume::Volume& volume,
                                   const std::array<double, 6>& maxima) {
    if (m_volume != &volume || !m_faceMaxima || *m_faceMaxima != maxima)
        m_valid = false;
    m_volume = &volume;
    m_faceMaxima = maxima;
}

void BorderCapCache::clear() {
    m_valid = false;
    m_volume = nullptr;
    m_faceMaxima.reset();
    m_cap = Mesh();
}

} // namespace lw::render
