#pragma once

// The few triangles of a device mesh that a view's contour may cross, brought to the host: the
// vector lines of an export (render/visible_polylines.h) chain Burns' segments of the whole
// surface, but only the triangles whose vertices' d = N . (eye - P) take both signs hold one --
// a few in a hundred. Selecting them on the device and downloading those alone replaces the
// download of the whole surface (and its pages on the host) by one of about 3 %.
//
//   flag     per triangle: mayHoldContour (kernels/common/silhouette_segment.h), a superset of
//            the triangles Burns' rule crosses (its margin covers rounding), so the host's own
//            test picks the same triangles from them as from the whole mesh
//   select   the flagged triangles' numbers in index order (CUB), so chains start in the order
//            the whole mesh gives
//   gather   each selected triangle's three vertices, positions and normals, unshared: vertex
//            3 i + k is corner k of the i-th selected triangle (the host welds equal positions)
// Public header: no CUDA types.

#include "lw/kernels/cuda/cuda_status.h"
#include "lw/kernels/cuda/marching_cubes_cuda.h"

#include <cstddef>
#include <glm/glm.hpp>
#include <memory>
#include <vector>

namespace lw::kernels::cuda {

class ContourTrianglesCuda {
public:
    ContourTrianglesCuda();
    ~ContourTrianglesCuda();
    ContourTrianglesCuda(const ContourTrianglesCuda&) = delete;
    ContourTrianglesCuda& operator=(const ContourTrianglesCuda&) = delete;

    // The triangles of `mesh` (device memory) that the contour seen from `viewer` may cross --
    // the eye (w = 1) or the unit vector toward the viewer (w = 0) -- appended to the host
    // arrays as unshared vertices (three a triangle, in the mesh's order). Blocks until they
    // are on the host.
    CudaStatus download(const DeviceMeshView& mesh, glm::vec4 viewer,
                        std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals);
    void release();

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace lw::kernels::cuda
