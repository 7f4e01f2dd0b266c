#pragma once

#include "lw/core/limits.h"
#include "lw/core/progress.h"
#include "lw/kernels/triangle_mesh.h"
#include "lw/kernels/voxel_grid.h"
#include "lw/volume/volume.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace lw::render {

// An indexed triangle mesh with shared vertices, in patient coordinates (mm): the engine's one
// mesh type (kernels/common/triangle_mesh.h), the same the marching-cubes kernels write.
using Mesh = kernels::TriangleMesh;

// The finite differences behind the vertex normals: central (6 voxels, the default), or
// smoothed across each axis (the 3D Sobel operator where the voxels are cubes; in-plane only
// across slices thicker than the pixel) for noisy scans. Diagram: kernels/common voxel_grid.h.
using GradientStencil = kernels::GradientStencil;
// "central" or "smoothed", as the CLI's --gradient and the stored settings spell it.
std::string_view gradientStencilName(GradientStencil stencil);
// The stencil a name spells; nullopt for any other text.
std::optional<GradientStencil> parseGradientStencil(std::string_view name);

struct IsoSurfaceOptions {
    // Cells per brick along each axis; 0 extracts the whole volume as one brick (the paper's
    // "S" variant), anything else is the chunked ("L") schedule. The mesh is the same either way.
    int brickCells = 0;
    unsigned threads = 0; // 0 = all cores
    // Polled by the kernels between work units; when set, extraction throws core::Cancelled.
    const core::CancelToken* cancel = nullptr;
    // Close the surface where the volume's border cuts it, as if the volume were padded with a
    // value far outside (kernels/cpu/border_cap_cpu.h): the cut face becomes part of the surface.
    // Off by default: marching cubes as other libraries do it (the tests of the algorithm, the
    // benchmark against them). What draws for a user takes SilhouetteSettings::closeAtBorder,
    // which is on by default.
    bool closeAtBorder = false;
    GradientStencil gradientStencil = GradientStencil::Central;
    // What the mesh may take on the host (default: half the physical memory). Counted before
    // it is allocated; a larger one throws core::Error naming its size and the limit.
    core::ImportLimits limits;
};

struct IsoSurfaceStats {
    std::size_t totalBricks = 0;
    // Bricks whose min/max admit the iso-value (the rest are skipped); the whole volume's one
    // brick is not scanned and always counts (volume::BrickGrid::forExtraction).
    std::size_t activeBricks = 0;
};

// Extraction from one volume at changing iso-values: the brick grid (min/max per brick, one
// scan of the volume; none for the whole volume's one brick, volume::BrickGrid::forExtraction) is
// built once here, each extract() then skips the bricks that cannot hold the surface. The volume
// must outlive the extractor.
class IsoSurfaceExtractor {
public:
    IsoSurfaceExtractor(const volume::Volume& volume, const IsoSurfaceOptions& options = {});
    ~IsoSurfaceExtractor();
    IsoSurfaceExtractor(const IsoSurfaceExtractor&) = delete;
    IsoSurfaceExtractor& operator=(const IsoSurfaceExtractor&) = delete;

    // Reuses `mesh`'s buffers (repeated extraction without fresh allocations). Throws
    // core::Cancelled when `cancel` is set during the extraction (the mesh is then empty).
    void extract(double isoReal, Mesh& mesh, IsoSurfaceStats* stats = nullptr,
                 const core::CancelToken* cancel = nullptr) const;
    Mesh extract(double isoReal, IsoSurfaceStats* stats = nullptr) const;

private:
    struct Impl;
    const volume::Volume& m_volume;
    IsoSurfaceOptions m_options;
    Impl* m_impl; // the brick grid; kernels types stay out of this header
};

// The iso-value in the volume's stored units, for the kernels (which compare stored voxels).
// Throws core::Error for a value mapping with slope 0, or a negative slope, which would flip
// inside and outside (inside = value >= iso).
double storedIsoValue(const volume::Volume& volume, double isoReal);

// True when a voxel on the volume's border is inside (value >= storedIso): only then can the
// surface be cut open by the border. Otherwise marching cubes gives a closed surface, on which
// back faces always lie behind front faces, so method 3 may cull them.
bool surfaceTouchesBorder(const volume::Volume& volume, double storedIso);

// Whether the surface at storedIso is closed: always when it is closed at the border, else when
// the border does not cut it.
bool surfaceIsClosed(const volume::Volume& volume, double storedIso, bool closeAtBorder);

// The border cap of `volume` at one iso-value, kept until the iso-value or the volume changes:
// renderers add it to what marching cubes gives (whole mesh, or one more piece of a brick or
// slab schedule) without re-extracting it each frame.
class BorderCapCache {
public:
    // The cap at storedIso (empty when the border does not cut the surface), its normals from
    // `stencil` as the surface's own.
    const Mesh& cap(const volume::Volume& volume, double storedIso,
                    GradientStencil stencil = GradientStencil::Central);
    // `volume`'s faces' maxima found elsewhere (kernels::cpu::BorderFaceMaxima's order; the
    // thick-slice copy's, found on the device): cap() of `volume` then does not read its faces.
    void useFaceMaxima(const volume::Volume& volume, const std::array<double, 6>& maxima);
    void clear();

private:
    const volume::Volume* m_volume = nullptr;
    double m_iso = 0.0;
    GradientStencil m_stencil = GradientStencil::Central;
    bool m_valid = false;
    Mesh m_cap;
    // m_volume's largest value per face (kernels::cpu::BorderFaceMaxima): read once per volume.
    std::optional<std::array<double, 6>> m_faceMaxima;
};

// Brick edge length the "auto" chunking picks for a volume.
int autoBrickCells(glm::ivec3 dims);

// Parses --chunks: "off" (0), "auto" (autoBrickCells) or a positive cell count.
int parseChunks(const std::string& text, glm::ivec3 dims);

// Marching cubes with per-vertex gradient normals at `isoReal` (real units, HU for CT; the
// volume's value mapping converts it). Inside = value >= iso. Vertices are ordered by global
// edge id and triangles by cell, so the result does not depend on brickCells or threads.
Mesh extractIsoSurface(const volume::Volume& volume, double isoReal,
                       const IsoSurfaceOptions& options = {}, IsoSurfaceStats* stats = nullptr);
// Same, reusing `mesh`'s buffers (repeated extraction without fresh allocations).
void extractIsoSurface(const volume::Volume& volume, double isoReal,
                       const IsoSurfaceOptions& options, Mesh& mesh,
                       IsoSurfaceStats* stats = nullptr);

} // namespace lw::render
