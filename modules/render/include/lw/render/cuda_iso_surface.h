#pragma once

// Marching cubes on the CUDA back-end for tools that time or fetch the extraction alone (`bench`,
// tests): the volume is uploaded once, each extract() leaves the mesh on the device. The same
// triangles as extractIsoSurface() in the same order. Without a CUDA build or device the
// constructor throws core::Error saying why (cudaAvailability()).

#include "lw/render/iso_surface.h"
#include "lw/volume/volume.h"

#include <cstddef>
#include <memory>

namespace lw::render {

struct CudaExtraction {
    std::size_t triangles = 0;
    std::size_t vertices = 0;
    double deviceMs = 0.0; // the kernels and scans, CUDA events
    // Its stages: active bricks and border test, classification and compaction, vertex and
    // triangle offsets, generation.
    double bricksMs = 0.0, classifyMs = 0.0, countMs = 0.0, generateMs = 0.0;
};

class CudaIsoSurfaceExtractor {
public:
    explicit CudaIsoSurfaceExtractor(const volume::Volume& volume);
    ~CudaIsoSurfaceExtractor();
    CudaIsoSurfaceExtractor(const CudaIsoSurfaceExtractor&) = delete;
    CudaIsoSurfaceExtractor& operator=(const CudaIsoSurfaceExtractor&) = delete;

    double uploadMs() const; // host -> device copy of the voxels (pageable memory), CUDA events
    // closeAtBorder: the border cap (iso_surface.h) follows the device mesh in download() and
    // counts in the result's triangles and vertices (it is made on the host, not timed here).
    // `stencil`: the normals' gradient (iso_surface.h), for the cap as for the device mesh.
    CudaExtraction extract(double isoReal, bool closeAtBorder = false,
                           GradientStencil stencil = GradientStencil::Central);
    void download(Mesh& mesh) const; // the last extraction's mesh

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::render
