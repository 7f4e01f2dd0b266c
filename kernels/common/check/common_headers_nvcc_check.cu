// Compile check: the host+device headers of kernels/common must build with nvcc (C++17) as
// well as with the host compiler, since the CUDA back-end will share them with the CPU one. This
// translation unit instantiates the device side of each; it is built, never run.
#include "lw/kernels/host_device.h"
#include "lw/kernels/marching_cubes.h"
#include "lw/kernels/marching_cubes_tables.h"
#include "lw/kernels/silhouette_segment.h"
#include "lw/kernels/voxel_grid.h"

#include <cstdint>

namespace lw::kernels {

__global__ void commonHeadersDeviceCheck(float* out) {
    const glm::vec3 p[3] = {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f), glm::vec3(0.0f, 1.0f, 0.0f)};
    const float d[3] = {1.0f, -1.0f, 0.5f};
    SegmentEndpoints segment;
    if (silhouetteSegment(p, d, segment))
        out[0] = segment.a.x + segment.b.y;
    const float corners[8] = {0, 1, 0, 1, 0, 1, 0, 1};
    out[1] = float(mcCaseIndex(corners, 0.5f));
    out[2] = mcEdgeParameter(0.0, 1.0, 0.25);
}

} // namespace lw::kernels
